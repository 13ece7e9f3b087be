#include "drive_model.hpp"

#include <Simbody.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include "contact_law.hpp"
#include "drive_command.hpp"
#include "drive_forces.hpp"
#include "setpoint_shaper.hpp"
#include "simbody_contact_forces.hpp"
#include "wheel_ground.hpp"

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

/// a and b are the same double bit for bit (unlike ==, which takes 0 for -0).
bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

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

/// What the forces and the friction update need of one wheel at the current (q, u).
struct WheelSample {
  Vec3 lever_m;               ///< wheel centre -> contact point, in W
  /// The contact frame: normal n (surface to wheel) and tangents t1, t2 (t1 along W's x
  /// projected on the contact plane, t2 = n x t1); W's z, x, y where the wheel stands level.
  Vec3 normal{0, 0, 1};
  Vec3 tangent1{1, 0, 0};
  Vec3 tangent2{0, 1, 0};
  bool level = true;          ///< normal exactly W's z: the components below are W's
  Vec2d slip_mps{};           ///< velocity of the wheel's material point at the contact point, along t1, t2
  double normal_n = 0.0;      ///< normal force of the contact law, 0 without contact [N]
  double rolling_mps = 0.0;   ///< wheel spin rate times the wheel radius [m/s]
  /// The last ground query of this wheel: where the sphere above (x, y) of W rests (a pure
  /// function of x, y and the ground, asked again only when the centre moves along the wall;
  /// a held robot's wheels stay put).
  double ground_x_m = NaN, ground_y_m = NaN;
  scene::SphereRest ground_rest;
};

struct DriveModelState::Data {
  /// q, u (and the simbody backend's Measure variables), realized to Velocity between steps.
  State simbody;
  std::vector<Vec2d> deflection_m;  ///< friction deflection z per wheel, in W's x, y [m]
  SetpointShaper shaper;            ///< dead time and rate-limited references
  std::vector<WheelSetpoint> targets;
  std::vector<double> wheel_angle_ref_rad;
  double contact_lost_s = 0.0;  ///< how long no wheel has touched the wall [s]
  Transform start_pose;         ///< where a held robot is kept
  std::int64_t t_ns = 0;
  std::int64_t substeps = 0;
  DriveOutputs out;  ///< at t_ns; out.fell is latched
  std::size_t wheel_count = 0;        ///< shape of the model that made it
  ContactBackend backend = ContactBackend::kDirect;

  // Held over the step being taken (from the inputs).
  double downforce_n = 0.0;
  Vec3 pf_m{0};  ///< P_F in R
  bool held = false;

  /// Derived from `simbody` by DriveModel::Impl::sample() whenever q or u change (the initial
  /// state, every substep), so always those of the current (q, u), and work arrays kept to
  /// avoid allocating per substep.
  struct Scratch {
    Transform chassis_pose;
    SpatialVec chassis_velocity;
    std::vector<WheelSample> samples;
    Vector mobility_forces;
    Vector_<SpatialVec> body_forces;
    Vector udot;
    Vector qdot;
    Vector_<SpatialVec> body_accelerations;
    std::vector<double> normal_n;
  } scratch;

  Data(std::size_t wheels, int delay_substeps, double max_rate_radps)
      : deflection_m(wheels, Vec2d{0.0, 0.0}),
        shaper(wheels, delay_substeps, max_rate_radps),
        targets(wheels),
        wheel_angle_ref_rad(wheels, 0.0),
        wheel_count(wheels) {
    scratch.samples.resize(wheels);
  }
};

DriveModelState::DriveModelState(std::unique_ptr<Data> data) : data_(std::move(data)) {}
DriveModelState::DriveModelState(const DriveModelState& other) : data_(std::make_unique<Data>(*other.data_)) {}
DriveModelState::DriveModelState(DriveModelState&& other) noexcept = default;
DriveModelState& DriveModelState::operator=(const DriveModelState& other) {
  if (this != &other) data_ = std::make_unique<Data>(*other.data_);
  return *this;
}
DriveModelState& DriveModelState::operator=(DriveModelState&& other) noexcept = default;
DriveModelState::~DriveModelState() = default;

