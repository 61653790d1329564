// The scaffolding every rope model of a scene shares (the ANCF rope at full order and the
// pendulum rope): the scene's support (a fixed anchor for crane: none, the T8036 structure rigid,
// modal or in full coordinates), the three drives, the initial state of docs/scenes.md
// (`initial.mode`: the held equilibrium or the stress-free straight rope, plus
// `initial.payload_velocity`) and the output row of docs/cli.md. A derived model supplies its
// rope: the straight and the static state, the consistent accelerations, where the end point
// sits in q, and the tension and energy of a state.
#pragma once

#include <memory>
#include <optional>

#include "crane_twin/drives/crane_drives.hpp"
#include "crane_twin/integrators/coupled_state.hpp"
#include "crane_twin/loads/wind_field.hpp"
#include "crane_twin/loads/wind_loads.hpp"
#include "crane_twin/rope/rope_support.hpp"
#include "crane_twin/simulation/crane_model.hpp"
#include "crane_twin/simulation/simulation.hpp"
#include "crane_twin/simulation/simulation_capabilities.hpp"

namespace crane_twin {

class SupportedRopeSimulation : public Simulation, public MeasuredWindInput {
 public:
  double time() const override { return state_.t; }
  SeriesValues series() const override { return seriesOf(state_); }
  double topTension() const override { return topTensionOf(state_); }
  Eigen::VectorXd hotSpotStresses() const override { return model_.hotSpotStresses(state_.z); }
  void sample(Eigen::Vector3d& payload, Eigen::Vector3d& cab,
              Eigen::Vector3d& jib_tip) const override;
  CoupledState fullState() const override { return state_; }
  /// Operator command from now on, overriding the scene's schedule (CraneDrives::setCommand).
  void setCommand(const CommandEntry& command) override { drives_.setCommand(command); }
  void setMeasuredWind(const Eigen::Vector3d& velocity) override;
  /// The wind (empty without `wind:` and before a measured wind).
  const std::optional<WindField>& wind() const { return wind_; }
  const CraneDrives& drives() const override { return drives_; }
  const RopeSupport& support() const override { return *support_; }
  RopeSupport& support() { return *support_; }
  const CraneModel& model() const { return model_; }
  /// The ground (empty without `ground:`).
  const std::optional<GroundContact>& ground() const { return ground_; }
  const CoupledState& state() const { return state_; }

  /// The output row of a state in this model's coordinates.
  SeriesValues seriesOf(const CoupledState& s) const;
  /// The row of a state whose rope part the caller evaluated itself (a reduced rope: payload,
  /// its velocity, top tension [N], mechanical energy [J], rope length [m]); s gives the
  /// support's coordinates and the top position.
  SeriesValues seriesWith(const CoupledState& s, const Eigen::Vector3d& payload,
                          const Eigen::Vector3d& payload_velocity, double tension, double energy,
                          double rope_length) const;
  /// The hoist drive's length less the rope lying on the load: what hangs [m] (docs/model.md
  /// "Ground contact").
  double hangingLength() const { return drives_.hoistLength() - piled_; }
  /// Rope lying on the landed load [m]: reeled in before the hanging rope shortens, added to
  /// while the hook rests on the load and the hoist pays out.
  double piledLength() const { return piled_; }
  /// Advance the drives by dt under the active command and move the support to their pose;
  /// false where nothing moved. z: the support's coordinates now (the caller's state: a reduced
  /// run integrates its own, not this run's state_), where the wind is taken.
  bool advanceDrives(double t, double dt, const Eigen::VectorXd& z);
  /// Static equilibrium of the scene (`initial.mode: equilibrium`: the chord at
  /// `initial.swing_deg`, azimuth `initial.swing_azimuth_deg`), the horizontal force on the end
  /// mass that holds it into *holding_force. With a ground, InputError naming rope.length where
  /// it puts the load's underside at or below the ground (checkRestsClearOfGround).
  CoupledState staticState(Eigen::Vector3d* holding_force = nullptr);

  /// After a step: the payload's position and velocity [m, m/s] and the rope's top tension [N].
  /// The hook rests on the landed load (rope paid out piles on it) from when the payload presses
  /// on the ground (the contact force of the output's `payload_landed`) and the rope carries
  /// less than its own weight and a tenth of the end mass's (kRestingLoadFraction), until the
  /// payload leaves the ground: the rope's axial ringing after a set-down does not take it off.
  /// No effect without `ground:`.
  void setHookResting(const Eigen::Vector3d& payload, const Eigen::Vector3d& payload_velocity,
                      double top_tension);
  static constexpr double kRestingLoadFraction = 0.1;
  /// The same point masses hang on the rope as in `other` (continueFrom restarts the
  /// generalized-alpha accelerations when they differ: a load changed, withPayloadMass).
  bool carriesTheLoadOf(const SupportedRopeSimulation& other) const {
    return model_.end_mass == other.model_.end_mass && model_.hook_mass == other.model_.hook_mass;
  }

