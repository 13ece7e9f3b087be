#pragma once
/// @file
/// Parameters of the drive model (docs/design.md#models, docs/robot-files.md#default-values):
/// chassis, drive units, contact, actuators, numerics and the fall criteria. Plain values in SI
/// units. The robot file fills the robot's own values (params_from_robot.hpp); the rest keep the
/// documented defaults, each derived from the robot's values where a rule is given.
///
/// Frames. Wall frame W: origin on the wall surface, z along the wall normal pointing away
/// from the wall (the wall is the half-space z < 0). Robot frame R: origin at the body centre
/// in the sealing plane, z away from the wall, x through chamber 1.

#include <memory>
#include <string>
#include <vector>

namespace climbsim::drive {

class WheelGround;

/// What a drive unit does (the robot file's wheels[i].kind).
enum class WheelKind {
  /// Steered about R's z through the wheel's contact point by a servo, and driven.
  kSteerable,
  /// Driven, always rolling along R's x (differential or skid steering): no steering joint.
  kFixed,
  /// Passive: swivels freely about R's z at its mount (no steering torque, a small damping;
  /// the wheel trails the swivel axis by trail_m, so the contact's own friction turns it into
  /// its rolling direction) and spins freely (no drive torque).
  kCaster,
};

/// "steerable", "fixed" or "caster".
const char* toString(WheelKind kind);
/// Whether the unit's wheel has a drive motor (steerable or fixed).
inline bool isDriven(WheelKind kind) { return kind != WheelKind::kCaster; }

/// One drive unit: a steering joint about R's z through the mount (a pin; a weld for a fixed
/// wheel), and a wheel spinning about the steering body's y axis. Steering angle 0 rolls the
/// wheel along R's +x; a positive wheel speed rolls it forwards along its heading (cos δ, sin δ)
/// in R.
struct WheelMount {
  double x_m = 0.0;  ///< mount in R, x [m]: the contact point (a caster's: its swivel axis)
  double y_m = 0.0;  ///< mount in R, y [m]
  WheelKind kind = WheelKind::kSteerable;
  double radius_m = 0.05;              ///< wheel radius r_w [m], > 0
  double friction_coefficient = 0.7;   ///< μ of this wheel on the wall, > 0 (robot file)
  /// σ of the contact law (ContactParams) [m], > 0; default: the wheel radius.
  double relaxation_length_m = 0.05;
  /// Caster only: the wheel's centre trails the swivel axis by this along the steering
  /// body's -x [m], >= 0 (0 for the other kinds); default: the wheel radius.
  double trail_m = 0.0;
};

/// Compliant wheel-wall contact: Hertz normal force with Hunt-Crossley dissipation,
///   N = (4/3) E sqrt(r_w) x^(3/2) (1 + 1.5 c xdot)   (x: penetration [m], N >= 0),
/// and elasto-plastic "bristle" friction with rolling relaxation (Pacejka's transient
/// single-contact model; r_w, μ and σ are each wheel's, WheelMount): a tangential deflection
/// z (in the wall plane) with
///   dz/dt = v_slip - (|ω| r_w / σ) z,   |k_t z| <= μ N   (beyond it the contact slides),
///   F_t = -(k_t z + c_t v_slip), limited to |F_t| <= μ N.
/// At rest (ω = 0, v_slip = 0) z holds: static friction without creep. Rolling at wheel
/// speed ω with traction F needs the slip velocity F |ω| r_w / (k_t σ) (rolling creep).
struct ContactParams {
  /// E of the Hertz law [Pa], > 0. Default: 1 mm penetration under the desired downforce
  /// shared by the wheels, for the smallest wheel (params_from_robot.hpp).
  double hertz_modulus_pa = 8.0e7;
  double dissipation_spm = 2.0;            ///< Hunt-Crossley c [s/m], >= 0
  double tangential_stiffness_npm = 2.0e5; ///< k_t [N/m], > 0
  double tangential_damping_nspm = 1.5e3;  ///< c_t [N s/m], >= 0
};

/// How the drive model computes its applied forces and accelerations. Both take the same
/// bodies, contact law (contact_law.hpp), servos, shaping, integration and outputs; they give
/// the same trajectories to round-off (tests/unit/drive/drive_backends_test.cpp).
enum class ContactBackend {
  /// The model computes gravity, the sphere/half-space wheel contacts, the servos, the
  /// adhesion and the sealing drag itself from Simbody's kinematics and gets udot from the
  /// articulated-body operator. The default: Simbody's contact and force bookkeeping cost
  /// more than the physics (climbsim-bench-drive prints the ratio).
  kDirect,
  /// Simbody does it: ContactTrackerSubsystem and CompliantContactSubsystem find each wheel's
  /// sphere against the wall's half-space and a ContactForceGenerator answers with the law;
  /// the other forces are Simbody force elements; udot from realizing Stage::Acceleration
  /// (simbody_contact_forces.hpp). The reference the direct backend is held to.
  kSimbody,
};

/// "direct" or "simbody".
const char* toString(ContactBackend backend);
/// "direct" or "simbody"; ConfigError naming `what` otherwise.
ContactBackend parseContactBackend(const std::string& what, const std::string& text);

/// PD servo with a torque limit: τ = clamp(kp (q_ref - q) + kd (qdot_ref - qdot), ±τ_max).
struct ServoParams {
  double kp_nmprad = 0.0;     ///< > 0
  double kd_nmsprad = 0.0;    ///< >= 0
  double torque_max_nm = 0.0; ///< > 0
};

/// Everything the drive model needs. validateDriveParams() before use (DriveModel does).
struct DriveParams {
  // --- chassis and drive units
  double mass_kg = 45.0;                 ///< total mass of the robot, > 0
  double com_height_m = 0.15;            ///< centre of mass above the wall (along R's z), > 0
  /// Farthest point of the body outline from R's origin [m], > 0: bounds the wheels and
  /// P_F, and is the lever of the sealing drag's yaw torque.
  double body_radius_m = 0.40;
  /// Principal moments of the chassis (without the drive units) about its own centre of
  /// mass, R's axes [kg m^2], > 0. Default (params_from_robot.hpp) with the chassis mass m_c
  /// and thickness t = 2 com_height_m: a circular body of radius R a uniform disc,
  /// Ixx = Iyy = m_c (R²/4 + t²/12), Izz = m_c R²/2; a rectangular body of length L (x) and
  /// width B (y) a uniform box, Ixx = m_c (B² + t²)/12, Iyy = m_c (L² + t²)/12,
  /// Izz = m_c (L² + B²)/12.
  double inertia_xx_kgm2 = 0.0;
  double inertia_yy_kgm2 = 0.0;
  double inertia_zz_kgm2 = 0.0;
  std::vector<WheelMount> wheels;        ///< 1..8 units, in robot-file order
  /// Mass of one drive unit (steering body + wheel, half each) as a fraction of mass_kg;
  /// the chassis carries the rest. (0, 0.5 / wheel count).
  double unit_mass_fraction = 0.04;
  /// Inertia about the wheel axle [kg m^2], > 0: the gear motor's rotor reflected through
  /// the gear (about 1e-5 kg m² x 50²) dominates the wheel's own m r²/2.
  double wheel_spin_inertia_kgm2 = 0.02;
  /// Inertia about the steering axis [kg m^2], > 0: the steering motor reflected as above.
  double steering_inertia_kgm2 = 0.01;
  /// A caster's inertia about its axle and about its swivel axis [kg m^2], > 0: no motor, but
  /// enough that the contact's bristle damping (c_t r² and c_t trail² over it) stays below
  /// 2 / substep_s for the explicit substep.
  double caster_inertia_kgm2 = 2.0e-3;
  /// A caster's swivel damping [N m s/rad], >= 0: τ = -c δ̇ (no steering servo).
  double caster_damping_nmsprad = 0.05;

