"""One Cyclone DDS participant configured to meet climbsim's Fast DDS services, and typed
readers and writers with climbsim's QoS whose listeners wake a Notifier.

Discovery: the Fast DDS services talk shared memory among themselves but also have a
UDPv4 transport (deploy/qos/climbsim.xml); Cyclone DDS speaks UDP only. The participant
is bound to the loopback interface and finds the others by unicast SPDP to 127.0.0.1 (the
well-known ports of participant indices 0..MAX_PARTICIPANT_INDEX of the domain), so that
nothing leaves the machine and no multicast route is needed.
"""

from __future__ import annotations

import os
import threading
from collections import deque
import time
from typing import Callable, Generic, TypeVar

from cyclonedds.core import Listener
from cyclonedds.domain import Domain, DomainParticipant
from cyclonedds.pub import DataWriter
from cyclonedds.sub import DataReader
from cyclonedds.topic import Topic

from . import qos as _qos

#: Largest domain id Fast DDS accepts with its default port mapping (7400 + 250 * domain).
MAX_DOMAIN_ID = 232
#: Highest participant index probed by unicast discovery on one domain of this machine.
MAX_PARTICIPANT_INDEX = 48

T = TypeVar("T")


class ConfigError(Exception):
    """A bad option or environment value; the message names it. Exit code 2."""


def parse_domain_id(source: str, text: str) -> int:
    """The domain id given as `text` by `source` (an option or variable name), 0..232."""
    try:
        value = int(text, 10)
    except ValueError:
        raise ConfigError(f"{source} = '{text}' is not an integer domain id") from None
    if not 0 <= value <= MAX_DOMAIN_ID:
        raise ConfigError(f"{source} = {text} is out of range; a domain id is 0..{MAX_DOMAIN_ID}")
    return value


def resolve_domain(domain: str | int | None) -> int:
    """--domain if given, else $CLIMBSIM_DOMAIN (like the C++ DdsSettings)."""
    if domain is not None and domain != "":
        return parse_domain_id("--domain", str(domain))
    env = os.environ.get("CLIMBSIM_DOMAIN", "")
    if not env:
        raise ConfigError(f"no DDS domain id: give --domain or set CLIMBSIM_DOMAIN (0..{MAX_DOMAIN_ID})")
    return parse_domain_id("CLIMBSIM_DOMAIN", env)


def _ipv4(source: str, text: str) -> str:
    parts = text.split(".")
    if len(parts) != 4 or not all(p.isdigit() and 0 <= int(p) <= 255 for p in parts):
        raise ConfigError(f"environment {source} = '{text}': '{text}' is not an IPv4 address")
    return text


def unicast_discovery(environ=os.environ) -> tuple[str, list[str]] | None:
    """(interface address, peer addresses) from CLIMBSIM_DDS_INTERFACE and CLIMBSIM_DDS_PEERS,
    or None when the run is on one host (CLIMBSIM_DDS_PEERS unset)."""
    peers_text = environ.get("CLIMBSIM_DDS_PEERS", "")
    if not peers_text:
        return None
    peers = [_ipv4("CLIMBSIM_DDS_PEERS", p) for p in peers_text.split(",")]
    interface = _ipv4("CLIMBSIM_DDS_INTERFACE", environ.get("CLIMBSIM_DDS_INTERFACE", ""))
    if interface not in peers:
        raise ConfigError(f"environment CLIMBSIM_DDS_INTERFACE = '{interface}': not one of CLIMBSIM_DDS_PEERS")
    return interface, peers


def cyclone_config(domain_id: int, environ=os.environ) -> str:
    """The Cyclone DDS configuration of a climbsim participant (see the module comment);
    lease and announcement period as the climbsim participant profile."""
    lease_ms = int(_qos.PARTICIPANT_LEASE_S * 1000)
    spdp_ms = int(_qos.PARTICIPANT_ANNOUNCEMENT_S * 1000)
    across_hosts = unicast_discovery(environ)
    if across_hosts is None:
        interface = '<NetworkInterface name="lo"/>'
        peers = '<Peer address="127.0.0.1"/>'
    else:
        interface = f'<NetworkInterface address="{across_hosts[0]}"/>'
        peers = "".join(f'<Peer address="{p}"/>' for p in across_hosts[1])
    return f"""<CycloneDDS><Domain id="{domain_id}">
  <General>
    <Interfaces>{interface}</Interfaces>
    <AllowMulticast>false</AllowMulticast>
  </General>
  <Discovery>
    <ParticipantIndex>auto</ParticipantIndex>
    <MaxAutoParticipantIndex>{MAX_PARTICIPANT_INDEX}</MaxAutoParticipantIndex>
    <Peers>{peers}</Peers>
    <LeaseDuration>{lease_ms}ms</LeaseDuration>
    <SPDPInterval>{spdp_ms}ms</SPDPInterval>
  </Discovery>
</Domain></CycloneDDS>"""