std::int64_t DriveModelState::t_ns() const { return data_->t_ns; }
const DriveOutputs& DriveModelState::outputs() const { return data_->out; }
const std::vector<WheelSetpoint>& DriveModelState::targets() const { return data_->targets; }
std::int64_t DriveModelState::substeps() const { return data_->substeps; }

/// The System and its bodies, fixed after construction; every function takes the evolving
/// state as an argument.
struct DriveModel::Impl {
  using Data = DriveModelState::Data;

  explicit Impl(const DriveParams& params, const WallOrientation& wall);

  void substep(Data& s, double h) const;
  /// Reads the kinematics the forces need from the state (realized to Velocity): after
  /// every change of q or u.
  void sample(Data& s) const;
  /// The applied forces at the sampled state: gravity, contact, servos, adhesion, drag.
  void applyForces(Data& s) const;
  /// udot at the current state (realized to Velocity and sampled), by the chosen backend.
  const Vector& accelerations(Data& s) const;
  void updateOutputs(Data& s) const;
  /// While held: the friction deflections that carry the in-plane load in static equilibrium.
  void holdingDeflections(Data& s) const;
  /// Sum over the units of their mass times their axle height [kg m]: 2 n m_half r_w when
  /// every wheel has the same radius (in that order), else the sum of 2 m_half r_i.
  double unitsAxleMoment() const;
  /// The wheel's contact with the ground at its centre `centre` and the wheel's velocity.
  void contact(std::size_t i, const Vec3& centre, const SpatialVec& v_wheel, WheelSample& ws) const;
  /// The start pose standing on the ground: `flat` (at rest on the wall plane) where every
  /// wheel stands level at height 0, else tilted to the least-squares plane through the
  /// wheels' rest heights and lifted until no wheel cuts the surface.
  Transform restingPose(const Transform& flat) const;

  DriveParams p;
  Vec3 gravity_mps2;
  MultibodySystem system;
  SimbodyMatterSubsystem matter{system};
  MobilizedBody::Free chassis;
  /// Per unit the steering body: on a pin about R's z (steerable, caster) or welded (fixed).
  std::vector<MobilizedBody> steering;
  std::vector<MobilizedBody::Pin> wheels;
  double chassis_kg = 0.0;
  Vec3 chassis_com_m;  ///< in the chassis frame R
  double half_unit_kg = 0.0;
  /// Invalid for a fixed wheel's welded steering body.
  std::vector<QIndex> steering_q, wheel_q;
  std::vector<UIndex> steering_u, wheel_u;
  /// ContactBackend::kSimbody: Simbody's contact and force subsystems (null: direct).
  std::unique_ptr<SimbodyContactForces> simbody_contact;
  /// The default state after realizeModel: initialState() starts from a copy.
  SimTK::State model_state;
  /// What the wheels stand on (direct backend only); null: the wall plane.
  std::shared_ptr<const WheelGround> ground;
  QIndex quaternion_q;
  int delay_substeps = 0;
};

