"""The participant side of climbsim's lockstep clock
(docs/design.md#the-shared-simulation-clock, idl/clock.idl) on Cyclone DDS, the same protocol
as the C++ LockstepParticipant (common/src/lockstep_participant.cpp):

1. wait until the clock's StepGrant writer and StepDone reader have matched;
2. announce ParticipantReady (TRANSIENT_LOCAL, keyed by name): the roster entry (period,
   offset, input and output topics) and the SHA-256 of every IDL file;
3. wait for RunStart, check the name is on its roster, wait until every data topic has
   matched an endpoint of each of its producers and consumers on the roster (by the DDS
   participant RunStart binds each to), send StepDone ARMED;
4. the horizon protocol: StepGrant carries a horizon H; compute every due step k < H
   (k >= offset and (k - offset) % period == 0) in order, each once its stamped inputs are
   there; write the outputs stamped with k; acknowledge progress (StepDone STEP_DONE with
   progress_step = the next due step) every W/2 steps and on reaching H, W = RunStart's
   window_steps;
5. end at the clock's Stop (exit 0 if completed or requested, 1 if failed); a step that
   raises sends StepDone FAILED with the message.

An Observer only listens: it is on no roster and never gates a step.
"""

from __future__ import annotations

import argparse
import logging
import os
import socket
import time
from collections import deque
from dataclasses import dataclass
from typing import Callable, Generic, TypeVar

import climbsim_idl as idl

from . import qos, topics
from .dds import ConfigError, DdsContext, resolve_domain, wait_for

EXIT_OK = 0  #: run completed or stopped on request
EXIT_FAILED = 1  #: the run failed (the clock's Stop says why)
EXIT_CONFIG = 2  #: bad options, files or roster

MAX_NAME_LENGTH = 64
#: After a failure, how long to wait for the clock's Stop so that the failure, not the
#: disappearance, is what the clock reports [s].
FAILURE_LINGER_S = 2.0

log = logging.getLogger("climbsim")

S = TypeVar("S")