 protected:
  /// Copies the model and builds its support (makeRopeSupport). Throws InputError.
  explicit SupportedRopeSimulation(const CraneModel& model);
  /// The drives' state of another run of the same scene, the support at their pose.
  void continueDrivesFrom(const SupportedRopeSimulation& other);
  /// Drives at their start, the support at the scene's pose at rest.
  void resetDrivesAndPose();
  /// The initial state of the scene at t = 0 (docs/scenes.md, `initial`), accelerations
  /// consistent. Call after resetDrivesAndPose().
  CoupledState sceneInitialState();
  /// `initial.mode: landed` (docs/scenes.md): the payload on the ground, the rope hanging
  /// straight to it unloaded, the rest of rope.length lying on the load. Throws InputError
  /// naming rope.length where the rope cannot reach.
  CoupledState landedState();
  /// The landed state with the structure at rest at z, the rope hung from its top there.
  CoupledState landedStateAt(const Eigen::VectorXd& z);
  /// The hoist rope's span from the top to the landed load's hook [m] and its direction `dir`.
  double landedSpan(const Eigen::Vector3d& top, Eigen::Vector3d& dir) const;
  /// Moves a landed state's structure to rest under what the rope's top exerts on it: passes of
  /// K_z dz = M_z z'' from the consistent accelerations, the rope hung again from the moved top,
  /// until the top's acceleration is under kBalancedTopAcceleration (at most kMaxBalancePasses).
  void balanceLandedStructure(CoupledState& s);
  static constexpr int kMaxBalancePasses = 40;
  static constexpr double kBalancedTopAcceleration = 1e-6;  ///< [m/s^2]
  /// InputError unless a start other than landed, its rope along `dir` from the top, hangs the
  /// load clear of the ground.
  void checkHangsClearOfGround(const Eigen::Vector3d& dir) const;
  /// The same for the equilibrium start's static state (stretched rope, deflected structure).
  void checkRestsClearOfGround(const CoupledState& s) const;

  /// Equilibrium with the chord at swing_rad from the vertical, azimuth az_rad (the solver's).
  virtual CoupledState swingEquilibrium(double swing_rad, double az_rad,
                                        Eigen::Vector3d* holding_force) = 0;
  /// The rope straight and unstretched from `top` along the unit direction `dir`, at rest.
  virtual Eigen::VectorXd straightRope(const Eigen::Vector3d& top,
                                       const Eigen::Vector3d& dir) const = 0;
  /// Set the hoist rope to the unstretched length that hangs straight down over `span` [m] at
  /// rest with its end unloaded (the payload resting on the ground; a rigging's hook block
  /// still on the rope), and return it (docs/scenes.md "initial.mode: landed").
  virtual double unloadedHangingLength(double span) = 0;
  /// That rope straight along `dir` from `top`, stretched by its own weight (and the hook
  /// block's on a rigging), at rest; a rigging below it.
  virtual Eigen::VectorXd unloadedHangingRope(const Eigen::Vector3d& top,
                                              const Eigen::Vector3d& dir) const = 0;
  virtual void initializeAccelerations(CoupledState& s) = 0;
  /// Index in q of the end point's x coordinate.
  virtual int endPointIndex() const = 0;
  virtual double topTensionOf(const CoupledState& s) const = 0;
  virtual double energyOf(const CoupledState& s) const = 0;
  virtual double ropeLength() const = 0;
  /// The rope's wind loads: per metre [N/m] and on the end point [N], crane frame.
  virtual void setRopeWind(const Eigen::Vector3d& per_length, const Eigen::Vector3d& end_force) = 0;
  /// Wind loads at time t on the rope, the payload and the structure (docs/model.md "Wind"),
  /// with the support at coordinates z (empty: at rest), and (record) the 3 s mean at the jib's
  /// height. No effect without wind.
  void updateWind(double t, const Eigen::VectorXd& z, bool record = true);
  /// No wind loads on the rope, the payload or the structure (a run without wind).
  void clearWindLoads();
  /// The support at pose (theta, radius), held there through the next step (a reset or a
  /// continued run: RopeSupport::setPoseStep with equal ends).
  void holdPose(double theta, double radius);

  const CraneModel model_;                     ///< own copy: callers may pass a temporary
  const std::optional<GroundContact> ground_;  ///< the scene's ground (the output's contact)
  double piled_ = 0.0;                         ///< rope lying on the landed load [m]
  bool hook_resting_ = false;  ///< the hook rests on the landed load (setHookResting)
  CraneDrives drives_;
  std::unique_ptr<RopeSupport> support_;
  CoupledState state_;
  std::optional<WindField> wind_;
  double wind_3s_ = 0.0;
  /// The structure's wind load patterns (structureWindPatterns) for the profile exponent
  /// wind_patterns_exponent_, given to the support; built once per exponent.
  std::optional<StructureWindPatterns> wind_patterns_;
  double wind_patterns_exponent_ = 0.0;
  Eigen::Vector3d wind_v_ = Eigen::Vector3d::Zero();  ///< v of the weights last set [m/s]
  bool structure_wind_stale_ = true;  ///< the wind changed since those weights were set
};

/// The height the wind's jib figures refer to [m]: the trolley rail's at the crane's largest
/// radius, or the anchor's without a crane (WindField's jib height).
double windJibHeight(const CraneModel& m);

/// The rope's support for a scene: FixedAnchor (crane: none: the anchor), RigidTrolleySupport
/// (structure.model: rigid), ModalStructureSupport or FullStructureSupport. Throws InputError
/// for slewing loads without a flexible structure and for too many structure modes.
std::unique_ptr<RopeSupport> makeRopeSupport(const CraneModel& model);

}  // namespace crane_twin
