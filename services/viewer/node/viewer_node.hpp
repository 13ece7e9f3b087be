#pragma once
/// @file
/// The viewer's DDS side: an observer (never on the roster, never gates a step). The step data
/// a recorder records come from the producers' observer batches (record/ObserverBatch: the
/// newest sample of each recorded topic, at most 30 a second per producer; best effort, profile
/// climbsim.record_observer), what no recorder records from best-effort KEEP_LAST 1 readers
/// of the topics (climbsim.observer); SimTime, latched readers of RunStart, Stop and
/// ParticipantReady, and a ClockControl writer for the page's run panel.

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>

#include "client_command.hpp"
#include "climbsim/dds_context.hpp"
#include "climbsim/height_grid.hpp"
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

  /// Samples taken by every reader so far (Fast DDS deliveries to the viewer).
  std::uint64_t deliveries() const { return dds_.deliveries(); }

  /// True once the data readers exist and the step data come in record batches.
  bool readsRecordBatches() const;

 private:
  struct Readers;
  struct DataReaders;
  void takeBatches(LiveState& state, PollResult& result);
  std::string name_;
  int max_depth_cells_;
  Notifier notifier_;
  DdsContext dds_;
  bool read_depth_ = true;
  std::unique_ptr<Readers> readers_;
  std::unique_ptr<DataReaders> data_readers_;  ///< once the run is under way
  std::optional<std::uint64_t> run_id_;        ///< of the first RunStart
  std::set<std::string> recorded_;             ///< topics a recorder on its roster records
  bool sim_time_seen_ = false;
  std::mutex control_mutex_;
};

}  // namespace climbsim::viewer