DriveModel::Impl::Impl(const DriveParams& params, const WallOrientation& wall)
    : p((validateDriveParams(params), params)),
      gravity_mps2(params.gravity_mps2 * Vec3(wall.gravity_x, wall.gravity_y, wall.gravity_z)),
      delay_substeps(static_cast<int>(std::lround(params.command_delay_s / params.substep_s))) {
  const double n = static_cast<double>(p.wheels.size());
  half_unit_kg = 0.5 * p.mass_kg * p.unit_mass_fraction;
  chassis_kg = p.mass_kg - 2.0 * n * half_unit_kg;
  // The units' mass sits at axle height; the chassis' centre of mass makes up the rest.
  chassis_com_m = Vec3(0, 0, (p.mass_kg * p.com_height_m - unitsAxleMoment()) / chassis_kg);
  const Inertia chassis_inertia = Inertia(p.inertia_xx_kgm2, p.inertia_yy_kgm2, p.inertia_zz_kgm2)
                                      .shiftFromMassCenter(chassis_com_m, chassis_kg);
  Body::Rigid chassis_body(MassProperties(chassis_kg, chassis_com_m, chassis_inertia));
  chassis = MobilizedBody::Free(matter.Ground(), Transform(), chassis_body, Transform());
  for (const auto& mount : p.wheels) {
    const double rw = mount.radius_m;
    const bool caster = mount.kind == WheelKind::kCaster;
    const double steer_inertia = caster ? p.caster_inertia_kgm2 : p.steering_inertia_kgm2;
    const double spin_inertia = caster ? p.caster_inertia_kgm2 : p.wheel_spin_inertia_kgm2;
    // Both bodies of a unit have their centre of mass at their origin (applyForces relies on it).
    Body::Rigid fork_body(MassProperties(half_unit_kg, Vec3(0), rotorInertia(steer_inertia, half_unit_kg, rw)));
    const Transform at_mount(Vec3(mount.x_m, mount.y_m, rw));
    if (mount.kind == WheelKind::kFixed) {
      steering.push_back(MobilizedBody::Weld(chassis, at_mount, fork_body, Transform()));
    } else {
      steering.push_back(MobilizedBody::Pin(chassis, at_mount, fork_body, Transform()));
    }
    Body::Rigid wheel_body(MassProperties(half_unit_kg, Vec3(0), rotorInertia(spin_inertia, half_unit_kg, rw)));
    // The pin turns about the steering body's y: positive rates roll the wheel along its x. A
    // caster's wheel trails its swivel axis along the steering body's -x.
    wheels.emplace_back(steering.back(), Transform(Rotation(-Pi / 2, XAxis), Vec3(-mount.trail_m, 0, 0)), wheel_body,
                        Transform());
  }
  if (p.contact_backend == ContactBackend::kSimbody) {
    simbody_contact = std::make_unique<SimbodyContactForces>(system, matter, p, gravity_mps2, chassis, steering, wheels);
  } else {
    ground = p.ground;
  }

  model_state = system.realizeTopology();
  system.realizeModel(model_state);
  quaternion_q = chassis.getFirstQIndex(model_state);
  for (std::size_t i = 0; i < wheels.size(); ++i) {
    const bool pinned = p.wheels[i].kind != WheelKind::kFixed;
    steering_q.push_back(pinned ? steering[i].getFirstQIndex(model_state) : QIndex());
    steering_u.push_back(pinned ? steering[i].getFirstUIndex(model_state) : UIndex());
    wheel_q.push_back(wheels[i].getFirstQIndex(model_state));
    wheel_u.push_back(wheels[i].getFirstUIndex(model_state));
  }
}

double DriveModel::Impl::unitsAxleMoment() const {
  const double n = static_cast<double>(p.wheels.size());
  const double rw = p.wheels.front().radius_m;
  const bool equal = std::all_of(p.wheels.begin(), p.wheels.end(),
                                 [rw](const WheelMount& w) { return w.radius_m == rw; });
  if (equal) return 2.0 * n * half_unit_kg * rw;
  double moment = 0.0;
  for (const auto& w : p.wheels) moment += 2.0 * half_unit_kg * w.radius_m;
  return moment;
}

void DriveModel::Impl::sample(Data& s) const {
  const SimTK::State& state = s.simbody;
  auto& w = s.scratch;
  w.chassis_pose = chassis.getBodyTransform(state);
  w.chassis_velocity = chassis.getBodyVelocity(state);
  const Real* u = &state.getU()[0];
  for (std::size_t i = 0; i < wheels.size(); ++i) {
    WheelSample& ws = w.samples[i];
    contact(i, wheels[i].getBodyTransform(state).p(), wheels[i].getBodyVelocity(state), ws);
    ws.rolling_mps = u[wheel_u[i]] * p.wheels[i].radius_m;
  }
}

