// What the CLI, the sweep and the ROS node need of a running scene, whichever model integrates
// it (the full-order ANCF rope, the reduced rope or the pendulum rope): step it, read the output
// quantities of docs/cli.md, write the CSV rows.
#pragma once

#include <Eigen/Dense>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace crane_twin {

struct CraneModel;
struct Scene;
struct CommandEntry;
struct CoupledState;
class CraneDrives;
class RopeSupport;

/// One row of the docs/cli.md time series.
struct SeriesValues {
  double t = 0.0;
  Eigen::Vector3d payload = Eigen::Vector3d::Zero(), payload_velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d cab = Eigen::Vector3d::Zero(), jib_tip = Eigen::Vector3d::Zero();
  Eigen::Vector3d trolley = Eigen::Vector3d::Zero();
  double rope_top_tension = 0.0, rope_length = 0.0, slew_angle = 0.0, trolley_radius = 0.0;
  double energy = 0.0, constraint_error = 0.0;
  int subdomains = 0;
  // Beyond the columns of the paper scenes: the physical warnings a crane engineer expects.
  double tension_ratio = 0.0;     ///< rope top tension / breaking force of all falls
  double wind_3s = 0.0;           ///< 3 s mean wind speed at the jib's height [m/s] (0: none)
  double load_chart_ratio = 0.0;  ///< payload / allowed load at the current radius (0: no crane)
  int warnings = 0;               ///< bit set of Warning
  long full_order_steps = 0;      ///< reduced rope: steps integrated at full order so far
  // The ground (docs/model.md "Ground contact"; 0 without `ground:`).
  bool payload_landed = false;  ///< the payload presses on the ground (contact_force > 0)
  double contact_force = 0.0;   ///< the ground's normal force on the payload [N]
  /// The crane file's hot spots' normal stresses [Pa, tension positive] (docs/fatigue.md;
  /// empty without hot spots or with a rigid structure), in CraneModel::hot_spots' order.
  std::vector<double> stresses;
};

/// Bits of SeriesValues::warnings.
enum Warning : int {
  kTensionOverBreakingForce = 1,      ///< tension_ratio > 1
  kOutsideLoadChart = 2,              ///< load_chart_ratio > 1
  kRopeLengthAtLimit = 4,             ///< the hoist is braking for or holding at a length limit
  kTrolleyAtLimit = 8,                ///< the trolley is braking for or holding at a radius limit
  kCommandLimited = 16,               ///< a command above a drive's speed limit was limited
  kTensionOverWorkingLoadLimit = 32,  ///< tension_ratio > 1 / rope.safety_factor
  kWindOverInServiceLimit = 64,  ///< 3 s mean wind at the jib's height above wind.in_service_limit
  kLiftOffOverDesignFactor = 128,  ///< a lift-off's dynamic factor above hoist.design_phi2
  kLastWarning = kLiftOffOverDesignFactor,
};
/// Human-readable name of one warning bit.
const char* warningName(int bit);

/// docs/cli.md time-series columns, in order (without the stress_ columns).
extern const char* const kSeriesHeader;
/// The header of a run of `model`: kSeriesHeader, then stress_<name> per hot spot.
std::string seriesHeader(const CraneModel& model);
void writeSeriesRow(std::ostream& out, const SeriesValues& v);

/// What a run counts (docs/cli.md, the summary line); zero where a model has no such thing.
struct RunStatistics {
  /// The subdomain reduction (rope.reduction: subdomains) alone: subdomains started and wall
  /// time in rope mode updates [s]; 0 for every other model.
  int subdomains = 0;
  double mode_update_seconds = 0.0;
  long halved_steps = 0;  ///< steps taken as halves because Newton failed at the full step
  /// Energy-consistent steps of a tension-only ANCF rope across slack/taut switches
  /// (FullOrderSolver::step).
  long energy_consistent_steps = 0;
  /// Reduced rope: hand-overs to full order so far, the steps integrated at full order, and
  /// whether the current step runs at full order.
  long hand_overs = 0;
  /// Speculative hand-backs taken back and re-integrated at full order (docs/model.md
  /// "Hand-over to full order").
  long hand_backs_taken_back = 0;
  long full_order_steps = 0;
  bool integrating_full_order = false;
  /// Reduced rope: the times it added a state's shapes to its basis, at an error indicator's
  /// miss or a hand-back (InvariantReducedSimulation::kMaxAddedShapes).
  long basis_additions = 0;
};

