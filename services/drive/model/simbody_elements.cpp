#include "simbody_elements.hpp"

#include <algorithm>
#include <cmath>

#include "contact_law.hpp"
#include "drive_forces.hpp"

namespace climbsim::drive {

using namespace SimTK;

WheelWallContact::WheelWallContact(const DriveParams& params, std::vector<MobilizedBodyIndex> wheel_bodies,
                                   std::vector<DeflectionVar> deflections)
    : ContactForceGenerator(CircularPointContact::classTypeId()),
      contact_(params.contact),
      mounts_(params.wheels),
      wheel_bodies_(std::move(wheel_bodies)),
      deflections_(std::move(deflections)) {}

int WheelWallContact::wheelOf(MobilizedBodyIndex body) const {
  for (std::size_t i = 0; i < wheel_bodies_.size(); ++i) {
    if (wheel_bodies_[i] == body) return static_cast<int>(i);
  }
  return -1;
}

void WheelWallContact::calcContactForce(const State& state, const Contact& overlapping, const SpatialVec& V_S1S2,
                                        ContactForce& force_S1) const {
  const CircularPointContact& contact = CircularPointContact::getAs(overlapping);
  const ContactTrackerSubsystem& tracker = getCompliantContactSubsystem().getContactTrackerSubsystem();
  const double x = contact.getDepth();
  const int wheel = wheelOf(tracker.getMobilizedBody(contact.getSurface2()).getMobilizedBodyIndex());
  const bool wall_is_1 = tracker.getMobilizedBody(contact.getSurface1()).getMobilizedBodyIndex() == GroundIndex;
  if (x <= 0 || wheel < 0 || !wall_is_1) {
    force_S1.clear();
    return;
  }
  const Rotation& R_GS1 = tracker.getContactSurfaceTransform(contact.getSurface1()).R();
  const UnitVec3& n = contact.getNormal();  // away from the wall, in S1
  // The wall is rigid next to the wheel: the force acts on the wall's surface.
  const Vec3 point = contact.getOrigin() + (0.5 * x) * n;
  const Vec3& w12 = V_S1S2[0];
  const Vec3& v12 = V_S1S2[1];
  const Vec3 vel = v12 + w12 % (point - contact.getTransform().p());
  const double xdot = -dot(vel, n);
  const Vec3 slip_S1 = vel + xdot * n;
  const WheelMount& mount = mounts_[static_cast<std::size_t>(wheel)];
  const double normal = normalForce(contact_, mount.radius_m, x, xdot);
  if (normal <= 0) {
    force_S1.setTo(contact.getContactId(), point, SpatialVec(Vec3(0), Vec3(0)), 0, 0);
    return;
  }
  // The law is written in the wall plane (W's x, y): move slip and deflection through W.
  const Vec3 slip_G = R_GS1 * slip_S1;
  const Vec3 z_G = deflections_[static_cast<std::size_t>(wheel)].getValue(state);
  const Vec2d f = frictionForce(contact_, mount, {z_G[0], z_G[1]}, {slip_G[0], slip_G[1]}, normal);
  const Vec3 friction_S1 = ~R_GS1 * Vec3(f[0], f[1], 0);
  const double elastic_energy = 0.4 * normal * x;
  const double power_loss = -dot(friction_S1, slip_S1) + std::max(0.0, normal * xdot);
  force_S1.setTo(contact.getContactId(), point, SpatialVec(Vec3(0), normal * Vec3(n) + friction_S1),
                 elastic_energy, power_loss);
}

void WheelWallContact::calcContactPatch(const State& state, const Contact& overlapping, const SpatialVec& V_S1S2,
                                        ContactPatch& patch) const {
  ContactForce force;
  calcContactForce(state, overlapping, V_S1S2, force);
  patch.clear();
  patch.m_resultant = force;
}

ServoTorques::ServoTorques(const DriveParams& params, std::vector<MobilizedBody> steering,
                           std::vector<MobilizedBody::Pin> wheels, std::vector<ServoReferenceVar> references)
    : params_(params),
      steering_(std::move(steering)),
      wheels_(std::move(wheels)),
      references_(std::move(references)) {}

void ServoTorques::calcForce(const State& state, Vector_<SpatialVec>&, Vector_<Vec3>&,
                             Vector& mobility_forces) const {
  for (std::size_t i = 0; i < steering_.size(); ++i) {
    const Vec4& ref = references_[i].getValue(state);
    const auto& steer = steering_[i];
    const auto& wheel = wheels_[i];
    const WheelKind kind = params_.wheels[i].kind;
    if (kind == WheelKind::kSteerable) {
      steer.applyOneMobilityForce(
          state, MobilizerUIndex(0),
          servoTorque(params_.steering_servo, ref[0], ref[1], steer.getOneQ(state, MobilizerQIndex(0)),
                      steer.getOneU(state, MobilizerUIndex(0))),
          mobility_forces);
    }
    if (kind == WheelKind::kCaster) {
      steer.applyOneMobilityForce(state, MobilizerUIndex(0),
                                  casterDamping(params_, steer.getOneU(state, MobilizerUIndex(0))), mobility_forces);
      continue;
    }
    wheel.applyOneMobilityForce(
        state, MobilizerUIndex(0),
        servoTorque(params_.wheel_servo, ref[2], ref[3], wheel.getOneQ(state, MobilizerQIndex(0)),
                    wheel.getOneU(state, MobilizerUIndex(0))),
        mobility_forces);
  }
}

AdhesionAndDrag::AdhesionAndDrag(const DriveParams& params, MobilizedBody chassis, AdhesionVar adhesion)
    : params_(params), chassis_(std::move(chassis)), adhesion_(std::move(adhesion)) {}

void AdhesionAndDrag::calcForce(const State& state, Vector_<SpatialVec>& body_forces, Vector_<Vec3>&,
                                Vector&) const {
  const Vec3& a = adhesion_.getValue(state);
  const double downforce_n = a[0];
  chassis_.applyForceToBodyPoint(state, Vec3(a[1], a[2], 0), Vec3(0, 0, -downforce_n), body_forces);
  const Vec3 v = chassis_.getBodyOriginVelocity(state);
  const SealingDrag drag =
      sealingDrag(params_, downforce_n, v[0], v[1], chassis_.getBodyAngularVelocity(state)[2]);
  chassis_.applyForceToBodyPoint(state, Vec3(0), Vec3(drag.fx_n, drag.fy_n, 0), body_forces);
  chassis_.applyBodyTorque(state, Vec3(0, 0, drag.torque_z_nm), body_forces);
}

}  // namespace climbsim::drive