void DriveModel::Impl::contact(std::size_t i, const Vec3& centre, const SpatialVec& v_wheel, WheelSample& ws) const {
  const double rw = p.wheels[i].radius_m;
  if (!ground) {
    // The wheel's sphere against the wall's half-space z < 0: penetration rw - centre z, the
    // contact point the centre projected on the wall plane, the normal W's z.
    ws.lever_m = Vec3(0, 0, -centre[2]);
    const Vec3 v = v_wheel[1] + v_wheel[0] % ws.lever_m;
    ws.slip_mps = {v[0], v[1]};
    ws.normal_n = normalForce(p.contact, rw, rw - centre[2], -v[2]);
    return;
  }
  // The sphere over the scene's surface: it would rest with its centre at z_rest; the
  // penetration along the contact normal n is (z_rest - z_c) n_z.
  if (!(sameBits(centre[0], ws.ground_x_m) && sameBits(centre[1], ws.ground_y_m))) {
    ws.ground_rest = ground->rest(centre[0], centre[1], rw);
    ws.ground_x_m = centre[0], ws.ground_y_m = centre[1];
  }
  const scene::SphereRest& rest = ws.ground_rest;
  if (!rest.touches) {
    // Nothing under the wheel within the sensors' reach: no contact.
    ws.level = true;
    ws.normal = Vec3(0, 0, 1), ws.tangent1 = Vec3(1, 0, 0), ws.tangent2 = Vec3(0, 1, 0);
    ws.lever_m = Vec3(0, 0, -centre[2]);
    ws.slip_mps = {0.0, 0.0};
    ws.normal_n = 0.0;
    return;
  }
  if (rest.level) {
    // A level patch at height h straight below: the plane's equations shifted by h (the same
    // numbers as the wall plane for h = 0).
    ws.level = true;
    ws.normal = Vec3(0, 0, 1), ws.tangent1 = Vec3(1, 0, 0), ws.tangent2 = Vec3(0, 1, 0);
    ws.lever_m = Vec3(0, 0, rest.point_m.z() - centre[2]);
    const Vec3 v = v_wheel[1] + v_wheel[0] % ws.lever_m;
    ws.slip_mps = {v[0], v[1]};
    ws.normal_n = normalForce(p.contact, rw, rest.centre_z_m - centre[2], -v[2]);
    return;
  }
  const Vec3 n(rest.normal.x(), rest.normal.y(), rest.normal.z());
  const double penetration = (rest.centre_z_m - centre[2]) * n[2];
  ws.level = false;
  ws.normal = n;
  ws.tangent1 = (Vec3(1, 0, 0) - n[0] * n).normalize();
  ws.tangent2 = n % ws.tangent1;
  ws.lever_m = -(rw - penetration) * n;
  const Vec3 v = v_wheel[1] + v_wheel[0] % ws.lever_m;
  ws.slip_mps = {dot(v, ws.tangent1), dot(v, ws.tangent2)};
  ws.normal_n = normalForce(p.contact, rw, penetration, -dot(v, n));
}

Transform DriveModel::Impl::restingPose(const Transform& flat) const {
  if (!ground) return flat;
  // Each wheel's rest height e_i (the centre's lowest height minus r_i) at its centre's
  // place on the wall at the flat pose, steering 0 (a caster's wheel trails its mount).
  const std::size_t n = p.wheels.size();
  std::vector<double> e(n, 0.0), x(n, 0.0), y(n, 0.0);
  std::vector<Vec3> centre_R(n);
  bool all_level_at_zero = true;
  int touching = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const WheelMount& m = p.wheels[i];
    centre_R[i] = Vec3(m.x_m - m.trail_m, m.y_m, m.radius_m);
    const Vec3 c = flat * centre_R[i];
    x[i] = c[0] - flat.p()[0], y[i] = c[1] - flat.p()[1];
    const scene::SphereRest rest = ground->rest(c[0], c[1], m.radius_m);
    if (!rest.touches) {
      e[i] = NaN;
      all_level_at_zero = false;
      continue;
    }
    ++touching;
    e[i] = rest.centre_z_m - m.radius_m;
    all_level_at_zero = all_level_at_zero && rest.level && rest.point_m.z() == 0.0;
  }
  if (all_level_at_zero || touching == 0) return flat;
  // Least squares e = a + b x + c y over the wheels that touch (only a lift below three).
  Mat33 a(0);
  Vec3 rhs(0);
  for (std::size_t i = 0; i < n; ++i) {
    if (isNaN(e[i])) continue;
    const Vec3 row(1.0, x[i], y[i]);
    a += row * ~row;
    rhs += e[i] * row;
  }
  Vec3 plane(0);
  if (touching >= 3 && std::fabs(det(a)) > 1e-12) {
    plane = a.invert() * rhs;
  }
  Rotation tilt;  // identity
  const UnitVec3 up(-plane[1], -plane[2], 1.0);
  const Vec3 axis = Vec3(0, 0, 1) % up.asVec3();
  if (axis.norm() > 0.0) tilt = Rotation(std::asin(std::min(1.0, axis.norm())), UnitVec3(axis));
  Transform pose(tilt * flat.R(), flat.p());
  // Lift until every touching wheel's centre is at or above its rest height.
  double lift = -Infinity;
  for (std::size_t i = 0; i < n; ++i) {
    if (isNaN(e[i])) continue;
    lift = std::max(lift, e[i] + p.wheels[i].radius_m - (pose * centre_R[i])[2]);
  }
  pose.updP()[2] += lift;
  return pose;
}

