// Scene files (docs/scenes.md): what to simulate and which effects to include. Every key is
// validated on load; a wrong type, a value out of range, an unknown key or a missing file raises an
// InputError naming the file and the dotted key.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "crane_twin/io/crane_description.hpp"
#include "crane_twin/loads/wind_field.hpp"

namespace crane_twin {

/// The model choices of a scene file (docs/scenes.md), parsed once when it is read; name()
/// gives the file's word for each.
enum class RopeModel { pendulum, full, reduced };
enum class RopeReduction { invariant, subdomains };  ///< reduced rope: the basis
enum class StructureModel { rigid, modal, full };
enum class InitialMode { equilibrium, stress_free, landed };
enum class IntegratorKind { generalized_alpha, newmark };
enum class SlewDriveModel { kinematic, torque };
const char* name(RopeModel m);
const char* name(RopeReduction r);
const char* name(StructureModel m);
const char* name(InitialMode m);
const char* name(IntegratorKind i);
const char* name(SlewDriveModel m);

/// One entry of the operator command schedule, held until the next entry.
struct CommandEntry {
  double t = 0.0;
  double slew_rate = 0.0;      ///< rad/s
  double trolley_speed = 0.0;  ///< m/s, positive outwards
  double hoist_speed = 0.0;    ///< m/s of hanging length, positive lowers the load
};

struct RopeSettings {
  RopeModel model = RopeModel::reduced;
  RopeReduction reduction = RopeReduction::invariant;
  int elements = 120;
  double length = 60.0;  ///< hanging length at t = 0 [m]
  int falls = 2;
  bool bending = true;
  double mode_fraction = 0.5;
  int mode_count = 0;                     ///< > 0 overrides mode_fraction
  double subdomain_delta = 0.05;          ///< [m]
  std::string mode_update = "warm";       ///< cold | warm (SubdomainSettings)
  double subdomain_residual = 0.0;        ///< [N] > 0: adaptive subdomains (SubdomainSettings)
  std::string subdomain_frame = "fixed";  ///< fixed | corotational (SubdomainSettings)
  double subdomain_rotation = 0.1;        ///< [rad] corotational: chord rotation per subdomain
  double damping = 0.0;                   ///< stiffness-proportional axial damping coefficient [s]
  double mass_per_length = 1.9;           ///< per fall [kg/m]
  double axial_stiffness = 2.2e7;         ///< EA per fall [N]
  double bending_stiffness = 78.5;        ///< EI per fall [N m^2]
  double breaking_force = 345e3;          ///< per fall [N]
  bool tension_only = true;               ///< no axial force in compression (docs/scenes.md)
  double safety_factor = 5.0;             ///< working load limit = breaking_force / safety_factor
  /// Single line in tension between the winch drum and the falls [m] (docs/model.md "Reeving").
  double reeving_length = 0.0;
};

/// `slewing.drive` (docs/scenes.md): kinematic (the angle follows the ramped rate command) or a
/// torque-limited drive through a torsional gear (SlewTorqueDrive).
struct SlewDriveSettings {
  SlewDriveModel model = SlewDriveModel::kinematic;
  double max_torque = 0.0;  ///< torque: gear torque limit [N m]
  double stiffness = 0.0;   ///< torque: gear stiffness at the ring [N m/rad], 0: rigid
  double damping = 0.0;     ///< torque: gear damping [N m s/rad]
};

/// `ground:` (docs/scenes.md, docs/model.md "Ground contact"): a horizontal landing surface under
/// the payload.
struct GroundSettings {
  double height = 0.0;         ///< world z of the surface [m]
  double stiffness = 1e8;      ///< contact spring k [N/m]
  double damping_ratio = 1.0;  ///< of the landing mass on k: c = 2 zeta sqrt(k m) [-]
  double friction = 0.5;       ///< Coulomb coefficient mu [-]
};

struct Scene {
  std::string file;
  std::string crane_name = "none";
  std::optional<CraneDescription> crane;  ///< empty with crane: none
  Eigen::Vector3d anchor = Eigen::Vector3d::Zero();
  double duration = 20.0;
  double time_step = 0.001;
  double output_interval = 0.01;
  IntegratorKind integrator = IntegratorKind::generalized_alpha;
  double rho_inf = 0.9;
  StructureModel structure_model = StructureModel::modal;
  int structure_modes = 100;
  double structure_damping_ratio = 0.01;
  bool structure_geometric_stiffness = false;  ///< P-delta under self-weight (docs/model.md)
  RopeSettings rope;
  double payload_mass = 3600.0;
  /// `payload.height`: from the point that carries the payload's mass down to the load's
  /// underside [m] (default the boxes docs/ros.md draws: loads/load_geometry.hpp).
  double payload_height = 0.0;
  double trolley_radius = 80.0;
  double slew_angle = 0.0;
  bool slew_inertial_loads = false;  ///< default: on when the structure is flexible
  SlewDriveSettings slew_drive;
  InitialMode initial_mode = InitialMode::equilibrium;
  /// `initial.payload_offset` (landed): the payload's horizontal offset from under the rope's
  /// top [m].
  Eigen::Vector2d payload_offset = Eigen::Vector2d::Zero();
  double swing_deg = 2.3;
  double swing_azimuth_deg = 0.0;
  Eigen::Vector3d payload_velocity = Eigen::Vector3d::Zero();
  double gravity = 9.81;
  /// `wind:` (docs/scenes.md; empty: no wind, until a measured wind arrives at the node).
  std::optional<WindSettings> wind;
  /// `hoist.design_phi2`: the dynamic factor phi_2 the crane is designed for (EN 13001-2); a
  /// lift-off above it sets warning bit 128 (0: no check).
  double hoist_design_phi2 = 0.0;
  /// `ground:` (empty: no ground, the payload can only hang).
  std::optional<GroundSettings> ground;
  std::vector<CommandEntry> commands;
  /// Where the crane stands on a site (docs/site.md): the mast foot [m] and the yaw about z
  /// [deg] of the crane's frame in the site frame. Places the ROS frames and the clearance
  /// monitor's parts; the simulation itself runs in the crane's frame.
  Eigen::Vector3d site_position = Eigen::Vector3d::Zero();
  double site_yaw_deg = 0.0;

