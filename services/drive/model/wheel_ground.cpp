#include "wheel_ground.hpp"

namespace climbsim::drive {

WheelGround::WheelGround(scene::SurfaceHeights heights) {
  std::promise<std::shared_ptr<const scene::SurfaceHeights>> ready;
  ready.set_value(std::make_shared<const scene::SurfaceHeights>(std::move(heights)));
  loading_ = ready.get_future().share();
}

WheelGround::WheelGround(std::shared_future<std::shared_ptr<const scene::SurfaceHeights>> loading)
    : loading_(std::move(loading)) {}

const scene::SurfaceHeights* WheelGround::heights() const {
  if (!asked_) {
    heights_ = loading_.get().get();
    asked_ = true;
  }
  return heights_;
}

scene::SphereRest WheelGround::rest(double x_m, double y_m, double radius_m) const {
  if (const scene::SurfaceHeights* heights = this->heights()) return heights->sphereRest(x_m, y_m, radius_m);
  scene::SphereRest plane;
  plane.touches = true;
  plane.centre_z_m = radius_m;
  plane.point_m = Eigen::Vector3d(x_m, y_m, 0.0);
  plane.level = true;
  return plane;
}

}  // namespace climbsim::drive