void DriveModel::Impl::applyForces(Data& s) const {
  auto& w = s.scratch;
  w.mobility_forces = 0;
  w.body_forces = SpatialVec(Vec3(0), Vec3(0));
  // Raw element access: the Debian build of Simbody checks every Vector index out of line.
  const Real* q = &s.simbody.getQ()[0];
  const Real* u = &s.simbody.getU()[0];
  Real* mobility = &w.mobility_forces[0];

  // Gravity at the centres of mass.
  const Vec3 chassis_weight = chassis_kg * gravity_mps2;
  const MobilizedBodyIndex c = chassis.getMobilizedBodyIndex();
  w.body_forces[c] += SpatialVec((w.chassis_pose.R() * chassis_com_m) % chassis_weight, chassis_weight);
  const Vec3 unit_weight = half_unit_kg * gravity_mps2;

  const std::vector<UnitReference>& refs = s.shaper.references();
  for (std::size_t i = 0; i < wheels.size(); ++i) {
    w.body_forces[steering[i].getMobilizedBodyIndex()][1] += unit_weight;
    SpatialVec& wheel = w.body_forces[wheels[i].getMobilizedBodyIndex()];
    wheel[1] += unit_weight;
    // Contact: the normal force and the bristle friction at the contact point.
    const WheelSample& ws = w.samples[i];
    if (ws.normal_n > 0.0) {
      const Vec2d f = frictionForce(p.contact, p.wheels[i], s.deflection_m[i], ws.slip_mps, ws.normal_n);
      const Vec3 force = ws.level ? Vec3(f[0], f[1], ws.normal_n)
                                  : f[0] * ws.tangent1 + f[1] * ws.tangent2 + ws.normal_n * ws.normal;
      wheel += SpatialVec(ws.lever_m % force, force);
    }
    // Servos (a steerable unit's two, a fixed wheel's drive), or a caster's swivel damping.
    const WheelKind kind = p.wheels[i].kind;
    if (kind == WheelKind::kSteerable) {
      mobility[steering_u[i]] += servoTorque(p.steering_servo, refs[i].steering_rad, refs[i].steering_rate_radps,
                                             q[steering_q[i]], u[steering_u[i]]);
    }
    if (kind == WheelKind::kCaster) {
      mobility[steering_u[i]] += casterDamping(p, u[steering_u[i]]);
    } else {
      mobility[wheel_u[i]] += servoTorque(p.wheel_servo, s.wheel_angle_ref_rad[i], refs[i].wheel_speed_radps,
                                          q[wheel_q[i]], u[wheel_u[i]]);
    }
  }

  // Adhesion -F z_W at P_F, and the sealing drag at R's origin.
  const Vec3 adhesion(0, 0, -s.downforce_n);
  w.body_forces[c] += SpatialVec((w.chassis_pose.R() * s.pf_m) % adhesion, adhesion);
  const Vec3& v = w.chassis_velocity[1];
  const SealingDrag drag = sealingDrag(p, s.downforce_n, v[0], v[1], w.chassis_velocity[0][2]);
  w.body_forces[c] += SpatialVec(Vec3(0, 0, drag.torque_z_nm), Vec3(drag.fx_n, drag.fy_n, 0));
}

const Vector& DriveModel::Impl::accelerations(Data& s) const {
  if (simbody_contact) {
    return simbody_contact->calcUDot(s.simbody, s.shaper.references(), s.wheel_angle_ref_rad, s.downforce_n, s.pf_m);
  }
  applyForces(s);
  system.realize(s.simbody, Stage::Dynamics);
  // The tree has no constraints: this is the whole forward dynamics (articulated body method).
  auto& w = s.scratch;
  matter.calcAccelerationIgnoringConstraints(s.simbody, w.mobility_forces, w.body_forces, w.udot,
                                             w.body_accelerations);
  return w.udot;
}

