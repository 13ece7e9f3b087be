#pragma once
/// @file
/// The downforce log's model: decides when a log line is due and writes it. Pure (no DDS, no
/// wall clock): it sees thermo's downforce samples in simulated time and answers, for each,
/// whether a line is due and what it says.

#include <cstdint>
#include <string>

#include "climbsim/model_contract.hpp"

namespace climbsim::downforce_log {

/// What the log is configured with.
struct DownforceLogParams {
  std::int64_t period_ns = 1'000'000'000;  ///< simulated time between two lines [ns] (> 0)
};

/// What the log remembers between samples.
struct DownforceLogState {
  std::int64_t next_due_ns = 0;  ///< the simulated time the next line is due at [ns]
};

/// One sample of thermo/AdhesionForce.
struct DownforceLogInputs {
  double downforce_n = 0.0;  ///< F = sum_i (p_o - p_i) A_i [N], > 0 pulls towards the wall
  double setpoint_n = 0.0;   ///< the set-point F* of the controller in force [N]; 0: none stated
};

/// The answer to one sample.
struct DownforceLogOutputs {
  bool due = false;   ///< true: `line` is to be logged
  double t_s = 0.0;   ///< simulated time the sample's value holds at [s] (the trace row's t_s)
  std::string line;   ///< "t = 3.000 s: F = 2187.4 N (set-point 2200 N)"; empty unless due
};

/// Logs the downforce once per period of simulated time: the first sample whose value holds
/// at or after each multiple k * period (k >= 1) gives a line, stamped with the time it holds at.
/// A sample stamped t_ns (the start of its step) holds at t_ns + dt_ns, the end of the step:
/// trace.csv has it in the row of that time (docs/design.md#the-shared-simulation-clock).
/// A line that comes late (samples missed) does not make later lines late: the next one is due
/// at the next multiple of the period after it.
class DownforceLog {
 public:
  using Params = DownforceLogParams;
  using State = DownforceLogState;
  using Inputs = DownforceLogInputs;
  using Outputs = DownforceLogOutputs;

  /// Throws std::invalid_argument if params.period_ns <= 0.
  explicit DownforceLog(Params params);

  const Params& params() const { return params_; }

  /// Before the first sample: the first line is due at one period.
  State initialState() const { return State{params_.period_ns}; }

  /// One sample of the step that starts at t_ns and lasts dt_ns [ns].
  Outputs step(State& state, const Inputs& inputs, std::int64_t t_ns, std::int64_t dt_ns) const;

 private:
  Params params_;
};

static_assert(is_model_v<DownforceLog>, "DownforceLog keeps the model contract");

/// The text of one line: "t = 3.000 s: F = 2187.4 N (set-point 2200 N)", or "(no set-point)"
/// when setpoint_n is 0 or less.
std::string formatLine(double t_s, const DownforceLogInputs& inputs);

}  // namespace climbsim::downforce_log
