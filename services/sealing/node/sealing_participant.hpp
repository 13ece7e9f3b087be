#pragma once
/// @file
/// climbsim-sealing on the lockstep: a SealingNode between its DDS topics (a part of the
/// executable, not of climbsim_sealing_node, which has no DDS entity).

#include <string>
#include <vector>

#include "climbsim/lockstep_participant.hpp"
#include "sealing/configure.hpp"
#include "sealing_node.hpp"

namespace climbsim::sealing {

/// What climbsim-sealing's command line adds to the setup for the lockstep.
struct SealingLockstepOptions {
  std::vector<std::string> depth_from;  ///< --depth-from: read DepthImage from these producers only (all: empty)
  unsigned images_every = 0;            ///< --images N: SealingImage every N-th due step (0: never)
};

/// Joins the run as `options` says and steps `node` every due step until the run ends: reads
/// DepthImage, writes this shard's Leakage; with images_every, the pictures on
/// sealing/SealingImage while a viewer looks; the pictures of setup.picture_times on the
/// reliable sealing/SealingPicture (the recorder keeps them). With
/// setup.end_on_seal_over_nothing a seal over nothing fails the run after that step's
/// leakage. Returns the run's exit code.
int runSealingParticipant(const ParticipantOptions& options, const SealingLockstepOptions& lockstep,
                          const SealingSetup& setup, SealingNode& node);

}  // namespace climbsim::sealing
