#pragma once
/// @file
/// climbsim-scene on the lockstep: a SceneNode between its DDS topics (a part of the
/// executable, not of climbsim_scene_node, which has no DDS entity).

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
int runSceneParticipant(const ParticipantOptions& options, const SceneSetup& setup, bool tiled, SceneNode& node);

}  // namespace climbsim::scene
