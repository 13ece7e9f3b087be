#include "drive_model.hpp"

#include <Simbody.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "contact_law.hpp"
#include "drive_command.hpp"
#include "setpoint_shaper.hpp"
#include "simbody_elements.hpp"

namespace climbsim::drive {

using namespace SimTK;

namespace {

/// Beyond this a downforce is garbage rather than physics [N].
constexpr double kAbsurdDownforceN = 1.0e6;

std::string fmt(double value) {
  std::ostringstream os;
  os << value;
  return os.str();
}

/// A rotor of axial inertia `axial` with just enough transverse inertia to be a rigid body
/// (Simbody checks the triangle inequality), plus `mass` spread over a disc of radius r.
Inertia rotorInertia(double axial, double mass, double radius) {
  const double transverse = axial / 2.0 + mass * radius * radius / 4.0;
  return Inertia(transverse, transverse, axial + mass * radius * radius / 2.0);
}

}  // namespace

std::string checkInputs(const DriveParams& params, const DriveInputs& in) {
  std::string why = checkCommand(params, in.command);
  if (!why.empty()) return why;
  if (!(std::isfinite(in.downforce_n) && std::fabs(in.downforce_n) <= kAbsurdDownforceN)) {
    return "downforce_n = " + fmt(in.downforce_n) + " (must be finite, |.| <= 1e6)";
  }
  const double reach = 2.0 * params.body_radius_m;
  if (!(std::isfinite(in.pf_x_m) && std::isfinite(in.pf_y_m) && std::hypot(in.pf_x_m, in.pf_y_m) <= reach)) {
    return "(pf_x_m, pf_y_m) = (" + fmt(in.pf_x_m) + ", " + fmt(in.pf_y_m) +
           ") (must be finite and within the body diameter of the centre)";
  }
  return {};
}

struct DriveModel::Impl {
  explicit Impl(const DriveParams& params, const WallOrientation& wall, const StartPose& start);

  void substep(double h);
  void updateOutputs();

  DriveParams p;
  MultibodySystem system;
  SimbodyMatterSubsystem matter{system};
  GeneralForceSubsystem forces{system};
  ContactTrackerSubsystem tracker{system};
  CompliantContactSubsystem contact{system, tracker};
  MobilizedBody::Free chassis;
  std::vector<MobilizedBody::Pin> steering;
  std::vector<MobilizedBody::Pin> wheels;
  std::vector<MobilizedBodyIndex> wheel_bodies;
  std::vector<ServoReferenceVar> servo_refs;
  std::vector<DeflectionVar> deflections;
  AdhesionVar adhesion;
  State state;
  QIndex quaternion_q;