  ContactParams contact;
  /// Who computes the forces (ContactBackend); not from the robot file.
  ContactBackend contact_backend = ContactBackend::kDirect;
  /// What the wheels stand on (wheel_ground.hpp): the scene's surface; null: the wall plane
  /// z_W = 0. Not from the robot file: the scenario's scene (configure.hpp). The simbody
  /// backend always uses the wall plane.
  std::shared_ptr<const WheelGround> ground;
  /// Length of the tyre's contact patch [m]: the chord 2 sqrt(2 r delta_0) of the smallest
  /// wheel at the nominal penetration delta_0 (1 mm under the desired downforce shared by the
  /// wheels, ContactParams). The scene's surface under the wheels is enveloped over a square
  /// patch of this side (climbsim/wall/surface_heights.hpp, docs/design.md#drive).
  double tyre_patch_m = 0.0;

  // --- actuators
  /// Wheel servo of every driven wheel on the integrated speed set-point (holds position at
  /// rest). Default torque limit: the friction-limited traction of one wheel under the desired
  /// downforce, μ F_desired r_w / wheel count (the largest over the driven wheels).
  ServoParams wheel_servo{500.0, 5.0, 25.0};
  ServoParams steering_servo{50.0, 2.0, 20.0};   ///< steering joint of a steerable wheel
  double max_steering_rate_radps = 1.5707963267948966;  ///< > 0 (robot file: 90 °/s)
  /// Dead time of every set-point (steering angle and wheel speed) [s], >= 0; rounded to
  /// whole substeps.
  double command_delay_s = 0.02;
  double max_speed_mps = 0.1;            ///< > 0: wheel surface speed limit (robot file)

