#pragma once
/// @file
/// The viewer's DDS side: an observer (never on the roster, never gates a step). Best-effort
/// KEEP_LAST 1 readers (profile climbsim.observer) of the step data and SimTime, latched
/// readers of RunStart, Stop and ParticipantReady, and a ClockControl writer for the page's
/// run panel.

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "client_command.hpp"
#include "climbsim/dds_context.hpp"
#include "height_grid.hpp"
#include "live_state.hpp"

namespace climbsim::viewer {

/// What poll() found besides the live state.
struct PollResult {
  bool changed = false;                        ///< the live state changed
  std::optional<HeightGrid> depth;             ///< the newest depth image, reduced, if one came
  std::uint64_t depth_step = 0;
  std::int64_t depth_t_ns = 0;
  std::map<std::string, std::string> sealing_png;  ///< kind -> newest PNG bytes that came
};

class ViewerNode {
 public:
  /// Creates the participant and every reader and writer; `max_depth_cells` bounds the
  /// reduced depth grid per side; `read_depth` false: no reader of the depth images at all.
  ViewerNode(const DdsSettings& settings, const std::string& name, int max_depth_cells, bool read_depth = true);
  ~ViewerNode();
  ViewerNode(const ViewerNode&) = delete;
  ViewerNode& operator=(const ViewerNode&) = delete;

  /// Takes every sample that came since the last call into `state` (latest value wins).
  PollResult poll(LiveState& state);

  /// Publishes a ClockControl; thread-safe. False if no clock is matched (nothing is sent).
  bool send(const ClockRequest& request);

  /// Woken by every sample, match and loss.
  Notifier& notifier() { return notifier_; }

 private:
  struct Readers;
  struct StepReaders;
  std::string name_;
  int max_depth_cells_;
  Notifier notifier_;
  DdsContext dds_;
  bool read_depth_ = true;
  std::unique_ptr<Readers> readers_;
  std::unique_ptr<StepReaders> step_readers_;  ///< once the run is under way
  std::mutex control_mutex_;
};

}  // namespace climbsim::viewer
