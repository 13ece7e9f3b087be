#pragma once
/// @file
/// Before a run starts: the depth renderers (climbsim-scene writing depth) and the sealing
/// shards (climbsim-sealing) of a compose file agree on the depth image, and every shard reads
/// a renderer that has its pixels (a sharded layout's bad input). The services find the same at
/// their first frame; here it is one line naming the compose file, the service and the values, exit
/// 2, before any process starts.
///
/// The rules, on each instance's command line (${replica} and ${replicas} expanded):
///  - a shard of a W x W px image of pixel size s (`--camera-px`, else the scenario's
///    depth_camera.size_px, else 256; s = `--view-m`, else the robot's view, over W) reads only
///    renderers whose image has the same size and pixel size (`--depth-size-px`, else the
///    scenario's, else the scene camera's, else 256; `--depth-width-m`, else the scene camera's
///    size, else the robot's view). The robot's view is robotDepthViewM of the instance's robot
///    (the scenario's with --scenario, else --robot's, else the default robot);
///  - shard I/N reads (from its `--depth-from` renderers, else from every depth renderer) a
///    renderer of the whole image, of `--tile I/N` (the tile rendered for exactly that shard) or
///    of `--tile 0/1` (the box of every sealing pixel);
///  - every `--depth-from` name is an instance of the compose file (one of another program than
///    climbsim-scene, e.g. a test feeder, is left to the clock's check at run start).

#include "compose_file.hpp"
#include "climbsim/scenario.hpp"
#include "climbsim/wall/scene_description.hpp"

namespace climbsim::launcher {

/// Throws ConfigError "<compose>:<line>: services.<name> (<instance>): ..." for the first
/// shard that breaks a rule above. Services that name a scene of their own (`--scene`) or
/// run offline are not checked. `description` is the scenario's scene.
void checkDepthLayout(const ComposeFile& compose, const Scenario& scenario, const scene::SceneDescription& description);

}  // namespace climbsim::launcher