  // --- sealing drag: the sealing slides on the wall with a friction proportional to the
  // downforce, D = sealing_drag_coefficient * F, opposing the body's motion along the wall
  // (regularised below drag_regularisation_mps so that the body at rest feels none), and a
  // yaw torque D * body_radius_m opposing rotation.
  double sealing_drag_coefficient = 0.03;     ///< >= 0
  double drag_regularisation_mps = 0.005;     ///< > 0

  // --- environment and numerics
  double gravity_mps2 = 9.81;                 ///< > 0; the direction is the wall's (WallOrientation)
  double substep_s = 0.001;                   ///< fixed integration step, (0, 0.01]

  // --- the robot has left the wall ("fell", latched) when, at the end of any substep:
  double fall_distance_m = 0.05;   ///< R's origin is farther than this from the wall plane, > 0
  double fall_contact_loss_s = 0.1;///< or no wheel has touched the wall for this long, > 0
  double fall_speed_mps = 1.0;     ///< or R's origin slides along the wall faster than this, > 0
};

/// One line naming the first invalid parameter and its value (empty: valid).
std::string checkDriveParams(const DriveParams& params);
/// Throws ConfigError("drive parameters: <why>") unless checkDriveParams is empty.
void validateDriveParams(const DriveParams& params);

/// Where gravity points for a wall of a given orientation.
struct WallOrientation {
  /// Gravity direction in W (unit vector); scaled by DriveParams::gravity_mps2.
  double gravity_x = 0.0;
  double gravity_y = -1.0;
  double gravity_z = 0.0;

  /// Vertical wall: W's y up, gravity -y.
  static WallOrientation vertical() { return {0.0, -1.0, 0.0}; }
  /// Horizontal floor: gravity -z (towards the wall).
  static WallOrientation floor() { return {0.0, 0.0, -1.0}; }
  /// A wall leaning `overhang_deg` beyond vertical about W's x: gravity (0, -cos a, sin a).
  /// 0 vertical, 90 ceiling, -90 floor; |a| <= 180.
  static WallOrientation overhang(double overhang_deg);
  /// "vertical", "floor", "ceiling" or "overhang:DEG"; ConfigError naming `what`.
  static WallOrientation parse(const std::string& what, const std::string& text);
};

/// Start pose of R on the wall: origin (x, y) in W on the wall surface, yaw about W's z
/// (R's x along (cos yaw, sin yaw, 0) in W).
struct StartPose {
  double x_m = 0.0;
  double y_m = 0.0;
  double yaw_rad = 0.0;
};

}  // namespace climbsim::drive