void DriveModel::Impl::substep(Data& s, double h) const {
  SimTK::State& state = s.simbody;
  auto& w = s.scratch;
  s.shaper.advance(s.targets, h);
  const double windup_rad = p.wheel_servo.torque_max_nm / p.wheel_servo.kp_nmprad;
  const Real* q_now = &state.getQ()[0];
  for (std::size_t i = 0; i < wheels.size(); ++i) {
    // Anti-windup: a wheel held back by the torque limit does not store up an angle error.
    const double theta = q_now[wheel_q[i]];
    s.wheel_angle_ref_rad[i] = std::clamp(s.wheel_angle_ref_rad[i] + s.shaper.references()[i].wheel_speed_radps * h,
                                          theta - windup_rad, theta + windup_rad);
  }

  // Semi-implicit Euler: u' = u + h udot(q, u, z), q' = q + h N(q) u'.
  {
    const Vector& udot = accelerations(s);
    const Real* a = &udot[0];
    Vector& u_vector = state.updU();
    Real* u = &u_vector[0];
    for (int k = 0, nu = u_vector.size(); k < nu; ++k) u[k] += h * a[k];
  }
  matter.multiplyByN(state, false, state.getU(), w.qdot);
  const Real* qdot = &w.qdot[0];
  Vector& q_vector = state.updQ();
  Real* q = &q_vector[0];
  for (int k = 0, nq = q_vector.size(); k < nq; ++k) q[k] += h * qdot[k];
  const double norm = std::sqrt(square(q[quaternion_q]) + square(q[quaternion_q + 1]) +
                                square(q[quaternion_q + 2]) + square(q[quaternion_q + 3]));
  for (int k = 0; k < 4; ++k) q[quaternion_q + k] /= norm;
  if (s.held) {
    // The hand holds the pose along the wall and the attitude, and keeps the robot from lifting
    // off, but lets it press into the wall: the wheels take the downforce while held.
    const double z_start = s.start_pose.p()[2];
    const double z = std::min(chassis.getOneQ(state, 6), z_start);
    const double vz = z >= z_start ? std::min(chassis.getOneU(state, 5), 0.0) : chassis.getOneU(state, 5);
    chassis.setQToFitTransform(state, Transform(s.start_pose.R(), Vec3(s.start_pose.p()[0], s.start_pose.p()[1], z)));
    chassis.setUToFitVelocity(state, SpatialVec(Vec3(0), Vec3(0, 0, vz)));
  }
  system.realize(state, Stage::Velocity);
  sample(s);
  ++s.substeps;

  // The friction deflections follow (q', u').
  bool any_contact = false;
  for (std::size_t i = 0; i < wheels.size(); ++i) {
    const WheelSample& ws = w.samples[i];
    any_contact = any_contact || ws.normal_n > 0.0;
    s.deflection_m[i] =
        advanceDeflection(p.contact, p.wheels[i], s.deflection_m[i], ws.slip_mps, ws.rolling_mps, ws.normal_n, h);
  }
  if (s.held) holdingDeflections(s);
  if (simbody_contact) simbody_contact->setDeflections(state, s.deflection_m);

  // A held robot cannot fall; without downforce its wheels barely touch the wall meanwhile.
  s.contact_lost_s = any_contact || s.held ? 0.0 : s.contact_lost_s + h;
  const Vec3& origin = w.chassis_pose.p();
  const Vec3& v = w.chassis_velocity[1];
  if (std::fabs(origin[2]) > p.fall_distance_m || s.contact_lost_s >= p.fall_contact_loss_s ||
      std::hypot(v[0], v[1]) > p.fall_speed_mps) {
    s.out.fell = true;
  }
}

