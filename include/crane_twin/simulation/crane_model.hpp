// Constant model description built from a scene (Pinocchio's Model): the structure mesh and
// its matrices (when the scene has a crane), the rope discretisation data, and the masses at
// the rope end. Everything a simulation mutates lives elsewhere.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "crane_twin/drives/crane_drives.hpp"
#include "crane_twin/elements/ground_contact.hpp"
#include "crane_twin/integrators/generalized_alpha.hpp"
#include "crane_twin/io/scene.hpp"
#include "crane_twin/structure/hot_spot_stress.hpp"
#include "crane_twin/structure/modal_analysis.hpp"
#include "crane_twin/structure/tower_crane_structure.hpp"

namespace crane_twin {

/// Equivalent single cable of an n-fall reeving (docs/model.md): n EA, n EI and n times the mass
/// per metre of one fall.
struct EquivalentRope {
  double mass_per_length = 0.0;    ///< n mu [kg/m]
  double axial_stiffness = 0.0;    ///< n EA [N]
  double bending_stiffness = 0.0;  ///< n EI [N m^2] (0 when rope.bending is false)
  double breaking_force = 0.0;     ///< n F_break [N]
  /// The reeving's line L_r as hanging length of the equivalent cable, L_r / n [m]
  /// (docs/model.md "Reeving").
  double reeving_equivalent_length = 0.0;
  /// Axial stiffness of the hanging equivalent cable of length L [m] with the reeving's line in
  /// series, n EA L / (L + L_r / n) [N]: the hook's axial stiffness n EA / (L + L_r / n).
  double axialStiffnessAt(double L) const {
    return axial_stiffness * L / (L + reeving_equivalent_length);
  }
};

/// The crane's hot-spot stresses as a run reads them (docs/fatigue.md): sigma = sigma_sw +
/// S_z z, z the structure's coordinates (modal: S Phi; full: S), sigma_sw under the self-weight
/// (the state the structure's dynamics runs about, docs/model.md).
struct HotSpotTable {
  std::vector<HotSpotRow> rows;
  Eigen::VectorXd self_weight;     ///< [Pa], one per hot spot
  Eigen::MatrixXd per_coordinate;  ///< S_z [Pa per coordinate], hot spots x coordinates
  /// sigma for the structure's coordinates z [Pa].
  Eigen::VectorXd stresses(const Eigen::VectorXd& z) const {
    return self_weight + per_coordinate * z;
  }
};

struct CraneModel {
  Scene scene;
  /// Built unless crane: none; constant and shared by the model's copies (each simulation and
  /// forecaster holds a copy of the model: the structure's matrices are not copied with it).
  std::shared_ptr<const TowerCraneStructure> structure;
  EquivalentRope rope;
  double end_mass = 0.0;  ///< at the chain's end node [kg]: payload + hook block, or the payload
                          ///< alone under a rigging
  double hook_mass =
      0.0;  ///< with a rigging (hook.rigging_length): the hook block at the hoist rope's end [kg]
  /// Point masses the hoist rope carries [kg]: payload and hook block.
  double hangingPointMass() const { return end_mass + hook_mass; }
  /// With structure.geometric_stiffness: each member's axial force under the self-weight and
  /// the static hanging load [N] (tension positive); structure->K then holds K + K_G.
  Eigen::VectorXd structure_axial_forces;
  /// The structure.modes lowest modes of (K, M) for structure.model modal or full (empty for
  /// rigid, or when structure.modes is not below the structure's DOF): computed once here, not
  /// by every simulation of the model (a twin's load change, a forecaster), and shared by
  /// copies of the model.
  std::shared_ptr<const ModalBasis> structure_modal_basis;
  /// The crane file's hot spots with a flexible structure (modal or full; empty otherwise).
  std::shared_ptr<const HotSpotTable> hot_spots;

