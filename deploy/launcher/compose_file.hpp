#pragma once
/// @file
/// The compose file (deploy/compose*.yaml, docs/scenario-files.md): which services run, how many
/// replicas, on which host, with which clock settings and DDS domain.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace climbsim::launcher {

/// Name of the clock process in logs, `ps` and `logs`; no service may take it.
inline constexpr const char* kClockProcessName = "clock";

/// Name of the host every composition has: this machine, no namespace.
inline constexpr const char* kLocalHost = "local";

/// Most replicas one service may ask for.
inline constexpr std::uint32_t kMaxReplicas = 100;

/// The `clock:` section: the options of climbsim-clock.
struct ClockSpec {
  double step_ms = 5.0;                ///< length of one step [ms], > 0
  std::optional<double> duration_s;    ///< simulated time to run [s], > 0; exclusive with `steps`
  std::optional<std::uint64_t> steps;  ///< number of steps to run, >= 1; exclusive with `duration_s`
  double rtf = 0.0;                    ///< real-time factor, >= 0 (0 = as fast as possible)
  double start_timeout_s = 30.0;       ///< the roster must be complete within this long [s], > 0
  double step_timeout_s = 10.0;        ///< per-step watchdog [s], > 0
  bool start_paused = false;           ///< hold before step 0 until resumed
  /// W: the horizon runs at most W steps ahead of the slowest participant (1 = one grant
  /// per step); empty: the clock's default.
  std::optional<std::uint32_t> window_steps;
  std::string host = kLocalHost;       ///< where the clock runs: a name from `hosts:`
  /// A pause nobody resumes within this ends the run [s], > 0; none: a pause may last for ever.
  std::optional<double> max_pause_s;
  /// Who may send ClockControl: DDS participant names, "name" (from any host)
  /// or "name@host" (host: a name from `hosts:`). None: climbsim-clockctl from the
  /// launcher's host and the compose file's viewer observers from theirs.
  std::optional<std::vector<std::string>> control;
  int control_line = 0;                ///< line of clock.control (for messages)
};

/// How the launcher starts a process on a host.
enum class HostKind {
  local,  ///< a child process of the launcher on this machine
  ssh,    ///< `ssh -tt USER@HOST` runs it; the host sees the same paths (shared or identical checkout)
  netns,  ///< `ip netns exec NAME` runs it on this machine inside a network namespace (tests)
};

/// One entry of `hosts:`; `local` exists without being written down.
struct HostSpec {
  std::string name;     ///< the key under `hosts:`
  HostKind kind = HostKind::local;
  std::string target;   ///< ssh: user@host; netns: the namespace's name; local: empty
  /// IPv4 address the other hosts reach this one at; required for every host of a
  /// composition that uses more than one host (the DDS initial peers and interface).
  std::string address;
  /// ssh: options put before the destination (e.g. [-p, 2222], [-i, KEY], [-F, CONFIG]).
  std::vector<std::string> ssh_options;
  int line = 0;         ///< 1-based line of the entry (0 for the implicit `local`)
};

/// One entry of `services:`.
struct ServiceSpec {
  std::string name;                  ///< the key under `services:`
  std::vector<std::string> command;  ///< argv; the launcher appends --name, --period, --offset, --domain
  std::uint32_t period = 1;          ///< due every `period` clock steps, >= 1
  /// `period: depth` or `period: laser`: the scenario's depth or laser period (rates.*_hz),
  /// resolved when the run's scenario is known; empty for a numeric period.
  std::string period_rate;
  std::uint32_t offset = 0;          ///< first due step, < period
  std::uint32_t replicas = 1;        ///< 1..kMaxReplicas instances
  std::string host = kLocalHost;     ///< where it runs: a name from `hosts:` (default `local`)
  int line = 0;                      ///< 1-based line of the entry in the file (for messages)
  /// `observer: true`: not on the clock's roster, never gates a step (the viewer); the launcher
  /// appends only --name and --domain. `up` starts observers, `run` only with --viewer.
  bool observer = false;

  /// The roster names of the instances: `name`, or `name-0` .. `name-N-1` for N > 1 replicas.
  std::vector<std::string> instanceNames() const;
};

/// A validated compose file.
struct ComposeFile {
  std::string source;                 ///< where it was read from (for messages)
  std::string name;                   ///< the composition's name (run directory, `ps`)
  std::optional<int> domain_id;       ///< 0..232, or nothing for `auto`
  /// `scenario:` the default scenario of `up` (absolute, resolved against the compose file's
  /// directory), or empty; `--scenario` replaces it.
  std::string scenario;
  int scenario_line = 0;              ///< 1-based line of `scenario:` (for messages)
  /// `security: on`: DDS Security for the run (`--secure` sets it too): the launcher
  /// makes a run CA, a certificate and permissions per participant (security_material.hpp).
  bool security = false;
  ClockSpec clock;
  std::vector<HostSpec> hosts;        ///< `local` first, then `hosts:` in file order
  std::vector<ServiceSpec> services;  ///< in file order

  /// The host named `name`; throws std::out_of_range if there is none (validated at parse).
  const HostSpec& host(const std::string& name) const;

  /// The hosts the clock and the services run on, in `hosts` order.
  std::vector<const HostSpec*> usedHosts() const;

  /// True when the clock and the services do not all run on `local`: every used host then
  /// needs an address, and DDS discovery goes by unicast initial peers.
  bool multiHost() const;

  /// Every instance name of every service that is not an observer, in file order: the clock's roster.
  std::vector<std::string> roster() const;
};

/// Tokens a service command may contain, replaced per instance by buildLaunchPlan:
/// ${scenario} (the run's resolved scenario file), ${out} (the run's output directory),
/// ${replica} (0-based instance index) and ${replicas} (instance count).
inline constexpr const char* kCommandTokens[] = {"${scenario}", "${out}", "${replica}", "${replicas}"};

/// Parses and validates compose YAML text. `source` names it in errors. Throws ConfigError
/// with one line "<source>:<line>: <key> = <value>: <what is wrong>" on any problem:
/// YAML syntax, unknown or duplicate keys, invalid or duplicate names, period 0,
/// offset >= period, domain_id outside 0..232, missing command, bad clock numbers,
/// a host that `hosts:` does not define, a host entry with a bad kind, target or address,
/// a used host without an address in a multi-host composition.
ComposeFile parseComposeText(const std::string& yaml_text, const std::string& source);

/// Reads and validates a compose file; throws ConfigError (also if it cannot be read).
ComposeFile loadComposeFile(const std::string& path);

}  // namespace climbsim::launcher
