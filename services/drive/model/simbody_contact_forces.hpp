#pragma once
/// @file
/// ContactBackend::kSimbody (internal to the model library): the drive model's forces and
/// accelerations computed by Simbody's own machinery, the reference the direct backend of
/// drive_model.cpp is held to. On the bodies the model built, it adds
///  - a ContactTrackerSubsystem and a CompliantContactSubsystem with the wall's half-space
///    (z < 0 in W) on Ground and a sphere of the wheel radius on every wheel; the
///    WheelWallContact generator answers each sphere/half-space contact with the law of
///    contact_law.hpp (simbody_elements.hpp);
///  - a GeneralForceSubsystem with UniformGravity, the servo torques and the adhesion with the
///    sealing drag as Force::Custom elements reading Measure variables;
/// and gets udot by realizing Stage::Acceleration (Simbody's forward dynamics).

#include <Simbody.h>

#include <vector>

#include "contact_law.hpp"
#include "drive_params.hpp"
#include "setpoint_shaper.hpp"
#include "simbody_elements.hpp"

namespace climbsim::drive {

class SimbodyContactForces {
 public:
  /// Adds the subsystems, contact surfaces and force elements to `system`; call before
  /// realizeTopology. `gravity_mps2` in W; `steering[i]` and `wheels[i]` are drive unit i's
  /// bodies. `system` must outlive this object.
  SimbodyContactForces(SimTK::MultibodySystem& system, SimTK::SimbodyMatterSubsystem& matter,
                       const DriveParams& params, const SimTK::Vec3& gravity_mps2,
                       const SimTK::MobilizedBody::Free& chassis,
                       const std::vector<SimTK::MobilizedBody>& steering,
                       const std::vector<SimTK::MobilizedBody::Pin>& wheels);

  /// udot [rad/s², m/s²] at `state` under the servo references (`references[i]` and the wheel
  /// angle reference `wheel_angle_ref_rad[i]` of unit i) and the adhesion F [N] at P_F (in R,
  /// z = 0): sets the Measure variables and realizes Stage::Acceleration. Valid until `state`
  /// changes.
  const SimTK::Vector& calcUDot(SimTK::State& state, const std::vector<UnitReference>& references,
                                const std::vector<double>& wheel_angle_ref_rad, double downforce_n,
                                const SimTK::Vec3& pf_m) const;

  /// Sets the friction deflections z [m] (in W's x, y) the contact generator reads. Must be
  /// called after every change of q or u, before anything reads a contact force (the .cpp says
  /// why).
  void setDeflections(SimTK::State& state, const std::vector<Vec2d>& deflection_m) const;

  /// The normal force on wheel i [N] (z in W of the wall's force on it) from Simbody's contact
  /// forces at `state` (realized to Velocity); 0 for a wheel without contact.
  void wheelNormalForces(const SimTK::State& state, std::vector<double>& normal_n) const;

 private:
  SimTK::GeneralForceSubsystem forces_;
  SimTK::ContactTrackerSubsystem tracker_;
  SimTK::CompliantContactSubsystem contact_;
  std::vector<SimTK::MobilizedBodyIndex> wheel_bodies_;
  std::vector<ServoReferenceVar> servo_refs_;
  std::vector<DeflectionVar> deflections_;
  AdhesionVar adhesion_;
};

}  // namespace climbsim::drive
