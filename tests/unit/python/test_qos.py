"""climbsim.qos mirrors deploy/qos/climbsim.xml, the QoS file of the C++ services."""

import os
import unittest
import xml.etree.ElementTree as ET
from pathlib import Path

from cyclonedds.qos import Policy

from climbsim import qos

ROOT = Path(os.environ.get("CLIMBSIM_ROOT", Path(__file__).resolve().parents[3]))
NS = {"f": "http://www.eprosima.com/XMLSchemas/fastRTPS_Profiles"}


def seconds(node) -> float:
    sec = node.find("f:sec", NS)
    nanosec = node.find("f:nanosec", NS)
    return (int(sec.text) if sec is not None else 0) + (int(nanosec.text) * 1e-9 if nanosec is not None else 0.0)


def xml_root():
    # Parsed strictly, comments included: the file must be well-formed XML for every client.
    return ET.fromstring((ROOT / "deploy/qos/climbsim.xml").read_bytes())


def xml_profiles() -> dict:
    root = xml_root()
    out = {}
    for tag in ("data_writer", "data_reader"):
        for node in root.iter(f"{{{NS['f']}}}{tag}"):
            history = node.find("f:topic/f:historyQos", NS)
            q = node.find("f:qos", NS)
            blocking = q.find("f:reliability/f:max_blocking_time", NS)
            lease = q.find("f:liveliness/f:lease_duration", NS)
            out[node.get("profile_name")] = qos.Profile(
                depth=int(history.find("f:depth", NS).text) if history.find("f:kind", NS).text == "KEEP_LAST" else -1,
                reliable=q.find("f:reliability/f:kind", NS).text == "RELIABLE",
                transient_local=q.find("f:durability/f:kind", NS).text == "TRANSIENT_LOCAL",
                max_blocking_s=seconds(blocking) if blocking is not None else None,
                liveliness_lease_s=seconds(lease) if lease is not None else None)
    return out


class QosMirror(unittest.TestCase):
    def test_every_profile_of_the_xml_file_is_mirrored_exactly(self):
        self.assertEqual(qos.PROFILES, xml_profiles())

    def test_participant_lease_matches(self):
        root = xml_root()
        disc = root.find(".//f:participant//f:discovery_config", NS)
        self.assertAlmostEqual(seconds(disc.find("f:leaseDuration", NS)), qos.PARTICIPANT_LEASE_S)
        self.assertAlmostEqual(seconds(disc.find("f:leaseAnnouncement", NS)), qos.PARTICIPANT_ANNOUNCEMENT_S)

    def test_cyclone_qos_forces_xcdr1_and_the_profile_settings(self):
        w = qos.qos_for(qos.LATCHED, "writer")
        self.assertEqual(w[Policy.DataRepresentation], Policy.DataRepresentation(use_cdrv0_representation=True))
        self.assertEqual(w[Policy.Durability], Policy.Durability.TransientLocal)
        self.assertEqual(w[Policy.History], Policy.History.KeepLast(1))
        r = qos.qos_for(qos.OBSERVER, "reader")
        self.assertEqual(r[Policy.Reliability], Policy.Reliability.BestEffort)
        with self.assertRaises(ValueError):
            qos.qos_for(qos.CONTROL, "listener")


if __name__ == "__main__":
    unittest.main()
