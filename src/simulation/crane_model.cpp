#include "crane_twin/simulation/crane_model.hpp"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include "crane_twin/io/input_error.hpp"
#include "crane_twin/structure/geometric_stiffness.hpp"
#include "crane_twin/structure/modal_cache.hpp"

namespace crane_twin {

// P-delta (docs/model.md "Geometric stiffness"): K + K_G(N), N the members' axial forces under
// the self-weight and the static hanging load (end mass, hanging rope, trolley) at the scene's
// trolley radius. Refused when the structure buckles under it (K + K_G not positive definite).
// `st`: the model's structure without any K_G, its own copy, which becomes the model's.
void addGeometricStiffness(CraneModel& m, TowerCraneStructure st) {
  const double g = m.scene.gravity;
  const double hanging = m.hangingPointMass() + m.ropeMass() + m.trolleyMass();
  const Eigen::VectorXd f =
      selfWeightLoad(st, g) + st.pointForce(st.trolleyWeights(m.scene.trolley_radius),
                                            Eigen::Vector3d(0.0, 0.0, -hanging * g));
  m.structure_axial_forces = memberAxialForces(st, staticDisplacement(st, f));
  st.K = st.K + geometricStiffness(st, m.structure_axial_forces);
  Eigen::SimplicialLLT<SparseMatrix> llt(st.K);
  m.structure = std::make_shared<const TowerCraneStructure>(std::move(st));
  if (llt.info() != Eigen::Success) {
    throw InputError(
        m.scene.file +
        ": key 'structure.geometric_stiffness': the structure buckles "
        "under its own weight and the hanging load (K + K_G is not positive definite)");
  }
}

// The rope and the masses at its end from m.scene (docs/model.md "Reeving", "Hook block").
void setRopeAndLoad(CraneModel& m) {
  const Scene& scene = m.scene;
  const int n = scene.rope.falls;
  m.rope.mass_per_length = n * scene.rope.mass_per_length;
  m.rope.axial_stiffness = n * scene.rope.axial_stiffness;
  m.rope.bending_stiffness = scene.rope.bending ? n * scene.rope.bending_stiffness : 0.0;
  m.rope.breaking_force = n * scene.rope.breaking_force;
  m.rope.reeving_equivalent_length = scene.rope.reeving_length / n;
  m.end_mass = scene.payload_mass + (scene.hasRigging() ? 0.0 : scene.hookBlockMass());
  m.hook_mass = scene.hasRigging() ? scene.hookBlockMass() : 0.0;
  // The static strain at the rope's top, W / (n EA), W the hanging weight: beyond
  // kMaxStaticStrain no steel wire rope holds it (they break at 1 to 3 %), and the static
  // solve would fail or mean nothing.
  const double weight = (m.end_mass + m.hook_mass + m.ropeMass()) * scene.gravity;
  const double strain = weight / m.rope.axial_stiffness;
  if (!(strain <= kMaxStaticStrain)) {
    char what[512];
    std::snprintf(what, sizeof what,
                  "the hanging weight, %.4g N at the rope's top, stretches the rope by %.3g %% "
                  "(n EA = %.4g N on %d falls); no steel wire rope holds that (they break at 1 "
                  "to 3 %%): at most %g %% is taken (payload.mass, hook.mass, "
                  "rope.mass_per_length, rope.axial_stiffness, rope.falls and gravity set it)",
                  weight, 100.0 * strain, m.rope.axial_stiffness, n, 100.0 * kMaxStaticStrain);
    // (the key of the largest share of the weight)
    const double rope_mass = m.ropeMass();
    const char* key = scene.hookBlockMass() > std::max(scene.payload_mass, rope_mass) ? "hook.mass"
                      : rope_mass > scene.payload_mass ? "rope.mass_per_length"
                                                       : "payload.mass";
    throw InputError(scene.file + ": key '" + key + "': " + what);
  }
}

// The modes every simulation of the model needs (makeRopeSupport).
void computeStructureModes(CraneModel& m) {
  m.structure_modal_basis.reset();
  const Scene& sc = m.scene;
  if (!m.structure || sc.structure_model == StructureModel::rigid) return;
  if (sc.structure_modes >= m.structure->free_dofs) return;  // makeRopeSupport refuses it
  ModalOptions opt;
  opt.count = sc.structure_modes;
  m.structure_modal_basis =
      std::make_shared<const ModalBasis>(cachedLowestModes(m.structure->K, m.structure->M, opt));
}

// The hot spots' stresses as functions of the structure's coordinates (after the modes).
void computeHotSpots(CraneModel& m) {
  m.hot_spots.reset();
  const Scene& sc = m.scene;
  if (!m.structure || !sc.crane || sc.crane->hot_spots.empty() ||
      sc.structure_model == StructureModel::rigid) {
    return;
  }
  if (sc.structure_model == StructureModel::modal && !m.structure_modal_basis) return;
  const TowerCraneStructure& st = *m.structure;
  auto t = std::make_shared<HotSpotTable>();
  try {
    t->rows = hotSpotRows(st, sc.crane->hot_spots);
  } catch (const InputError& e) {
    throw InputError(sc.crane->file + ": key 'hot_spots': " + e.what());
  }
  const Eigen::VectorXd u_sw = staticDisplacement(st, selfWeightLoad(st, sc.gravity));
  const int n = static_cast<int>(t->rows.size());
  const bool modal = sc.structure_model == StructureModel::modal;
  t->self_weight.resize(n);
  t->per_coordinate.setZero(n, modal ? m.structure_modal_basis->phi.cols() : st.free_dofs);
  for (int i = 0; i < n; ++i) {
    const HotSpotRow& r = t->rows[i];
    t->self_weight(i) = r.stress(u_sw);
    for (const auto& [eq, c] : r.coefficients) {
      if (modal) {
        t->per_coordinate.row(i) += c * m.structure_modal_basis->phi.row(eq);
      } else {
        t->per_coordinate(i, eq) += c;
      }
    }
  }
  m.hot_spots = t;
}

CraneModel buildCraneModel(const Scene& scene) {
  CraneModel m;
  m.scene = scene;
  setRopeAndLoad(m);
  // Even a rigid structure needs the geometry (rail, jib tip, cab reference points); P-delta
  // (refused without a crane) takes the built structure as its own.
  if (scene.crane) {
    TowerCraneStructure st = TowerCraneStructure::build(*scene.crane);
    if (scene.structure_geometric_stiffness) {
      addGeometricStiffness(m, std::move(st));
    } else {
      m.structure = std::make_shared<const TowerCraneStructure>(std::move(st));
    }
  }
  computeStructureModes(m);
  computeHotSpots(m);
  return m;
}

CraneModel withScene(const CraneModel& model, const Scene& scene) {
  const Scene& o = model.scene;
  auto refuse = [&scene](const std::string& key, const std::string& what) {
    throw InputError(scene.file + ": key '" + key + "': " + what +
                     " differs from the running model's (a new model is built from the file)");
  };
  if (scene.crane_name != o.crane_name || scene.crane.has_value() != o.crane.has_value()) {
    refuse("crane", "the crane");
  }
  if (scene.structure_model != o.structure_model || scene.structure_modes != o.structure_modes ||
      scene.structure_geometric_stiffness != o.structure_geometric_stiffness) {
    refuse("structure", "the structure model");
  }
  const RopeSettings &r = scene.rope, &q = o.rope;
  if (r.model != q.model || r.elements != q.elements || r.falls != q.falls ||
      r.mass_per_length != q.mass_per_length || r.axial_stiffness != q.axial_stiffness ||
      r.bending != q.bending || r.bending_stiffness != q.bending_stiffness ||
      r.reeving_length != q.reeving_length || scene.hasRigging() != o.hasRigging()) {
    refuse("rope", "the rope's discretisation or section");
  }
  // The payload as the file's checks would take it (Scene's payload.mass, hook and ground).
  auto refuseMass = [&scene](const std::string& what) {
    throw InputError(scene.file + ": key 'payload.mass': " + what);
  };
  const double mass = scene.payload_mass;
  if (!std::isfinite(mass) || mass < 0.0) {
    refuseMass("must be a finite mass >= 0 [kg], got " + std::to_string(mass));
  }
  if (scene.hasRigging() && !(mass > 0.0)) {
    refuseMass("must be > 0 under a rigging (hook.rigging_length carries the payload)");
  }
  if (scene.ground && !(mass + scene.hookBlockMass() > 0.0)) {
    refuseMass("must be > 0 with ground: and no hook block (something must land)");
  }
  CraneModel m = model;
  m.scene = scene;
  setRopeAndLoad(m);
  if (scene.structure_geometric_stiffness) {
    TowerCraneStructure without = *m.structure;
    without.K = without.K - geometricStiffness(without, model.structure_axial_forces);
    addGeometricStiffness(m, std::move(without));
    computeStructureModes(m);  // K changed with the load
    computeHotSpots(m);
  }
  return m;
}

CraneModel withPayloadMass(const CraneModel& model, double payload_mass) {
  Scene s = model.scene;
  s.payload_mass = payload_mass;
  return withScene(model, s);
}

CraneModel withPayloadPickedUp(const CraneModel& model, const CraneDrives& drives,
                               double payload_mass) {
  Scene s = model.scene;
  s.payload_mass = payload_mass;
  if (s.crane) {
    s.slew_angle = drives.slewAngle();
    s.trolley_radius = drives.trolleyRadius();
    s.rope.length = drives.hoistLength();
  }
  s.initial_mode = InitialMode::equilibrium;
  s.swing_deg = 0.0;
  s.payload_velocity = Eigen::Vector3d::Zero();
  s.commands.clear();
  return withScene(model, s);
}

GeneralizedAlpha integratorFor(const Scene& sc) {
  return sc.integrator == IntegratorKind::newmark ? GeneralizedAlpha::newmark()
                                                  : GeneralizedAlpha::fromRhoInf(sc.rho_inf);
}

std::optional<GroundContact> groundContactOf(const CraneModel& m) {
  if (!m.scene.ground) return std::nullopt;
  const GroundSettings& g = *m.scene.ground;
  GroundContactParameters p;
  p.height = g.height;
  p.stiffness = g.stiffness;
  p.damping = groundDamping(g.stiffness, m.end_mass, g.damping_ratio);
  p.friction = g.friction;
  p.payload_height = m.scene.payload_height;
  return GroundContact(p);
}

}  // namespace crane_twin