void DriveModel::Impl::holdingDeflections(Data& s) const {
  // In-plane load on the robot at rest: gravity (force G and its moment M about R's origin O
  // along the wall normal); the adhesion and the normal forces are normal to the wall, the
  // sealing drag is zero at rest. The wheels' friction forces f_i at the contact points d_i
  // (from O) must cancel it: sum f_i = -G, sum (d_i x f_i)_z = -M. Of the many solutions take
  // the one that loads each driven wheel in proportion to its normal force N_i (least sum
  // |f_i|² / N_i; a caster swivels and spins freely and carries none):
  // f_i = -N_i (lambda + mu e_i), e_i = z x d_i, with
  //   [S 0 Ex; 0 S Ey; Ex Ey Q] [lambda_x lambda_y mu] = [Gx Gy M],
  //   S = sum N_i, E = sum N_i e_i, Q = sum N_i |d_i|².
  // The bristles then carry it with deflections -f_i / k_t: released, nothing has to move.
  const SimTK::State& state = s.simbody;
  const auto& samples = s.scratch.samples;
  const auto carries = [this](std::size_t i) { return isDriven(p.wheels[i].kind); };
  const Transform& chassis_pose = s.scratch.chassis_pose;
  const Vec3& o = chassis_pose.p();
  Vec3 g_force = chassis_kg * gravity_mps2;
  Vec3 g_moment = (chassis_pose.R() * chassis_com_m) % (chassis_kg * gravity_mps2);
  for (std::size_t i = 0; i < wheels.size(); ++i) {
    for (const MobilizedBody* b : {static_cast<const MobilizedBody*>(&steering[i]), static_cast<const MobilizedBody*>(&wheels[i])}) {
      const Vec3 weight = half_unit_kg * gravity_mps2;
      g_force += weight;
      g_moment += (b->getBodyTransform(state).p() - o) % weight;
    }
  }
  Mat33 a(0);
  Vec3 b(g_force[0], g_force[1], g_moment[2]);
  std::vector<Vec2d> e(wheels.size(), Vec2d{0.0, 0.0});
  int carrying = 0;
  for (std::size_t i = 0; i < wheels.size(); ++i) {
    const double n = carries(i) ? samples[i].normal_n : 0.0;
    if (!(n > 0.0)) continue;
    ++carrying;
    const Vec3 d = wheels[i].getBodyTransform(state).p() - o;
    e[i] = {-d[1], d[0]};
    a(0, 0) += n;
    a(1, 1) += n;
    a(0, 2) += n * e[i][0];
    a(1, 2) += n * e[i][1];
    a(2, 2) += n * (d[0] * d[0] + d[1] * d[1]);
  }
  a(2, 0) = a(0, 2);
  a(2, 1) = a(1, 2);
  if (!(a(0, 0) > 0.0)) return;  // no wheel touches: the hand carries everything
  if (carrying == 1) {
    // One wheel cannot take a moment: it carries the force, the hand the rest.
    a(0, 2) = a(1, 2) = a(2, 0) = a(2, 1) = b[2] = 0.0;
    a(2, 2) = 1.0;
  }
  const Vec3 x = a.invert() * b;
  for (std::size_t i = 0; i < wheels.size(); ++i) {
    const double n = carries(i) ? samples[i].normal_n : 0.0;
    if (!(n > 0.0)) continue;
    Vec2d z{n * (x[0] + x[2] * e[i][0]) / p.contact.tangential_stiffness_npm,
            n * (x[1] + x[2] * e[i][1]) / p.contact.tangential_stiffness_npm};
    const double limit = p.wheels[i].friction_coefficient * n / p.contact.tangential_stiffness_npm;
    const double size = std::hypot(z[0], z[1]);
    if (size > limit) {
      z[0] *= limit / size;
      z[1] *= limit / size;
    }
    s.deflection_m[i] = z;
  }
}

void DriveModel::Impl::updateOutputs(Data& s) const {
  const SimTK::State& state = s.simbody;
  auto& w = s.scratch;
  DriveOutputs& out = s.out;
  const Vec3& origin = w.chassis_pose.p();
  const Quaternion quat = w.chassis_pose.R().convertRotationToQuaternion();
  const Vec3& av = w.chassis_velocity[0];
  const Vec3& v = w.chassis_velocity[1];
  for (int k = 0; k < 3; ++k) {
    out.position_m[k] = origin[k];
    out.linear_velocity_mps[k] = v[k];
    out.angular_velocity_radps[k] = av[k];
  }
  for (int k = 0; k < 4; ++k) out.orientation_wxyz[k] = quat[k];
  out.wheels.resize(wheels.size());
  if (simbody_contact) {
    simbody_contact->wheelNormalForces(state, w.normal_n);
  } else {
    w.normal_n.resize(wheels.size());
    for (std::size_t i = 0; i < wheels.size(); ++i) w.normal_n[i] = w.samples[i].normal_n;
  }
  for (std::size_t i = 0; i < wheels.size(); ++i) {
    const WheelSample& ws = w.samples[i];
    WheelOutputs& o = out.wheels[i];
    o.steering_rad = steering_q[i].isValid() ? state.getQ()[steering_q[i]] : 0.0;
    o.wheel_speed_radps = state.getU()[wheel_u[i]];
    o.normal_force_n = w.normal_n[i];
    o.slip_mps = ws.normal_n > 0.0 ? std::hypot(ws.slip_mps[0], ws.slip_mps[1]) : 0.0;
  }
}

