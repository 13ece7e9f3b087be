#pragma once
/// @file
/// The clock's watch over the processes of the participants on its own host: a kill -9 is seen
/// in /proc within one loop turn (100 ms), and a process stopped (SIGSTOP, a debugger) once it
/// has been stopped for a second, not when the DDS lease runs out. The lease (4 s,
/// deploy/qos/climbsim.xml) is longer than that on purpose: a loaded machine may starve a
/// process that runs of the CPU for seconds, and the lease must not take it for dead.
///
/// Why not the lease alone: Fast DDS 2.9's shared-memory transport locks each port with a
/// boost interprocess mutex that gives up after 1 s (its bundled boostconfig.hpp sets
/// BOOST_INTERPROCESS_TIMEOUT_WHEN_LOCKING_DURATION_MS 1000). A process killed while it holds
/// its port's mutex leaves every push to that port blocked 1 s, until the port's watchdog
/// marks it broken and the port is made again; meanwhile the pushing threads, the one that
/// sends the participant announcements among them, stand still. Then every participant misses
/// the others' announcements for 3-5 s, all leases run out at once, and the first participant
/// dropped, not always the dead one, is blamed (Lockstep.KillNine..., 1 run in 10-20 under
/// load). The dead process's own state in /proc says which one died.
///
/// A participant counts as on this host only when everything says so: its announced host
/// name is this host's, its DDS participant's GUID prefix carries this host's id (bytes 2-3,
/// which Fast DDS derives from the host's addresses) and the low 16 bits of the announced pid
/// (bytes 4-5), and /proc holds a running process of that pid when it announces. Another
/// machine that happens to have the same name, another network namespace, or another DDS
/// vendor is left to the lease.

#include <chrono>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "climbsim/sender_identity.hpp"

namespace climbsim::clock {

/// The state letter of /proc/<pid>/stat (R, S, D, T, t, Z, X, ...), 0 if there is no such
/// process.
char processState(std::uint32_t pid);

/// True if the state letter means the process has ended (0: none, Z: a zombie, X: dead).
bool processEnded(char state);

/// True if `host` (as a participant announces it: at most kMaxNameLength characters) is this
/// host's name.
bool isThisHostName(const std::string& host);

/// True if the participant `theirs` that announced host name `host` and process `pid` runs on
/// the same host as the local DDS participant `ours` (see the file comment).
bool onThisHost(const ParticipantId& theirs, const ParticipantId& ours, const std::string& host, std::uint32_t pid);

/// The processes of this host's participants, by participant name.
class ProcessWatch {
 public:
  /// Watches `pid` for `participant` (replacing an earlier pid of that name).
  void watch(const std::string& participant, std::uint32_t pid) { pids_[participant] = pid; }

  /// The participants whose processes have ended since the last call, each once, with
  /// their pids.
  std::vector<std::pair<std::string, std::uint32_t>> ended();

  /// Number of participants watched (those whose process has not been reported ended).
  std::size_t size() const { return pids_.size(); }

  /// The participants whose processes have been stopped (SIGSTOP, a debugger: state T or t)
  /// at every look for at least `limit`, each once, with their pids. A stopped process never
  /// answers, so it is named by its state, after as long as the DDS lease used to take
  /// (the lease itself is longer: a loaded machine may starve a running process of a second).
  std::vector<std::pair<std::string, std::uint32_t>> stoppedFor(std::chrono::steady_clock::duration limit);

 private:
  std::map<std::string, std::uint32_t> pids_;
  std::map<std::string, std::chrono::steady_clock::time_point> stopped_since_;  ///< by participant
  std::set<std::string> named_stopped_;  ///< reported by stoppedFor once
};

}  // namespace climbsim::clock