@dataclass(frozen=True)
class Schedule:
    """Due every `period_steps` clock steps from `offset_steps` on."""

    period_steps: int = 1
    offset_steps: int = 0

    def validate(self, what: str) -> None:
        if self.period_steps < 1:
            raise ConfigError(f"{what}: period_steps = {self.period_steps}; it must be >= 1")
        if not 0 <= self.offset_steps < self.period_steps:
            raise ConfigError(f"{what}: offset_steps = {self.offset_steps}; it must be < period_steps = "
                              f"{self.period_steps}")

    def is_due(self, step: int) -> bool:
        return step >= self.offset_steps and (step - self.offset_steps) % self.period_steps == 0

    def last_due_before(self, step: int) -> int | None:
        """The last step < `step` at which this schedule is due, if any."""
        if step <= self.offset_steps:
            return None
        return self.offset_steps + ((step - 1 - self.offset_steps) // self.period_steps) * self.period_steps


@dataclass(frozen=True)
class StepContext:
    """One granted step: t_ns = step * dt_ns."""

    step: int
    t_ns: int  #: simulation time at the start of the step [ns]
    dt_ns: int  #: length of one clock step [ns]


class RunEnded(Exception):
    """Raised from waits inside a step when the run ends; run() returns its exit code."""

    def __init__(self, exit_code: int) -> None:
        super().__init__(exit_code)
        self.exit_code = exit_code


def validate_name(what: str, name: str) -> None:
    """As climbsim::validateName: 1..64 characters of letters, digits, '_', '-', '.'."""
    if not name:
        raise ConfigError(f"{what}: empty name")
    if len(name) > MAX_NAME_LENGTH:
        raise ConfigError(f"{what}: name '{name}' is longer than {MAX_NAME_LENGTH} characters")
    for c in name:
        if not (c.isascii() and c.isalnum()) and c not in "_-.":
            raise ConfigError(f"{what}: name '{name}' has the character '{c}'; use letters, digits, '_', '-' and '.'")


def add_participant_options(parser: argparse.ArgumentParser) -> None:
    """--name, --period, --offset, --start-timeout-s, --domain, as the C++ services take them
    (the launcher appends --name, --period, --offset and --domain)."""
    parser.add_argument("--name", required=True, help="participant name on the clock's roster")
    parser.add_argument("--period", type=int, default=1, help="due every PERIOD clock steps (>= 1)")
    parser.add_argument("--offset", type=int, default=0, help="first due step (< period)")
    parser.add_argument("--start-timeout-s", type=float, default=60.0,
                        help="give up if the run has not started after this long")
    parser.add_argument("--domain", default=None, help="DDS domain id, 0..232 (default: $CLIMBSIM_DOMAIN)")
    parser.add_argument("--qos", default=None,
                        help="ignored: the C++ services' QoS file; this client mirrors it (climbsim.qos)")


class StampedInput(Generic[S]):
    """A topic read inside the lockstep; samples have `source`, `step` and `t_ns`."""

    def __init__(self, owner: "LockstepParticipant", topic: str, data_type: type, same_step: bool = False) -> None:
        self._owner = owner
        self.topic = topic
        #: True: read the producer's last due step <= k (lag 0) instead of < k.
        self.same_step = same_step
        self._reader = owner.dds.reader(topic, data_type, qos.STEP_DATA)
        self._by_source: dict[str, deque] = {}

    def matched_writers(self) -> int:
        return self._reader.matched_writers()

    def matched_participants(self) -> set[bytes]:
        return self._reader.matched_participants()

    def drain(self) -> None:
        identities = self._owner.producer_identities(self.topic)
        if identities is None:
            return  # before the run start nobody's identity is known: the samples wait in the reader
        for sample in self._reader.take():
            sender = self._reader.sender(sample)
            if identities.get(sample.source) != sender or sender is None:
                self._owner.dropped.drop(self.topic, sender, f"claims to be '{sample.source}', not a producer of the "
                                                             "topic on the roster")
                continue
            queue = self._by_source.setdefault(sample.source, deque())
            queue.append(sample)
            while len(queue) > 4096:  # a producer is at most a window ahead; far more is a fault
                queue.popleft()

    def get(self, ctx: StepContext) -> list[S]:
        """The sample each producer on the roster wrote at its last due step before ctx.step
        (zero-order hold), waiting for each; ordered by producer name."""
        out: list[S] = []
        for producer, schedule in self._owner.producers_of(self.topic):
            stamp = schedule.last_due_before(ctx.step + 1 if self.same_step else ctx.step)
            if stamp is None:
                continue
            while True:
                seen = self._owner.dds.notifier.generation()
                self.drain()
                queue = self._by_source.setdefault(producer, deque())
                while queue and queue[0].step < stamp:
                    queue.popleft()
                if queue and queue[0].step == stamp:
                    out.append(queue[0])
                    break
                if queue:
                    raise RuntimeError(f"topic '{self.topic}': needed the sample of '{producer}' stamped {stamp} "
                                       f"but the next one is stamped {queue[0].step}")
                self._owner.wait_for_news(seen)
        return out


class StampedOutput(Generic[S]):
    """A topic written inside the lockstep, stamped with the step being computed."""

    def __init__(self, owner: "LockstepParticipant", topic: str, data_type: type) -> None:
        self._owner = owner
        self.topic = topic
        self._writer = owner.dds.writer(topic, data_type, qos.STEP_DATA)

    def matched_readers(self) -> int:
        return self._writer.matched_readers()

    def matched_participants(self) -> set[bytes]:
        return self._writer.matched_participants()

    def write(self, ctx: StepContext, sample: S) -> None:
        """Sets sample.source, .step and .t_ns from ctx and writes it."""
        if self._owner.current_step != ctx.step:
            raise RuntimeError(f"topic '{self.topic}': written outside its step {ctx.step}")
        sample.source = self._owner.name
        sample.step = ctx.step
        sample.t_ns = ctx.t_ns
        self._writer.write(sample)


#: The run id the launcher gives every process of a run (C++: climbsim/run_id_env.hpp).
ENV_RUN_ID = "CLIMBSIM_RUN_ID"


def _expected_run_id() -> int | None:
    value = os.environ.get(ENV_RUN_ID, "")
    if not value:
        return None
    if not value.isdigit():
        raise ConfigError(f"{ENV_RUN_ID} = '{value}': not a run id (an unsigned 64-bit number)")
    return int(value)


class _SenderLog:
    """Samples dropped because their sender is not who it must be: counted, logged once per writer."""

    def __init__(self, who: str) -> None:
        self.who = who
        self.dropped = 0
        self._logged: set[bytes | None] = set()

    def drop(self, topic: str, sender: bytes | None, why: str) -> None:
        self.dropped += 1
        if sender not in self._logged and len(self._logged) < 1024:
            self._logged.add(sender)
            log.warning("%s: dropped a sample of '%s' from DDS participant %s: %s (counted, logged once per "
                        "sender)", self.who, topic, sender.hex() if sender else "?", why)


class _ClockBinding:
    """Which clock this process believes: the DDS participant that sent the first
    RunStart of this run (of the launcher's CLIMBSIM_RUN_ID, if given) that binds `name`, if
    on its roster, to this process's own DDS participant. RunStart, Stop and StepGrant are
    taken only from it. A Stop that comes before any RunStart, even of the launcher's run id,
    waits: that id is no secret once the clock has published RunStart (an outsider reads it
    there and may forge a Stop that reaches us before our copy of the RunStart). It is judged
    once the RunStart binds the clock, or taken if the clock leaves without one
    (take_stop_of_unstarted_run)."""

    def __init__(self, dds: DdsContext, name: str, log_: _SenderLog) -> None:
        self._dds = dds
        self._name = name
        self._log = log_
        self._expected = _expected_run_id()
        self._run_starts = dds.reader(topics.RUN_START, idl.RunStart, qos.LATCHED)
        self._stops = dds.reader(topics.STOP, idl.Stop, qos.LATCHED)
        self._early_stops: list = []
        self.run_start: idl.RunStart | None = None
        self.stop: idl.Stop | None = None
        self.clock: bytes | None = None
        self.identities: dict[str, bytes] = {}  #: roster participant -> GUID prefix

    def is_clock(self, reader, sample) -> bool:
        """True if `sample` (with a run_id) is of this run and from its clock."""
        return (self.run_start is not None and sample.run_id == self.run_start.run_id
                and reader.sender(sample) == self.clock)

    def _take_run_start(self, r) -> None:
        sender = self._run_starts.sender(r)
        if self.run_start is not None:
            if not self.is_clock(self._run_starts, r):
                self._log.drop(topics.RUN_START, sender, f"run {r.run_id}, after this run's clock started it")
            return
        if self._expected is not None and r.run_id != self._expected:
            self._log.drop(topics.RUN_START, sender, f"run id {r.run_id} is not this run's ({ENV_RUN_ID})")
            return
        ids: dict[str, bytes] = {}
        for i in getattr(r, "identities", []):
            try:
                ids[i.participant] = bytes.fromhex(i.guid_prefix)
            except ValueError:
                pass
        for e in r.roster:
            if e.participant not in ids or (e.participant == self._name and ids[e.participant] != self._dds.id):
                self._log.drop(topics.RUN_START, sender,
                               f"run {r.run_id} does not bind '{e.participant}' to the DDS participant that is it")
                return
        self.run_start, self.clock, self.identities = r, sender, ids

    def _take_stop(self, s) -> None:
        if self.stop is not None:
            return
        if self.run_start is not None:
            if self.is_clock(self._stops, s):
                self.stop = s
            else:
                self._log.drop(topics.STOP, self._stops.sender(s), f"run {s.run_id}, not from this run's clock")
        elif len(self._early_stops) < 64:
            self._early_stops.append((s, self._stops.sender(s)))

    def take_stop_of_unstarted_run(self) -> None:
        """The clock left without a RunStart: it never made the run id public, so the first
        early Stop of the launcher's run id is its (e.g. a bad roster)."""
        if self.stop is not None or self.run_start is not None or self._expected is None:
            return
        self.stop = next((s for s, _ in self._early_stops if s.run_id == self._expected), None)

    def poll(self) -> None:
        """Takes what the latched RunStart and Stop readers hold."""
        for r in self._run_starts.take():
            self._take_run_start(r)
        if self.run_start is not None and self._early_stops:
            for s, sender in self._early_stops:
                if s.run_id == self.run_start.run_id and sender == self.clock:
                    self.stop = self.stop or s
                else:
                    self._log.drop(topics.STOP, sender, f"run {s.run_id}, not from this run's clock")
            self._early_stops = []
        for s in self._stops.take():
            self._take_stop(s)


class LockstepParticipant:
    """A process on the clock's roster. Declare inputs and outputs, then run()."""

    def __init__(self, name: str, domain: int | str | None = None, schedule: Schedule = Schedule(),
                 start_timeout_s: float = 60.0, dds: DdsContext | None = None) -> None:
        validate_name("--name", name)
        schedule.validate(f"participant '{name}'")
        if not start_timeout_s > 0:
            raise ConfigError(f"--start-timeout-s = {start_timeout_s}; it must be > 0")
        self.name = name
        self.schedule = schedule
        self.start_timeout_s = start_timeout_s
        self.dds = dds if dds is not None else DdsContext(resolve_domain(domain))
        self._grants = self.dds.reader(topics.STEP_GRANT, idl.StepGrant, qos.CONTROL)
        self.dropped = _SenderLog(name)
        self._binding = _ClockBinding(self.dds, name, self.dropped)
        self._done = self.dds.writer(topics.STEP_DONE, idl.StepDone, qos.CONTROL)
        self._ready = self.dds.writer(topics.PARTICIPANT_READY, idl.ParticipantReady, qos.LATCHED)
        self._inputs: list[StampedInput] = []
        self._outputs: list[StampedOutput] = []
        self.run_start: idl.RunStart | None = None
        self.stop: idl.Stop | None = None
        self._producer_ids: dict[str, dict[str, bytes]] = {}
        self._clock_seen = False
        self._clock_lost = False
        self.horizon = 0  #: every due step below it may be computed
        self.progress = 0  #: every due step below it is done
        self._acked = 0
        self.current_step: int | None = None

    @classmethod
    def from_args(cls, args: argparse.Namespace) -> "LockstepParticipant":
        """From the options of add_participant_options()."""
        return cls(args.name, args.domain, Schedule(args.period, args.offset), args.start_timeout_s)

    def input(self, topic: str, data_type: type, same_step: bool = False) -> StampedInput:
        """Declares a stamped input (before run()): the participant waits for it every step.
        `same_step`: read the producer's sample of the same step (lag 0; the clock refuses
        cycles of such inputs)."""
        port = StampedInput(self, topic, data_type, same_step)
        self._inputs.append(port)
        return port

    def output(self, topic: str, data_type: type) -> StampedOutput:
        """Declares a stamped output (before run())."""
        port = StampedOutput(self, topic, data_type)
        self._outputs.append(port)
        return port

    # ------------------------------------------------------------------ control plane

    def _poll_control(self) -> None:
        self._binding.poll()
        self.run_start, self.stop = self._binding.run_start, self._binding.stop
        for g in self._grants.take():
            if self._binding.is_clock(self._grants, g):
                self.horizon = max(self.horizon, g.horizon_step)
            elif self.run_start is not None:
                self.dropped.drop(topics.STEP_GRANT, self._grants.sender(g), f"run {g.run_id}, not this run's clock")
        if not self._clock_seen and self._grants.matched_writers() > 0:
            self._clock_seen = True
        for sender in self._grants.take_lost_senders():
            # Only this run's clock leaving counts (an outsider's grant writer may come and go);
            # before the run start, when no grant writer is left.
            clock = self._binding.clock
            if self._clock_seen and (sender == clock if clock is not None else self._grants.matched_writers() == 0):
                self._clock_lost = True
        if self._clock_lost and self.run_start is None:
            self._binding.take_stop_of_unstarted_run()
            self.stop = self._binding.stop
        for port in self._inputs:
            port.drain()

    def _exit_code_for_stop(self, stop: idl.Stop) -> int:
        if stop.kind == idl.StopKind.STOP_COMPLETED:
            log.info("run completed at step %d", stop.last_step)
            return EXIT_OK
        if stop.kind == idl.StopKind.STOP_REQUESTED:
            log.info("run stopped on request after step %d: %s", stop.last_step, stop.reason)
            return EXIT_OK
        if stop.kind == idl.StopKind.STOP_FELL:
            log.warning("run ended after step %d: %s", stop.last_step, stop.reason)
            return EXIT_OK
        log.error("run failed%s: %s", f" because of '{stop.culprit}'" if stop.culprit else "", stop.reason)
        return EXIT_FAILED

    def wait_for_news(self, seen_generation: int) -> None:
        """Waits for news from DDS (at most 0.2 s), watching the control plane; raises RunEnded."""
        self._poll_control()
        if self.stop is not None:
            raise RunEnded(self._exit_code_for_stop(self.stop))
        if self._clock_lost:
            log.error("the clock vanished (its liveliness was lost) without stopping the run")
            raise RunEnded(EXIT_FAILED)
        self.dds.notifier.wait_changed(seen_generation, 0.2)

    def _wait_until(self, condition: Callable[[], bool], deadline: float, what: str) -> None:
        while True:
            seen = self.dds.notifier.generation()
            self._poll_control()
            if condition():
                return
            if time.monotonic() >= deadline:
                raise TimeoutError(f"timed out after {self.start_timeout_s:g} s waiting for {what}")
            self.wait_for_news(seen)

    def producer_identities(self, topic: str) -> dict[str, bytes] | None:
        """Producers of `topic` on the roster -> the GUID prefix of their DDS participants (None
        before the run start)."""
        if self.run_start is None:
            return None
        found = self._producer_ids.get(topic)
        if found is None:
            found = {e.participant: self._binding.identities[e.participant]
                     for e in self.run_start.roster if topic in e.output_topics}
            self._producer_ids[topic] = found
        return found

    def producers_of(self, topic: str) -> list[tuple[str, Schedule]]:
        """Producers (name, schedule) of `topic` on this run's roster, sorted by name."""
        if self.run_start is None:
            return []
        found = [(e.participant, Schedule(e.period_steps, e.offset_steps))
                 for e in self.run_start.roster if topic in e.output_topics]
        return sorted(found, key=lambda p: p[0])

    def _consumers_of(self, topic: str) -> list[str]:
        # Readers of every producer of the topic, and those reading it from this participant
        # (input_sources "topic=name"; see idl/clock.idl).
        prefix = topic + "="
        names = []
        for e in self.run_start.roster:
            if topic not in e.input_topics:
                continue
            selected = [s[len(prefix):] for s in e.input_sources if s.startswith(prefix)]
            if not selected or self.name in selected:
                names.append(e.participant)
        return names

    def _announce_ready(self) -> None:
        entry = idl.RosterEntry(participant=self.name, period_steps=self.schedule.period_steps,
                                offset_steps=self.schedule.offset_steps,
                                input_topics=[p.topic for p in self._inputs],
                                output_topics=[p.topic for p in self._outputs],
                                same_step_inputs=[p.topic for p in self._inputs if p.same_step],
                                recorded_topics=[], input_sources=[])
        self._ready.write(idl.ParticipantReady(
            participant=self.name, entry=entry,
            idl_hashes=[idl.IdlHash(file=f, sha256=h) for f, h in idl.IDL_HASHES],
            host=socket.gethostname()[:MAX_NAME_LENGTH], pid=os.getpid()))

    def _arm_data_endpoints(self, deadline: float) -> None:
        if not any(e.participant == self.name for e in self.run_start.roster):
            raise RuntimeError(f"the run started without '{self.name}' on its roster")
        recorded = {t for e in self.run_start.roster for t in e.recorded_topics}
        for port in self._outputs:
            if port.topic in recorded:
                raise ConfigError(f"a recorder reads topic '{port.topic}' through record batches, which the Python "
                                  "client does not write; record another topic or use a C++ producer")

        # Matched by identity, not counted: a writer or reader of the topic that is not on the
        # roster (an outsider's, a plain DDS observer's) must not stand in for a roster member
        # whose endpoint has not matched yet, or that member misses the first samples
        # (VOLATILE) and the run waits for them until the watchdog.
        identities = self._binding.identities
        waits = ([(p, {identities.get(name) for name, _ in self.producers_of(p.topic)}) for p in self._inputs]
                 + [(p, {identities.get(name) for name in self._consumers_of(p.topic)}) for p in self._outputs])

        # The clock, too: its StepDone reader must have matched before ARMED is written.
        waits += [(self._grants, {self._binding.clock}), (self._done, {self._binding.clock})]

        def matched() -> bool:
            return all(wanted <= port.matched_participants() for port, wanted in waits)

        self._wait_until(matched, deadline, "the data topics to match their producers and consumers")

    def _send_done(self, step: int, kind: idl.StepDoneKind, message: str) -> None:
        self._done.write(idl.StepDone(participant=self.name,
                                      run_id=self.run_start.run_id if self.run_start else 0,
                                      progress_step=step, kind=kind, message=message[:255]))

    def _report_progress(self) -> None:
        if self.progress > self._acked:
            self._send_done(self.progress, idl.StepDoneKind.STEP_DONE, "")
            self._acked = self.progress

    def _fail_run(self, message: str) -> None:
        # The clock's reason names the step ("participant 'x' failed at step N: ..."): the
        # message sent carries none of its own; the local log line has it.
        if self.current_step is not None:
            log.error("step %d: %s", self.current_step, message)
        else:
            log.error("%s", message)
        try:
            step = self.current_step if self.current_step is not None else self.progress
            self._send_done(step, idl.StepDoneKind.FAILED, message)
            deadline = time.monotonic() + FAILURE_LINGER_S
            while self.stop is None and not self._clock_lost and time.monotonic() < deadline:
                seen = self.dds.notifier.generation()
                self._poll_control()
                if self.stop is None:
                    self.dds.notifier.wait_changed(seen, min(0.1, max(0.0, deadline - time.monotonic())))
        except Exception as e:  # noqa: BLE001 - reporting must not hide the original failure
            log.error("could not report the failure to the clock: %s", e)

    def run(self, step: Callable[[StepContext], None]) -> int:
        """Announces ready, waits for the run start, calls `step` for every due step below the
        clock's horizon, in order, until the clock stops the run. Returns the exit code; a
        `step` that raises fails the run with its message."""
        deadline = time.monotonic() + self.start_timeout_s
        try:
            self._wait_until(lambda: self._grants.matched_writers() > 0 and self._done.matched_readers() > 0,
                             deadline, f"the clock on domain {self.dds.domain_id}")
            self._announce_ready()
            log.info("ready (period %d offset %d), waiting for the run to start",
                     self.schedule.period_steps, self.schedule.offset_steps)
            self._wait_until(lambda: self.run_start is not None, deadline, "the run to start")
            self._arm_data_endpoints(deadline)
            end_step = self.run_start.end_step
            stride = max(1, self.run_start.window_steps // 2)
            self.progress = self._acked = min(self.schedule.offset_steps, end_step)
            self._send_done(0, idl.StepDoneKind.ARMED, "")
            dt_ns = self.run_start.dt_ns
            while True:
                seen = self.dds.notifier.generation()
                self._poll_control()
                if self.stop is None and self.progress < min(self.horizon, end_step):
                    k = self.progress
                    self.current_step = k
                    step(StepContext(k, k * dt_ns, dt_ns))
                    self.current_step = None
                    self.progress = min(k + self.schedule.period_steps, end_step)
                    if self.progress - self._acked >= stride:
                        self._report_progress()
                    continue
                self._report_progress()  # at the horizon: say so, and wait for more
                self.wait_for_news(seen)
        except RunEnded as ended:
            return ended.exit_code
        except ConfigError as e:
            self._fail_run(str(e))
            return EXIT_CONFIG
        except Exception as e:  # noqa: BLE001 - any failure of a step ends the run, named
            self._fail_run(str(e) or type(e).__name__)
            return EXIT_FAILED


class Observer:
    """Listens to climbsim without gating the clock: on no roster, sends no StepDone.
    Its readers use the step-data QoS (RELIABLE, KEEP_LAST 34) by default, or the observer QoS
    (BEST_EFFORT) for viewers. Producers write a stamped sample only at the steps some roster
    member reads it (docs/design.md#horizons), so an observer sees those stamps, not every step.
    Step-data readers may be created before the run or during it: producers arm on the readers
    of the participants the roster names (by identity), so an observer's reader does not take
    a roster member's place; it sees the samples written after it matched."""

    def __init__(self, domain: int | str | None = None, dds: DdsContext | None = None) -> None:
        self.dds = dds if dds is not None else DdsContext(resolve_domain(domain))
        self.dropped = _SenderLog("observer")
        self._binding = _ClockBinding(self.dds, "", self.dropped)
        self.sim_time = self.dds.reader(topics.SIM_TIME, idl.SimTime, qos.OBSERVER)
        self.run_start: idl.RunStart | None = None
        self.stop: idl.Stop | None = None

    def reader(self, topic: str, data_type: type, profile: str = qos.STEP_DATA):
        return self.dds.reader(topic, data_type, profile)

    def poll(self) -> None:
        """Updates run_start and stop from the latched clock topics (of this run's clock only)."""
        self._binding.poll()
        self.run_start, self.stop = self._binding.run_start, self._binding.stop

    def wait(self, timeout_s: float = 0.2) -> None:
        """Waits for news from DDS, at most `timeout_s`."""
        seen = self.dds.notifier.generation()
        self.poll()
        if self.stop is None:
            self.dds.notifier.wait_changed(seen, timeout_s)


__all__ = ["EXIT_CONFIG", "EXIT_FAILED", "EXIT_OK", "LockstepParticipant", "Observer", "RunEnded", "Schedule",
           "StampedInput", "StampedOutput", "StepContext", "add_participant_options", "wait_for"]
