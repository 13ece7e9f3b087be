#include "simbody_contact_forces.hpp"

#include <algorithm>

namespace climbsim::drive {

using namespace SimTK;

SimbodyContactForces::SimbodyContactForces(MultibodySystem& system, SimbodyMatterSubsystem& matter,
                                           const DriveParams& p, const Vec3& gravity_mps2,
                                           const MobilizedBody::Free& chassis,
                                           const std::vector<MobilizedBody>& steering,
                                           const std::vector<MobilizedBody::Pin>& wheels)
    : forces_(system), tracker_(system), contact_(system, tracker_), adhesion_(forces_, Stage::Dynamics, Vec3(0)) {
  system.setUseUniformBackground(true);
  // Simbody's material friction is unused: the generator applies each wheel's own (WheelMount).
  const ContactMaterial material(p.contact.hertz_modulus_pa, p.contact.dissipation_spm,
                                 p.wheels.front().friction_coefficient, p.wheels.front().friction_coefficient, 0.0);
  // HalfSpace fills x > 0 of its frame; turned so that it fills z < 0 of W.
  matter.Ground().updBody().addContactSurface(Transform(Rotation(Pi / 2, YAxis), Vec3(0)),
                                              ContactSurface(ContactGeometry::HalfSpace(), material));
  const ContactCliqueId wheels_clique = ContactSurface::createNewContactClique();
  for (std::size_t i = 0; i < wheels.size(); ++i) {
    MobilizedBody::Pin wheel = wheels[i];
    ContactSurface sphere(ContactGeometry::Sphere(p.wheels[i].radius_m), material);
    sphere.joinClique(wheels_clique);
    wheel.updBody().addContactSurface(Transform(), sphere);
    wheel_bodies_.push_back(wheel.getMobilizedBodyIndex());
    servo_refs_.emplace_back(forces_, Stage::Dynamics, Vec4(0));
    // The deflections enter Simbody's contact force cache, which is computed lazily and
    // depends on Velocity, yet changing one invalidates only Dynamics: one Velocity
    // realization per substep instead of two. Safe because the model changes them only right
    // after changing q and u (which invalidate that cache), before anything reads it.
    deflections_.emplace_back(forces_, Stage::Dynamics, Vec3(0));
  }
  contact_.adoptForceGenerator(new WheelWallContact(p, wheel_bodies_, deflections_));
  Force::UniformGravity(forces_, matter, gravity_mps2);
  Force::Custom(forces_, new ServoTorques(p, steering, wheels, servo_refs_));
  Force::Custom(forces_, new AdhesionAndDrag(p, chassis, adhesion_));
}

const Vector& SimbodyContactForces::calcUDot(State& state, const std::vector<UnitReference>& references,
                                             const std::vector<double>& wheel_angle_ref_rad, double downforce_n,
                                             const Vec3& pf_m) const {
  for (std::size_t i = 0; i < servo_refs_.size(); ++i) {
    const UnitReference& ref = references[i];
    servo_refs_[i].setValue(
        state, Vec4(ref.steering_rad, ref.steering_rate_radps, wheel_angle_ref_rad[i], ref.wheel_speed_radps));
  }
  adhesion_.setValue(state, Vec3(downforce_n, pf_m[0], pf_m[1]));
  forces_.getMultibodySystem().realize(state, Stage::Acceleration);
  return state.getUDot();
}

void SimbodyContactForces::setDeflections(State& state, const std::vector<Vec2d>& deflection_m) const {
  for (std::size_t i = 0; i < deflections_.size(); ++i) {
    deflections_[i].setValue(state, Vec3(deflection_m[i][0], deflection_m[i][1], 0));
  }
}

void SimbodyContactForces::wheelNormalForces(const State& state, std::vector<double>& normal_n) const {
  normal_n.assign(wheel_bodies_.size(), 0.0);
  const ContactSnapshot& active = tracker_.getActiveContacts(state);
  for (int k = 0; k < contact_.getNumContactForces(state); ++k) {
    const ContactForce& force = contact_.getContactForce(state, k);
    const Contact& c = active.getContactById(force.getContactId());
    const MobilizedBodyIndex body = tracker_.getMobilizedBody(c.getSurface2()).getMobilizedBodyIndex();
    const auto it = std::find(wheel_bodies_.begin(), wheel_bodies_.end(), body);
    if (it == wheel_bodies_.end()) continue;
    // Force on the wheel, in Ground = W: its z component is the normal force.
    normal_n[static_cast<std::size_t>(it - wheel_bodies_.begin())] = std::max(0.0, force.getForceOnSurface2()[1][2]);
  }
}

}  // namespace climbsim::drive