class Notifier:
    """A generation counter that DDS listener threads bump and the owner waits on."""

    def __init__(self) -> None:
        self._cond = threading.Condition()
        self._generation = 0

    def generation(self) -> int:
        with self._cond:
            return self._generation

    def notify(self, *_args) -> None:
        with self._cond:
            self._generation += 1
            self._cond.notify_all()

    def wait_changed(self, seen: int, timeout_s: float) -> None:
        """Returns when the generation differs from `seen`, or after `timeout_s`."""
        deadline = time.monotonic() + timeout_s
        with self._cond:
            while self._generation == seen:
                left = deadline - time.monotonic()
                if left <= 0:
                    return
                self._cond.wait(left)


#: Cyclone DDS log categories (ddsrt/log.h).
_LOG_FATAL, _LOG_ERROR, _LOG_WARNING = 1, 2, 4
_log_mask_set = False


def _quiet_cyclone_warnings() -> None:
    """Cyclone DDS 11 warns "data(builtin, vendor 1.15) ...: deserialization failed" for every
    liveliness message of every Fast DDS 2.9 participant (5 a second each; harmless, a known
    interop quirk: matching, data and liveliness by lease all work). Its warnings go to stderr
    unless CLIMBSIM_CYCLONE_WARNINGS=1; fatal errors and errors always do."""
    global _log_mask_set
    if _log_mask_set or os.environ.get("CLIMBSIM_CYCLONE_WARNINGS", "") == "1":
        return
    from cyclonedds.internal import load_cyclonedds

    load_cyclonedds().dds_set_log_mask(_LOG_FATAL | _LOG_ERROR)
    _log_mask_set = True


_domains: dict[int, tuple[Domain, str]] = {}
_domains_lock = threading.Lock()


def _domain(domain_id: int, config: str) -> Domain:
    """The process's Domain object of `domain_id` (Cyclone allows one per id and process); it
    holds the configuration and must outlive the participants."""
    with _domains_lock:
        _quiet_cyclone_warnings()
        found = _domains.get(domain_id)
        if found is None:
            found = (Domain(domain_id, config), config)
            _domains[domain_id] = found
        elif found[1] != config:
            raise ConfigError(f"domain {domain_id} is already configured otherwise in this process")
        return found[0]


class DdsContext:
    """The DomainParticipant of one process and its topics."""

    def __init__(self, domain_id: int, config: str | None = None) -> None:
        self.domain_id = domain_id
        self.notifier = Notifier()
        self._domain = _domain(domain_id, config if config is not None else cyclone_config(domain_id))
        self.participant = DomainParticipant(domain_id)
        #: This process's identity on the domain: the GUID prefix of its DDS participant.
        self.id: bytes = self.participant.guid.bytes[:12]
        self._topics: dict[str, Topic] = {}

    def topic(self, name: str, data_type: type) -> Topic:
        """The topic `name` of `data_type` (created once)."""
        found = self._topics.get(name)
        if found is None:
            found = Topic(self.participant, name, data_type)
            self._topics[name] = found
        return found

    def reader(self, name: str, data_type: type, profile: str) -> "Reader":
        return Reader(self, name, data_type, profile)

    def writer(self, name: str, data_type: type, profile: str) -> "Writer":
        return Writer(self, name, data_type, profile)