class Simulation {
 public:
  virtual ~Simulation() = default;
  /// Build the initial state of docs/scenes.md (t = 0).
  virtual void initialize() = 0;
  /// One time step. Throws NumericalFailure.
  virtual void step() = 0;
  virtual double time() const = 0;
  virtual SeriesValues series() const = 0;
  /// The rope's top tension now [N], series().rope_top_tension without the rest of the row
  /// (cheap enough for every step: StepTensionPeak, for the lift-off factor and the warnings).
  virtual double topTension() const = 0;
  /// The crane file's hot spots' stresses now [Pa], series().stresses without the rest of the
  /// row (cheap enough for every step: the usage count's rainflow, docs/fatigue.md "Usage");
  /// empty without hot spots.
  virtual Eigen::VectorXd hotSpotStresses() const = 0;
  /// Payload position and the cab / jib-tip displacements, without the energy and tension
  /// series() computes (cheap enough to sample every few steps).
  virtual void sample(Eigen::Vector3d& payload, Eigen::Vector3d& cab,
                      Eigen::Vector3d& jib_tip) const = 0;
  virtual int ropeNodes() const = 0;
  virtual Eigen::Vector3d ropeNode(int j) const = 0;
  /// The rope node of the hook block: the chain's last (the payload's) unless the payload hangs
  /// on a rigging under it (docs/model.md "Hook block").
  virtual int hookNode() const { return ropeNodes() - 1; }
  /// Operator command from now on, overriding the scene's schedule (the node-facing API,
  /// docs/model.md "Drives"). Throws std::invalid_argument for a non-finite value and InputError
  /// for what is not built; the state is unchanged then.
  virtual void setCommand(const CommandEntry& command) = 0;
  /// The state in the rope model's own full coordinates (ANCF q, or the pendulum's two points;
  /// the reduced model expands its own: O(n r)) and the support's coordinates z.
  virtual CoupledState fullState() const = 0;
  /// fullState().q read as 3-vectors: true where a block is a point, false for a slope. Default
  /// ANCF's 6 per node (point, slope) on ropeNodes(); the pendulum's are all points; a rigging
  /// adds the payload's point after the hoist rope's nodes (AncfRope).
  virtual std::vector<bool> fullStatePositionBlocks() const;
  /// The drives' state (slewing angle, trolley radius, hoist length, speeds, flags).
  virtual const CraneDrives& drives() const = 0;
  /// What holds the rope (structure, rigid trolley point or anchor).
  virtual const RopeSupport& support() const = 0;
  /// Points along the deformed rope, top to end: per_element points per element of the model
  /// (interpolated with its shape functions), then the end point [m, world frame].
  virtual std::vector<Eigen::Vector3d> ropeCurve(int per_element) const = 0;
  /// What the run has counted so far (the summary line, the node's diagnostics).
  virtual RunStatistics statistics() const = 0;

 protected:
  /// CorrectableMotion::setMotion's size check (simulation_capabilities.hpp):
  /// std::invalid_argument unless m's q, v, z, zd have the sizes of the
  /// model's full state `like`.
  static void checkMotionSizes(const CoupledState& m, const CoupledState& like);

 public:
  /// `t,node,x,y,z` rows for every rope node.
  void writeNodeRows(std::ostream& out) const;
};

/// The rope model a scene runs (the one rule; makeSimulation and crane_sim info read it).
enum class RopeModelKind { full, invariant_reduced, subdomain_reduced, pendulum };
/// rope.model full -> full; reduced -> invariant_reduced, or subdomain_reduced with
/// rope.reduction: subdomains, or full where a hook rigging hangs under the block (the reduced
/// ropes' bases carry no rigging yet: docs/model.md "Hook block"); pendulum -> pendulum.
RopeModelKind ropeModelOf(const Scene& scene);
/// The rope coordinates a run of the scene integrates (the reduced ropes' basis size, the
/// pendulum's points, or the ANCF rope's).
int integratedRopeCoordinates(const CraneModel& model);

/// The simulation the scene's rope.model asks for (CraneSimulation for full,
/// InvariantReducedSimulation for reduced, SubdomainReducedSimulation for reduced with
/// rope.reduction: subdomains, PendulumCraneSimulation for pendulum). Throws InputError.
std::unique_ptr<Simulation> makeSimulation(const CraneModel& model);

/// A simulation of `model` that continues `from` (ContinuableRun::continueFrom): its state, drives
/// and time, now with model's loads. For a load that changes in a running twin
/// (withPayloadMass; docs/twin.md "Picks and set-downs"): the rope, stretched for the old load,
/// takes the new one from this step on. Throws InputError where `from`'s model cannot continue
/// (the subdomain reduced rope; another rope model or discretisation).
std::unique_ptr<Simulation> continueWithModel(const CraneModel& model, const Simulation& from);

}  // namespace crane_twin
