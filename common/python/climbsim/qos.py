"""The QoS of climbsim's topics (docs/design.md#topics-and-qos) for Cyclone DDS, mirrored
from the one QoS file of the C++ services, deploy/qos/climbsim.xml (a test compares the two).

Every endpoint also forces XCDR1 (plain CDR): Fast DDS 2.9 reads and writes only XCDR1,
while Cyclone DDS may pick XCDR2, whose 8-byte members are aligned to 4 bytes.
"""

from __future__ import annotations

from dataclasses import dataclass

from cyclonedds.qos import Policy, Qos
from cyclonedds.util import duration


@dataclass(frozen=True)
class Profile:
    """One endpoint profile of deploy/qos/climbsim.xml."""

    depth: int  #: KEEP_LAST depth; -1 = KEEP_ALL
    reliable: bool  #: RELIABLE, else BEST_EFFORT
    transient_local: bool  #: TRANSIENT_LOCAL, else VOLATILE
    max_blocking_s: float | None = None  #: writer: reliability max_blocking_time [s]
    liveliness_lease_s: float | None = None  #: writer: AUTOMATIC liveliness lease [s]


#: Profile name (as in the XML file) -> settings.
PROFILES: dict[str, Profile] = {
    # Clock control plane: StepGrant, StepDone, ClockControl.
    "climbsim.control.writer": Profile(16, True, False, max_blocking_s=1.0, liveliness_lease_s=4.0),
    "climbsim.control.reader": Profile(16, True, False),
    # Latched control plane: ParticipantReady (keyed), RunStart, Stop.
    "climbsim.latched.writer": Profile(1, True, True, max_blocking_s=1.0, liveliness_lease_s=4.0),
    "climbsim.latched.reader": Profile(1, True, True),
    # Stamped step data read inside the lockstep.
    # W + 2 per producer: a producer runs up to W steps ahead (the clock's window_steps).
    "climbsim.step_data.writer": Profile(34, True, False, max_blocking_s=1.0),
    "climbsim.step_data.reader": Profile(34, True, False),
    # Record batches (record/RecordBatch): a producer's samples for the recorders; KEEP_ALL.
    "climbsim.record.writer": Profile(-1, True, False, max_blocking_s=1.0),
    "climbsim.record.reader": Profile(-1, True, False),
    # Observers of the record batches (the viewer): best effort, latest batch per producer.
    "climbsim.record_observer.writer": Profile(1, False, False),
    "climbsim.record_observer.reader": Profile(1, False, False),
    # Observer streams (SimTime, images for viewing).
    "climbsim.observer.writer": Profile(1, False, False),
    "climbsim.observer.reader": Profile(1, False, False),
    # Pictures a run keeps (sealing/SealingPicture): every one must arrive, late readers too.
    "climbsim.pictures.writer": Profile(64, True, True, max_blocking_s=1.0),
    "climbsim.pictures.reader": Profile(64, True, True),
}

CONTROL = "climbsim.control"  #: grant, done, clock control
LATCHED = "climbsim.latched"  #: ready, run start, stop
STEP_DATA = "climbsim.step_data"  #: stamped lockstep data
OBSERVER = "climbsim.observer"  #: SimTime, viewer images
PICTURES = "climbsim.pictures"  #: sealing pictures the recorder keeps
RECORD = "climbsim.record"  #: record batches (recorders)
RECORD_OBSERVER = "climbsim.record_observer"  #: record batches, best effort (viewers)

#: Participant lease [s] and announcement period [s] of the climbsim participant profile:
#: a killed process is noticed 4 s after its last announcement (docs/design.md#failures-and-stop).
PARTICIPANT_LEASE_S = 4.0
PARTICIPANT_ANNOUNCEMENT_S = 0.2


def _ns(seconds: float) -> int:
    return duration(seconds=seconds)


def qos_for(profile: str, role: str) -> Qos:
    """Cyclone DDS QoS of `profile` (CONTROL, LATCHED, STEP_DATA, OBSERVER, PICTURES, RECORD) for `role`
    "reader" or "writer"."""
    if role not in ("reader", "writer"):
        raise ValueError(f"role must be 'reader' or 'writer', not {role!r}")
    p = PROFILES[f"{profile}.{role}"]
    policies = [
        Policy.History.KeepAll if p.depth < 0 else Policy.History.KeepLast(p.depth),
        Policy.Durability.TransientLocal if p.transient_local else Policy.Durability.Volatile,
        Policy.DataRepresentation(use_cdrv0_representation=True),
    ]
    if p.reliable:
        policies.append(Policy.Reliability.Reliable(max_blocking_time=_ns(p.max_blocking_s or 0.1)))
    else:
        policies.append(Policy.Reliability.BestEffort)
    if p.liveliness_lease_s is not None:
        policies.append(Policy.Liveliness.Automatic(lease_duration=_ns(p.liveliness_lease_s)))
    return Qos(*policies)