class Reader(Generic[T]):
    """A DataReader with a climbsim QoS profile; data, matching and liveliness changes wake
    the context's Notifier.

    Samples are taken out of the DDS reader as they arrive (in its listener) into a queue of
    their own per writer, at most the profile's history depth each: in the reader's shared
    KEEP_LAST history, a writer that floods a key (an outsider forging samples with a
    producer's `source`) would push the real writer's samples out before they are read
    (the C++ Reader does the same)."""

    def __init__(self, dds: DdsContext, name: str, data_type: type, profile: str) -> None:
        self.topic_name = name
        self._lost = 0
        self._senders: dict[int, bytes] = {}  # publication handle -> GUID prefix of its participant
        self._lost_handles: list[int] = []
        self._lock = threading.Lock()
        depth = _qos.PROFILES[f"{profile}.reader"].depth
        self._per_writer_depth = depth if depth > 0 else None  # KEEP_ALL: unbounded, as DDS
        self._queues: dict[int, deque] = {}  # publication handle -> (arrival number, sample)
        self._arrivals = 0
        notifier = dds.notifier

        def on_matched(_reader, status) -> None:
            if status.current_count_change < 0:
                with self._lock:
                    self._lost += 1
                    self._lost_handles.append(status.last_publication_handle)
            notifier.notify()

        def on_liveliness(_reader, status) -> None:
            if status.not_alive_count_change > 0:
                with self._lock:
                    self._lost += 1
                    self._lost_handles.append(status.last_publication_handle)
            notifier.notify()

        def on_data(reader) -> None:
            self._take_from_dds(reader)
            notifier.notify()

        listener = Listener(on_data_available=on_data,
                            on_subscription_matched=on_matched,
                            on_liveliness_changed=on_liveliness)
        self._reader = DataReader(dds.participant, dds.topic(name, data_type), qos=_qos.qos_for(profile, "reader"),
                                  listener=listener)
        self._take_from_dds(self._reader)  # anything that arrived before the listener was set

    def _take_from_dds(self, reader) -> None:
        # Taken and queued under one lock: the listener's thread and take() both take, and a
        # batch taken by one must not be queued after a later batch taken by the other.
        with self._lock:
            while True:
                batch = reader.take(N=64)
                if not batch:
                    return
                for sample in batch:
                    # Invalid samples (disposals, unregistrations) come as cyclonedds.core.InvalidSample.
                    if not hasattr(sample, "__idl__"):
                        continue
                    info = getattr(sample, "sample_info", None)
                    handle = info.publication_handle if info is not None else 0
                    queue = self._queues.get(handle)
                    if queue is None:
                        queue = self._queues[handle] = deque(maxlen=self._per_writer_depth)
                    queue.append((self._arrivals, sample))
                    self._arrivals += 1

    def take(self) -> list[T]:
        """Every valid sample received since the last call (at most the history depth per
        writer), oldest first."""
        self._take_from_dds(self._reader)
        with self._lock:
            queues, self._queues = self._queues, {}
        entries = [entry for queue in queues.values() for entry in queue]
        entries.sort(key=lambda entry: entry[0])
        return [sample for _, sample in entries]

    def sender(self, sample) -> bytes | None:
        """The 12-byte RTPS GUID prefix of the DDS participant whose writer sent `sample`
        (who a sample comes from), or None if the writer is no longer matched."""
        info = getattr(sample, "sample_info", None)
        if info is None:
            return None
        handle = info.publication_handle
        prefix = self._senders.get(handle)
        if prefix is None:
            data = self._reader.get_matched_publication_data(handle)
            if data is None:
                return None
            prefix = data.participant_key.bytes[:12]
            if len(self._senders) < 4096:
                self._senders[handle] = prefix
        return prefix

    def take_lost_senders(self) -> list[bytes | None]:
        """The DDS participants (GUID prefixes, None if never heard from) of the writers lost
        since the last call."""
        with self._lock:
            handles, self._lost_handles = self._lost_handles, []
        return [self._senders.get(h) for h in handles]

    def take_lost(self) -> int:
        """How many writers were unmatched or lost their liveliness since the last call."""
        with self._lock:
            lost, self._lost = self._lost, 0
        return lost

    def matched_writers(self) -> int:
        return self._reader.get_subscription_matched_status().current_count

    def matched_participants(self) -> set[bytes]:
        """The DDS participants (12-byte GUID prefixes) of the writers matched now. Who to
        wait for before a run starts: a count would let any writer of the topic (an
        outsider's) stand in for a producer whose writer has not matched yet, and a sample
        written before the match is lost to this VOLATILE reader."""
        return _participants(self._reader.get_matched_publications, self._reader.get_matched_publication_data)


class Writer(Generic[T]):
    """A DataWriter with a climbsim QoS profile; matching wakes the Notifier."""

    def __init__(self, dds: DdsContext, name: str, data_type: type, profile: str) -> None:
        self.topic_name = name
        notifier = dds.notifier
        listener = Listener(on_publication_matched=lambda _w, _s: notifier.notify())
        self._writer = DataWriter(dds.participant, dds.topic(name, data_type), qos=_qos.qos_for(profile, "writer"),
                                  listener=listener)

    def write(self, sample: T) -> None:
        self._writer.write(sample)

    def matched_readers(self) -> int:
        return self._writer.get_publication_matched_status().current_count

    def matched_participants(self) -> set[bytes]:
        """The DDS participants (12-byte GUID prefixes) of the readers matched now (see
        Reader.matched_participants)."""
        return _participants(self._writer.get_matched_subscriptions, self._writer.get_matched_subscription_data)


def _participants(matched_handles, endpoint_data) -> set[bytes]:
    # cyclonedds-python sizes the handle array by a first call and fills it by a second: an
    # endpoint matched in between raises IndexError. The caller waits on the notifier and asks
    # again, so a try that raced counts as nothing matched yet.
    try:
        handles = matched_handles()
    except IndexError:
        return set()
    out = set()
    for handle in handles:
        data = endpoint_data(handle)
        if data is not None:  # unmatched meanwhile
            out.add(data.participant_key.bytes[:12])
    return out


def wait_for(condition: Callable[[], bool], notifier: Notifier, timeout_s: float, what: str) -> None:
    """Waits until `condition()` holds, re-checking on every notification (and every 0.2 s);
    raises TimeoutError naming `what`."""
    deadline = time.monotonic() + timeout_s
    while True:
        seen = notifier.generation()
        if condition():
            return
        if time.monotonic() >= deadline:
            raise TimeoutError(f"timed out after {timeout_s:g} s waiting for {what}")
        notifier.wait_changed(seen, min(0.2, max(0.0, deadline - time.monotonic())))
