#pragma once
/// @file
/// What the drive's wheels stand on (docs/design.md#drive): the scene's static surface as
/// heights over the wall plane (climbsim/wall/surface_heights.hpp), possibly still loading in
/// the background. Without one (DriveParams::ground null) the wheels stand on the wall plane
/// z_W = 0.

#include <future>
#include <memory>

#include "climbsim/wall/surface_heights.hpp"

namespace climbsim::drive {

class WheelGround {
 public:
  /// Surface heights ready now.
  explicit WheelGround(scene::SurfaceHeights heights);
  /// Surface heights still being made: the first query waits for them (and rethrows what
  /// making them threw). A null result leaves the wheels on the wall plane.
  explicit WheelGround(std::shared_future<std::shared_ptr<const scene::SurfaceHeights>> loading);

  /// Where a wheel (a sphere of radius `radius_m`) above (x_m, y_m) of W rests
  /// (SurfaceHeights::sphereRest). Not for several threads at once (the heights are built
  /// tile by tile as the wheels reach them).
  scene::SphereRest rest(double x_m, double y_m, double radius_m) const;

 private:
  const scene::SurfaceHeights* heights() const;

  std::shared_future<std::shared_ptr<const scene::SurfaceHeights>> loading_;
  mutable const scene::SurfaceHeights* heights_ = nullptr;
  mutable bool asked_ = false;
};

}  // namespace climbsim::drive
