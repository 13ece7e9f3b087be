#include "recorded_depth_grids.hpp"

#include <mcap/reader.hpp>

#include <fastdds/rtps/common/SerializedPayload.h>

#include <cstring>

#include "climbsim/errors.hpp"
#include "climbsim/height_grid.hpp"
#include "climbsim/recording/mcap_check.hpp"
#include "climbsim/topic_names.hpp"
#include "scenePubSubTypes.h"

namespace climbsim::viewer {

std::vector<std::pair<double, std::string>> recordedDepthGrids(const std::string& path) {
  const recording::McapCheck check = recording::checkMcap(path);
  if (!check.closed) throw ConfigError(path + ": " + check.problem);
  std::vector<std::pair<double, std::string>> out;
  if (!check.channels.count(topic::kDepthGrid)) return out;
  mcap::McapReader reader;
  if (const auto status = reader.open(path); !status.ok()) throw ConfigError(path + ": " + status.message);
  mcap::ReadMessageOptions options;
  options.topicFilter = [](std::string_view topic) { return topic == topic::kDepthGrid; };
  DepthGridPubSubType type;
  std::string problem;
  for (const auto& view : reader.readMessages([&problem](const mcap::Status& s) { problem = s.message; }, options)) {
    eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<std::uint32_t>(view.message.dataSize));
    std::memcpy(payload.data, view.message.data, view.message.dataSize);
    payload.length = static_cast<std::uint32_t>(view.message.dataSize);
    climbsim::DepthGrid g;
    if (!type.deserialize(&payload, &g) || g.height_m().size() != static_cast<std::size_t>(g.size()) * g.size()) {
      throw ConfigError(path + ": a scene/DepthGrid message does not decode");
    }
    const HeightGrid grid{static_cast<int>(g.size()), g.cell_m(), g.height_m()};
    out.emplace_back(static_cast<double>(g.t_ns()) * 1e-9, heightGridJson(grid, g.step(), g.t_ns()).dump());
  }
  reader.close();
  if (!problem.empty()) throw ConfigError(path + ": " + problem);
  return out;
}

}  // namespace climbsim::viewer