DriveModel::DriveModel(const DriveParams& params, const WallOrientation& wall)
    : impl_(std::make_unique<Impl>(params, wall)) {}

DriveModel::~DriveModel() = default;

DriveModelState DriveModel::initialState(const StartPose& start, std::int64_t t_ns) const {
  const Impl& m = *impl_;
  auto data = std::make_unique<Impl::Data>(m.wheels.size(), m.delay_substeps, m.p.max_steering_rate_radps);
  data->backend = m.p.contact_backend;
  data->simbody = m.model_state;
  data->start_pose = m.restingPose(Transform(Rotation(start.yaw_rad, ZAxis), Vec3(start.x_m, start.y_m, 0)));
  m.chassis.setQToFitTransform(data->simbody, data->start_pose);
  data->scratch.mobility_forces.resize(data->simbody.getNU());
  data->scratch.body_forces.resize(m.matter.getNumBodies());
  data->scratch.qdot.resize(data->simbody.getNQ());
  m.system.realize(data->simbody, Stage::Velocity);
  m.sample(*data);
  data->t_ns = t_ns;
  data->out.t_ns = t_ns;
  m.updateOutputs(*data);
  return DriveModelState(std::move(data));
}

DriveOutputs DriveModel::step(DriveModelState& state, const DriveInputs& inputs, std::int64_t t_ns,
                              std::int64_t dt_ns) const {
  const Impl& m = *impl_;
  Impl::Data& s = *state.data_;
  if (dt_ns <= 0) throw std::invalid_argument("DriveModel::step: dt_ns = " + std::to_string(dt_ns) + " (must be > 0)");
  if (t_ns != s.t_ns) {
    throw std::invalid_argument("DriveModel::step: t_ns = " + std::to_string(t_ns) + " but the state is at " +
                                std::to_string(s.t_ns));
  }
  if (s.wheel_count != m.wheels.size() || s.backend != m.p.contact_backend ||
      s.simbody.getSystemTopologyStageVersion() != m.system.getSystemTopologyCacheVersion()) {
    throw std::invalid_argument("DriveModel::step: the state was made by a model of another shape (" +
                                std::to_string(s.wheel_count) + " wheels, " + toString(s.backend) + " backend)");
  }
  if (const std::string why = checkInputs(m.p, inputs); !why.empty()) {
    throw std::invalid_argument("DriveModel::step: " + why);
  }
  s.targets = wheelTargets(m.p, inputs.command, s.targets);
  s.downforce_n = inputs.downforce_n;
  s.pf_m = Vec3(inputs.pf_x_m, inputs.pf_y_m, 0);
  s.held = inputs.held;

  // The samples are a function of (q, u), taken after every change of them (initialState,
  // substep) and copied with the state: a copied state (whose Simbody cache is empty) steps
  // exactly as the original once realized again.
  m.system.realize(s.simbody, Stage::Velocity);

  const auto substep_ns = static_cast<std::int64_t>(std::llround(m.p.substep_s * 1e9));
  const std::int64_t count = std::max<std::int64_t>(1, (dt_ns + substep_ns - 1) / substep_ns);
  const double h = static_cast<double>(dt_ns) * 1e-9 / static_cast<double>(count);
  for (std::int64_t k = 0; k < count; ++k) m.substep(s, h);

  s.t_ns = t_ns + dt_ns;
  s.out.t_ns = s.t_ns;
  m.updateOutputs(s);
  return s.out;
}

const DriveParams& DriveModel::params() const { return impl_->p; }

}  // namespace climbsim::drive
