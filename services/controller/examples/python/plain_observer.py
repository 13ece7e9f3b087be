"""A listener on plain Cyclone DDS (no climbsim runtime): prints the downforce of a running run.

    ./deploy/climbsim ps                                    # the run's DDS domain, e.g. 10
    build/bin/climbsim-python services/controller/examples/python/plain_observer.py 10

It only reads (a BEST_EFFORT reader gates nothing), so it may come and go while the run goes
on. What it needs to meet climbsim's Fast DDS services, as `climbsim topics` and the table of
docs/controllers.md#topics-and-qos say: the topic name, the type (climbsim::AdhesionForce from
idl/, as the build generated it into climbsim_idl), XCDR1, and discovery by unicast on this
machine.
"""

import sys
import time

from cyclonedds.domain import Domain, DomainParticipant
from cyclonedds.internal import load_cyclonedds
from cyclonedds.qos import Policy, Qos
from cyclonedds.sub import DataReader
from cyclonedds.topic import Topic

import climbsim_idl as idl

domain_id = int(sys.argv[1]) if len(sys.argv) > 1 else 10
seconds = float(sys.argv[2]) if len(sys.argv) > 2 else 1e9

# Cyclone 11 warns "deserialization failed" for every liveliness message of Fast DDS 2.9
# (harmless): keep fatal errors and errors (1 | 2), drop warnings.
load_cyclonedds().dds_set_log_mask(1 | 2)

# Fast DDS announces itself by unicast too: find it at this machine's well-known ports.
config = f"""<CycloneDDS><Domain id="{domain_id}"><General><Interfaces><NetworkInterface name="lo"/></Interfaces>
  <AllowMulticast>false</AllowMulticast></General><Discovery><ParticipantIndex>auto</ParticipantIndex>
  <MaxAutoParticipantIndex>48</MaxAutoParticipantIndex><Peers><Peer address="127.0.0.1"/></Peers>
  </Discovery></Domain></CycloneDDS>"""
domain = Domain(domain_id, config)
participant = DomainParticipant(domain_id)
topic = Topic(participant, "thermo/AdhesionForce", idl.AdhesionForce)
reader = DataReader(participant, topic, qos=Qos(
    Policy.Reliability.BestEffort, Policy.History.KeepLast(1), Policy.Durability.Volatile,
    Policy.DataRepresentation(use_cdrv0_representation=True)))

end = time.monotonic() + seconds
last_print = 0.0
while time.monotonic() < end:
    for sample in reader.take(N=16):
        if time.monotonic() - last_print >= 0.5:
            print(f"t = {sample.t_ns * 1e-9:7.3f} s  F = {sample.downforce_n:7.1f} N", flush=True)
            last_print = time.monotonic()
    time.sleep(0.01)