  SetpointShaper shaper;
  std::vector<WheelSetpoint> targets;
  std::vector<double> wheel_angle_ref_rad;
  std::vector<double> slip_mps;
  double contact_lost_s = 0.0;
  Transform start_pose;
  bool held = false;
  bool started = false;
  std::int64_t next_t_ns = 0;
  std::int64_t substeps = 0;
  DriveOutputs out;
};

DriveModel::Impl::Impl(const DriveParams& params, const WallOrientation& wall, const StartPose& start)
    : p((validateDriveParams(params), params)),
      adhesion(forces, Stage::Dynamics, Vec3(0)),
      shaper(params.wheels.size(), static_cast<int>(std::lround(params.command_delay_s / params.substep_s)),
             params.max_steering_rate_radps),
      targets(params.wheels.size()),
      wheel_angle_ref_rad(params.wheels.size(), 0.0),
      slip_mps(params.wheels.size(), 0.0) {
  const double n = static_cast<double>(p.wheels.size());
  const double rw = p.wheel_radius_m;
  const double half_unit_kg = 0.5 * p.mass_kg * p.unit_mass_fraction;
  const double chassis_kg = p.mass_kg - 2.0 * n * half_unit_kg;
  // The units' mass sits at axle height; the chassis' centre of mass makes up the rest.
  const double chassis_com_m = (p.mass_kg * p.com_height_m - 2.0 * n * half_unit_kg * rw) / chassis_kg;
  const Vec3 com(0, 0, chassis_com_m);
  const Inertia chassis_inertia =
      Inertia(p.inertia_xx_kgm2, p.inertia_yy_kgm2, p.inertia_zz_kgm2).shiftFromMassCenter(com, chassis_kg);
  Body::Rigid chassis_body(MassProperties(chassis_kg, com, chassis_inertia));
  chassis = MobilizedBody::Free(matter.Ground(), Transform(), chassis_body, Transform());

  system.setUseUniformBackground(true);
  const ContactMaterial material(p.contact.hertz_modulus_pa, p.contact.dissipation_spm,
                                 p.contact.friction_coefficient, p.contact.friction_coefficient, 0.0);
  // HalfSpace fills x > 0 of its frame; turned so that it fills z < 0 of W.
  matter.Ground().updBody().addContactSurface(Transform(Rotation(Pi / 2, YAxis), Vec3(0)),
                                              ContactSurface(ContactGeometry::HalfSpace(), material));
  const ContactCliqueId wheels_clique = ContactSurface::createNewContactClique();
  for (const auto& mount : p.wheels) {
    Body::Rigid fork_body(
        MassProperties(half_unit_kg, Vec3(0), rotorInertia(p.steering_inertia_kgm2, half_unit_kg, rw)));
    steering.emplace_back(chassis, Transform(Vec3(mount.x_m, mount.y_m, rw)), fork_body, Transform());
    Body::Rigid wheel_body(
        MassProperties(half_unit_kg, Vec3(0), rotorInertia(p.wheel_spin_inertia_kgm2, half_unit_kg, rw)));
    ContactSurface sphere(ContactGeometry::Sphere(rw), material);
    sphere.joinClique(wheels_clique);
    wheel_body.addContactSurface(Transform(), sphere);
    // The pin turns about the steering body's y: positive rates roll the wheel along its x.
    wheels.emplace_back(steering.back(), Transform(Rotation(-Pi / 2, XAxis), Vec3(0)), wheel_body, Transform());
    wheel_bodies.push_back(wheels.back().getMobilizedBodyIndex());
    servo_refs.emplace_back(forces, Stage::Dynamics, Vec4(0));
    // The deflections enter Simbody's contact force cache, which is computed lazily and
    // depends on Velocity, yet changing one invalidates only Dynamics: one Velocity
    // realization per substep instead of two. Safe because substep() changes them only
    // right after changing q and u (which invalidate that cache), before anything reads it.
    deflections.emplace_back(forces, Stage::Dynamics, Vec3(0));
  }
  contact.adoptForceGenerator(new WheelWallContact(p, wheel_bodies, deflections));
  Force::UniformGravity(forces, matter,
                        p.gravity_mps2 * Vec3(wall.gravity_x, wall.gravity_y, wall.gravity_z));
  Force::Custom(forces, new ServoTorques(p, steering, wheels, servo_refs));
  Force::Custom(forces, new AdhesionAndDrag(p, chassis, adhesion));

  state = system.realizeTopology();
  system.realizeModel(state);
  start_pose = Transform(Rotation(start.yaw_rad, ZAxis), Vec3(start.x_m, start.y_m, 0));
  chassis.setQToFitTransform(state, start_pose);
  quaternion_q = chassis.getFirstQIndex(state);
  system.realize(state, Stage::Velocity);
  updateOutputs();
}

void DriveModel::Impl::substep(double h) {
  shaper.advance(targets, h);
  const double windup_rad = p.wheel_servo.torque_max_nm / p.wheel_servo.kp_nmprad;
  for (std::size_t i = 0; i < wheels.size(); ++i) {
    const UnitReference& ref = shaper.references()[i];
    // Anti-windup: a wheel held back by the torque limit does not store up an angle error.
    const double theta = wheels[i].getOneQ(state, MobilizerQIndex(0));
    wheel_angle_ref_rad[i] =
        std::clamp(wheel_angle_ref_rad[i] + ref.wheel_speed_radps * h, theta - windup_rad, theta + windup_rad);
    servo_refs[i].setValue(
        state, Vec4(ref.steering_rad, ref.steering_rate_radps, wheel_angle_ref_rad[i], ref.wheel_speed_radps));
  }

  system.realize(state, Stage::Acceleration);
  state.updU() += h * state.getUDot();
  Vector qdot;
  matter.multiplyByN(state, false, state.getU(), qdot);
  state.updQ() += h * qdot;
  Vector& q = state.updQ();
  const double norm = std::sqrt(square(q[quaternion_q]) + square(q[quaternion_q + 1]) +
                                square(q[quaternion_q + 2]) + square(q[quaternion_q + 3]));
  for (int k = 0; k < 4; ++k) q[quaternion_q + k] /= norm;
  if (held) {
    chassis.setQToFitTransform(state, start_pose);
    chassis.setUToFitVelocity(state, SpatialVec(Vec3(0), Vec3(0)));
  }
  state.updTime() += h;
  system.realize(state, Stage::Velocity);
  ++substeps;

  bool any_contact = false;
  const double rw = p.wheel_radius_m;
  for (std::size_t i = 0; i < wheels.size(); ++i) {
    const Vec3 centre = wheels[i].getBodyOriginLocation(state);
    const Vec3 point(centre[0], centre[1], 0);
    const Vec3 vel = wheels[i].findStationVelocityInGround(state, wheels[i].findStationAtGroundPoint(state, point));
    const double normal = normalForce(p.contact, rw, rw - centre[2], -vel[2]);
    any_contact = any_contact || normal > 0.0;
    slip_mps[i] = normal > 0.0 ? std::hypot(vel[0], vel[1]) : 0.0;
    const Vec3& z = deflections[i].getValue(state);
    const Vec2d next = advanceDeflection(p.contact, {z[0], z[1]}, {vel[0], vel[1]},
                                         wheels[i].getOneU(state, MobilizerUIndex(0)) * rw, normal, h);
    deflections[i].setValue(state, Vec3(next[0], next[1], 0));
  }

  // A held robot cannot fall; without downforce its wheels barely touch the wall meanwhile.
  contact_lost_s = any_contact || held ? 0.0 : contact_lost_s + h;
  const Vec3 origin = chassis.getBodyOriginLocation(state);
  const Vec3 v = chassis.getBodyOriginVelocity(state);
  if (std::fabs(origin[2]) > p.fall_distance_m || contact_lost_s >= p.fall_contact_loss_s ||
      std::hypot(v[0], v[1]) > p.fall_speed_mps) {
    out.fell = true;
  }
}

void DriveModel::Impl::updateOutputs() {
  system.realize(state, Stage::Velocity);
  const Vec3 origin = chassis.getBodyOriginLocation(state);
  const Quaternion quat = chassis.getBodyRotation(state).convertRotationToQuaternion();
  const Vec3 v = chassis.getBodyOriginVelocity(state);
  const Vec3 w = chassis.getBodyAngularVelocity(state);
  for (int k = 0; k < 3; ++k) {
    out.position_m[k] = origin[k];
    out.linear_velocity_mps[k] = v[k];
    out.angular_velocity_radps[k] = w[k];
  }
  for (int k = 0; k < 4; ++k) out.orientation_wxyz[k] = quat[k];
  out.wheels.assign(wheels.size(), WheelOutputs{});
  for (std::size_t i = 0; i < wheels.size(); ++i) {
    out.wheels[i].steering_rad = steering[i].getOneQ(state, MobilizerQIndex(0));
    out.wheels[i].wheel_speed_radps = wheels[i].getOneU(state, MobilizerUIndex(0));
    out.wheels[i].slip_mps = slip_mps[i];
  }
  const ContactSnapshot& active = tracker.getActiveContacts(state);
  for (int k = 0; k < contact.getNumContactForces(state); ++k) {
    const ContactForce& force = contact.getContactForce(state, k);
    const Contact& c = active.getContactById(force.getContactId());
    const MobilizedBodyIndex body = tracker.getMobilizedBody(c.getSurface2()).getMobilizedBodyIndex();
    const auto it = std::find(wheel_bodies.begin(), wheel_bodies.end(), body);
    if (it == wheel_bodies.end()) continue;
    // Force on the wheel, in Ground = W: its z component is the normal force.
    out.wheels[static_cast<std::size_t>(it - wheel_bodies.begin())].normal_force_n =
        std::max(0.0, force.getForceOnSurface2()[1][2]);
  }
}

DriveModel::DriveModel(const DriveParams& params, const WallOrientation& wall, const StartPose& start)
    : impl_(std::make_unique<Impl>(params, wall, start)) {}

DriveModel::~DriveModel() = default;

const DriveOutputs& DriveModel::step(std::int64_t t_ns, std::int64_t dt_ns, const DriveInputs& inputs) {
  auto& m = *impl_;
  if (dt_ns <= 0) throw std::invalid_argument("DriveModel::step: dt_ns = " + std::to_string(dt_ns) + " (must be > 0)");
  if (m.started && t_ns != m.next_t_ns) {
    throw std::invalid_argument("DriveModel::step: t_ns = " + std::to_string(t_ns) + " but the last step ended at " +
                                std::to_string(m.next_t_ns));
  }
  if (const std::string why = checkInputs(m.p, inputs); !why.empty()) {
    throw std::invalid_argument("DriveModel::step: " + why);
  }
  m.started = true;
  m.targets = wheelTargets(m.p, inputs.command, m.targets);
  m.adhesion.setValue(m.state, Vec3(inputs.downforce_n, inputs.pf_x_m, inputs.pf_y_m));
  m.state.setTime(static_cast<double>(t_ns) * 1e-9);

  const auto substep_ns = static_cast<std::int64_t>(std::llround(m.p.substep_s * 1e9));
  const std::int64_t count = std::max<std::int64_t>(1, (dt_ns + substep_ns - 1) / substep_ns);
  const double h = static_cast<double>(dt_ns) * 1e-9 / static_cast<double>(count);
  for (std::int64_t k = 0; k < count; ++k) m.substep(h);

  m.next_t_ns = t_ns + dt_ns;
  m.out.t_ns = m.next_t_ns;
  m.updateOutputs();
  return m.out;
}

void DriveModel::setHeld(bool held) { impl_->held = held; }
bool DriveModel::held() const { return impl_->held; }

const DriveOutputs& DriveModel::outputs() const { return impl_->out; }
const DriveParams& DriveModel::params() const { return impl_->p; }
const std::vector<WheelSetpoint>& DriveModel::targets() const { return impl_->targets; }
std::int64_t DriveModel::substeps() const { return impl_->substeps; }

}  // namespace climbsim::drive
