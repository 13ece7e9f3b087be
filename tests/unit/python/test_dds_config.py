"""The Cyclone DDS configuration of a climbsim participant: one host or across hosts."""

import unittest
import xml.etree.ElementTree as ET

from climbsim import dds


class CycloneConfig(unittest.TestCase):
    def test_one_host_binds_loopback_and_peers_on_localhost(self):
        root = ET.fromstring(dds.cyclone_config(42, environ={}))
        self.assertEqual(root.find("Domain").get("id"), "42")
        self.assertEqual(root.find(".//NetworkInterface").get("name"), "lo")
        self.assertEqual([p.get("address") for p in root.iter("Peer")], ["127.0.0.1"])
        self.assertEqual(root.find(".//AllowMulticast").text, "false")

    def test_across_hosts_binds_its_address_and_peers_every_host(self):
        env = {"CLIMBSIM_DDS_PEERS": "10.77.0.1,10.77.0.2", "CLIMBSIM_DDS_INTERFACE": "10.77.0.2"}
        root = ET.fromstring(dds.cyclone_config(7, environ=env))
        self.assertEqual(root.find(".//NetworkInterface").get("address"), "10.77.0.2")
        self.assertEqual([p.get("address") for p in root.iter("Peer")], ["10.77.0.1", "10.77.0.2"])

    def test_bad_environment_is_a_config_error_naming_the_variable(self):
        with self.assertRaisesRegex(dds.ConfigError, "CLIMBSIM_DDS_PEERS = '10.77.0.300'"):
            dds.cyclone_config(7, environ={"CLIMBSIM_DDS_PEERS": "10.77.0.300", "CLIMBSIM_DDS_INTERFACE": "10.77.0.1"})
        with self.assertRaisesRegex(dds.ConfigError, "CLIMBSIM_DDS_INTERFACE = '10.77.0.3': not one of"):
            dds.cyclone_config(7, environ={"CLIMBSIM_DDS_PEERS": "10.77.0.1", "CLIMBSIM_DDS_INTERFACE": "10.77.0.3"})
        with self.assertRaisesRegex(dds.ConfigError, "CLIMBSIM_DDS_INTERFACE"):
            dds.cyclone_config(7, environ={"CLIMBSIM_DDS_PEERS": "10.77.0.1"})


if __name__ == "__main__":
    unittest.main()