  /// Rope DOF count of the ANCF discretisation: 6 per node, and the payload point's 3 with a
  /// rigging (AncfRope).
  int ropeDofs() const { return 6 * (scene.rope.elements + 1) + (scene.hasRigging() ? 3 : 0); }
  /// Total rope mass of the hanging length [kg].
  double ropeMass() const { return rope.mass_per_length * scene.rope.length; }
  /// Mass that moves with the trolley point [kg] (0 without a crane): the trolley, and the
  /// reeving's line mu L_r, which the jib carries (docs/model.md "Reeving").
  double trolleyMass() const {
    return scene.crane
               ? scene.crane->trolley_mass + scene.rope.mass_per_length * scene.rope.reeving_length
               : 0.0;
  }
  /// The hot spots' stresses for the structure's coordinates z [Pa] (docs/fatigue.md:
  /// sigma = sigma_sw + S_z z), empty without hot spots.
  Eigen::VectorXd hotSpotStresses(const Eigen::VectorXd& z) const {
    return hot_spots ? hot_spots->stresses(z) : Eigen::VectorXd();
  }
  /// Gravity (0, 0, -g) [m/s^2].
  Eigen::Vector3d gravityVector() const { return Eigen::Vector3d(0.0, 0.0, -scene.gravity); }
};

/// The largest static strain at the rope's top a model is built for, W / (n EA) with W the
/// hanging weight (end mass, hook block and hanging rope): several times the strain a steel
/// wire rope breaks at (1 to 3 %); beyond it the scene is refused naming the key of the
/// largest share of the weight (payload.mass, hook.mass or rope.mass_per_length).
constexpr double kMaxStaticStrain = 0.1;

/// The model of a scene: the crane's structure (its modes and hot spots), the equivalent rope
/// and the masses at its end. Throws InputError naming the key for a structure that buckles
/// (structure.geometric_stiffness) and for a hanging weight beyond kMaxStaticStrain.
CraneModel buildCraneModel(const Scene& scene);

/// The model of `scene`, which differs from model.scene only in its load, pose, initial state
/// and commands (payload.mass, trolley.radius, slewing.angle, rope.length, initial.*,
/// commands): the structure's matrices are reused, not rebuilt, and with
/// structure.geometric_stiffness K_G is recomputed for the new hanging load
/// (K + K_G(N_new) = (K + K_G(N_old)) - K_G(N_old) + K_G(N_new), K_G linear in N).
/// Throws InputError naming the key for another crane, structure or rope discretisation, a
/// payload.mass that is not finite and >= 0 (> 0 under a rigging, or with `ground:` and no hook
/// block), and what buildCraneModel refuses.
CraneModel withScene(const CraneModel& model, const Scene& scene);

/// The model with another payload mass [kg] (a load picked up, or the twin's estimate of it;
/// docs/twin.md "Picks and set-downs"), everything else kept, payload.height included.
/// Throws what withScene throws (payload.mass named).
CraneModel withPayloadMass(const CraneModel& model, double payload_mass);

/// A new load of `payload_mass` [kg] picked up where the crane stands (the node's ~set_payload,
/// docs/ros.md "Changing the load"): the drives' slew angle, trolley radius and hoist length as
/// the scene's pose, the load hanging at rest (initial.mode equilibrium, no swing, no
/// commands), everything else kept. Throws what withScene throws.
CraneModel withPayloadPickedUp(const CraneModel& model, const CraneDrives& drives,
                               double payload_mass);

/// The scene's ground under the payload (docs/model.md "Ground contact"): `ground:`'s height,
/// stiffness and friction, the payload's height (payload.height), and the damper
/// c = 2 zeta sqrt(k m) for the mass that lands, m = end_mass (payload and hook block, or the
/// payload alone on a rigging). Empty without `ground:`.
std::optional<GroundContact> groundContactOf(const CraneModel& model);

/// The scene's integrator (generalized_alpha with its rho_inf, or newmark; docs/scenes.md).
GeneralizedAlpha integratorFor(const Scene& scene);

}  // namespace crane_twin
