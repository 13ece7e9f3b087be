#pragma once
/// @file
/// The drive model's own Simbody elements for ContactBackend::kSimbody (internal to the model
/// library): the wheel-wall contact force generator for Simbody's CompliantContactSubsystem,
/// the servo torques of the drive units, and the adhesion force with the sealing drag. They
/// evaluate the same laws as the direct backend (contact_law.hpp, drive_forces.hpp) through
/// Simbody's contact geometry and force elements.

#include <Simbody.h>

#include <vector>

#include "drive_params.hpp"

namespace climbsim::drive {

/// Per drive unit: reference of the steering and wheel servos (δ_ref, δ̇_ref, θ_ref, ω_ref).
using ServoReferenceVar = SimTK::Measure_<SimTK::Vec4>::Variable;
/// Per wheel: friction deflection z in W (x, y; z component 0) [m].
using DeflectionVar = SimTK::Measure_<SimTK::Vec3>::Variable;
/// Adhesion input (F [N], P_F x [m], P_F y [m]) in R.
using AdhesionVar = SimTK::Measure_<SimTK::Vec3>::Variable;

/// Responds to the CircularPointContact of a wheel's sphere against the wall's half-space
/// with the contact law of contact_law.hpp: Hertz/Hunt-Crossley normal force and bristle
/// friction from the wheel's deflection variable. The wall must be the contact's surface 1
/// (Simbody's tracker orders half-space before sphere); contacts of other bodies get no force.
class WheelWallContact : public SimTK::ContactForceGenerator {
 public:
  /// `wheel_bodies[i]` carries wheel i's sphere; `deflections[i]` is its friction state.
  WheelWallContact(const DriveParams& params, std::vector<SimTK::MobilizedBodyIndex> wheel_bodies,
                   std::vector<DeflectionVar> deflections);

  void calcContactForce(const SimTK::State& state, const SimTK::Contact& overlapping,
                        const SimTK::SpatialVec& V_S1S2, SimTK::ContactForce& force_S1) const override;
  void calcContactPatch(const SimTK::State& state, const SimTK::Contact& overlapping,
                        const SimTK::SpatialVec& V_S1S2, SimTK::ContactPatch& patch) const override;

  /// Index of the wheel whose body is `body`, or -1.
  int wheelOf(SimTK::MobilizedBodyIndex body) const;

 private:
  ContactParams contact_;
  std::vector<WheelMount> mounts_;
  std::vector<SimTK::MobilizedBodyIndex> wheel_bodies_;
  std::vector<DeflectionVar> deflections_;
};

/// Steering and wheel servos of every drive unit: PD on the references with a torque limit
/// (ServoParams), applied as mobility forces of the steering and wheel pins; a fixed wheel
/// has the wheel servo only (its steering body is welded), a caster no servo but its swivel
/// damping (casterDamping).
class ServoTorques : public SimTK::Force::Custom::Implementation {
 public:
  ServoTorques(const DriveParams& params, std::vector<SimTK::MobilizedBody> steering,
               std::vector<SimTK::MobilizedBody::Pin> wheels, std::vector<ServoReferenceVar> references);
  void calcForce(const SimTK::State& state, SimTK::Vector_<SimTK::SpatialVec>& body_forces,
                 SimTK::Vector_<SimTK::Vec3>& particle_forces, SimTK::Vector& mobility_forces) const override;
  SimTK::Real calcPotentialEnergy(const SimTK::State&) const override { return 0; }

 private:
  DriveParams params_;
  std::vector<SimTK::MobilizedBody> steering_;
  std::vector<SimTK::MobilizedBody::Pin> wheels_;
  std::vector<ServoReferenceVar> references_;
};

/// The adhesion force -F z_W at P_F on the chassis, and the sealing drag (sealingDrag in
/// drive_forces.hpp) at R's origin.
class AdhesionAndDrag : public SimTK::Force::Custom::Implementation {
 public:
  AdhesionAndDrag(const DriveParams& params, SimTK::MobilizedBody chassis, AdhesionVar adhesion);
  void calcForce(const SimTK::State& state, SimTK::Vector_<SimTK::SpatialVec>& body_forces,
                 SimTK::Vector_<SimTK::Vec3>& particle_forces, SimTK::Vector& mobility_forces) const override;
  SimTK::Real calcPotentialEnergy(const SimTK::State&) const override { return 0; }

 private:
  DriveParams params_;
  SimTK::MobilizedBody chassis_;
  AdhesionVar adhesion_;
};

}  // namespace climbsim::drive
