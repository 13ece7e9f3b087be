#pragma once
/// @file
/// climbsim-scene on the lockstep: a SceneNode between its DDS topics (a part of the
/// executable, not of climbsim_scene_node, which has no DDS entity).

#include <functional>
#include <memory>

#include "climbsim/lockstep_participant.hpp"
#include "scene/configure.hpp"
#include "scene_node.hpp"

namespace climbsim::scene {

/// Joins the run as `options` says and, every due step until the run ends, applies the
/// RobotState samples to `node` and writes what setup.write_depth and setup.write_laser ask
/// for. A renderer of the whole depth image (not `tiled`) also puts a reduced image
/// (scene/DepthGrid, 64 x 64 block means) into the record batches of a recorder that records
/// it, at the first due step at or after each 0.1 s of simulated time. Returns the run's exit
/// code.
/// The participant and its endpoints are made first, with a shared-memory segment for images of
/// `camera`'s size; then `build_node` builds the node while DDS discovery goes on.
int runSceneParticipant(const ParticipantOptions& options, const SceneSetup& setup, bool tiled,
                        const DepthCameraParams& camera, const std::function<std::unique_ptr<SceneNode>()>& build_node);

}  // namespace climbsim::scene