  /// `hook: {mass, rigging_length}` (docs/model.md "Hook block"): the hook block's mass [kg]
  /// (default the crane file's, 0 with crane: none) and the rigging's unstretched length [m]
  /// from the hook to the payload (0: hook block and payload lumped at the rope's end).
  double hook_mass = 0.0;
  double hook_rigging_length = 0.0;

  /// Hook block mass [kg] (hook.mass).
  double hookBlockMass() const { return hook_mass; }
  /// The payload hangs on its own rigging under the hook block (a double pendulum).
  bool hasRigging() const { return hook_rigging_length > 0.0; }
};

/// `random_commands:` of a scene (docs/stability.md hard case): a seeded, reproducible schedule.
struct RandomCommandSpec {
  int seed = 0;
  double interval = 1.0;  ///< s between entries
  double fraction = 1.0;  ///< of each drive's speed limit, (0, 1]
  bool slew = true, trolley = true, hoist = false;
};

/// The schedule a RandomCommandSpec stands for over [0, duration).
std::vector<CommandEntry> randomCommandSchedule(const CraneDescription& crane,
                                                const RandomCommandSpec& spec, double duration);

/// Load a scene, apply `key.path=value` overrides, validate everything. The crane file named
/// by `crane:` is looked up as <scene dir>/../cranes/<name>.yaml, or taken as a path when it
/// ends in .yaml.
Scene loadScene(const std::string& path, const std::vector<std::string>& overrides = {});

}  // namespace crane_twin
