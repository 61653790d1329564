#include "crane_twin/simulation/supported_rope_simulation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "crane_twin/integrators/newton_step.hpp"
#include "crane_twin/io/input_error.hpp"
#include "crane_twin/loads/wind_loads.hpp"
#include "crane_twin/rope/swing_direction.hpp"
#include "crane_twin/simulation/crane_warnings.hpp"
#include "crane_twin/structure/modal_cache.hpp"
#include "crane_twin/structure/structure_support.hpp"

namespace crane_twin {

std::unique_ptr<RopeSupport> makeRopeSupport(const CraneModel& model) {
  const Scene& sc = model.scene;
  if (sc.slew_inertial_loads && (!model.structure || sc.structure_model == StructureModel::rigid)) {
    throw InputError(
        sc.file +
        ": key 'slewing.inertial_loads': the inertial loads of slewing act "
        "on a flexible structure (structure.model: modal or full); this scene has " +
        (model.structure ? std::string("a rigid one") : std::string("none (crane: none)")));
  }
  if (!model.structure) return std::make_unique<FixedAnchor>(sc.anchor);
  const TowerCraneStructure& st = *model.structure;
  const double theta = sc.slew_angle;
  if (sc.structure_model == StructureModel::rigid) {
    return std::make_unique<RigidTrolleySupport>(st, sc.trolley_radius, theta);
  }
  if (sc.structure_modes >= st.free_dofs) {
    throw InputError(sc.file + ": key 'structure.modes': must be below the structure's " +
                     std::to_string(st.free_dofs) + " DOF, got " +
                     std::to_string(sc.structure_modes));
  }
  // The model's modes (buildCraneModel), or computed here for a model built otherwise.
  std::shared_ptr<const ModalBasis> modes = model.structure_modal_basis;
  if (!modes) {
    ModalOptions opt;
    opt.count = sc.structure_modes;
    modes = std::make_shared<const ModalBasis>(cachedLowestModes(st.K, st.M, opt));
  }
  const ModalBasis& b = *modes;
  if (sc.structure_model == StructureModel::modal) {
    auto modal = std::make_unique<ModalStructureSupport>(st, b, sc.structure_damping_ratio,
                                                         sc.trolley_radius, theta);
    if (sc.slew_inertial_loads) modal->enableSlewingLoads();
    return modal;
  }
  // full: Rayleigh damping matched at the first and the structure.modes-th frequency (a single
  // mode gives no second frequency: match at 10 w1 then).
  const double w1 = std::sqrt(b.omega2(0));
  const double wk = b.omega2.size() > 1 ? std::sqrt(b.omega2(b.omega2.size() - 1)) : 10.0 * w1;
  auto full = std::make_unique<FullStructureSupport>(
      st, sc.structure_damping_ratio, w1, wk > w1 ? wk : 10.0 * w1, sc.trolley_radius, theta);
  if (sc.slew_inertial_loads) full->enableSlewingLoads();
  return full;
}

namespace {
// The rotating part's inertia for a torque slewing drive (0 otherwise: not needed).
double torqueDriveInertia(const CraneModel& m) {
  if (m.scene.slew_drive.model != SlewDriveModel::torque || !m.structure) return 0.0;
  return slewingInertia(*m.structure, m.trolleyMass(), m.scene.trolley_radius);
}
}  // namespace

// The height the wind's jib figures refer to: the trolley rail's, or the anchor's.
double windJibHeight(const CraneModel& m) {
  return m.structure ? trolleyPoint(*m.structure, m.scene.crane->max_radius).z()
                     : m.scene.anchor.z();
}

SupportedRopeSimulation::SupportedRopeSimulation(const CraneModel& model)
    : model_(model),
      ground_(groundContactOf(model_)),
      drives_(model_.scene, torqueDriveInertia(model_)),
      support_(makeRopeSupport(model_)) {
  if (model_.scene.wind) wind_.emplace(*model_.scene.wind, windJibHeight(model_));
}

void SupportedRopeSimulation::setMeasuredWind(const Eigen::Vector3d& v) {
  if (!v.allFinite()) throw std::invalid_argument("measured wind must be finite");
  if (!wind_) {
    if (!(windJibHeight(model_) > 0.0)) {
      throw InputError(model_.scene.file + ": a measured wind needs the anchor above the ground");
    }
    WindSettings w;
    w.payload_area = payloadCubeFaceArea(model_.scene.payload_mass);
    wind_.emplace(w, windJibHeight(model_));
  }
  wind_->setMeasured(v);
  structure_wind_stale_ = true;
}

// Rope and payload loads from the wind at the rope's mid-height and the payload's (the trolley
// point less half and all of the hanging length); the structure's from its members' load
// patterns, weighted at unit gust (g = 1) for the current slewing angle and mean wind, and
// scaled by g(t)^2 (u is proportional to g).
void SupportedRopeSimulation::updateWind(double t, const Eigen::VectorXd& z, bool record) {
  if (!wind_) return;
  const double top =
      (z.size() == support_->size() ? support_->point(z)
                                    : support_->point(Eigen::VectorXd::Zero(support_->size())))
          .z();
  const double L = drives_.hoistLength();
  const Scene& sc = model_.scene;
  setRopeWind(
      ropeWindLoad(*wind_, t, top - 0.5 * L, sc.rope.falls, ropeDiameter(sc.rope.mass_per_length)),
      payloadWindLoad(*wind_, t, top - L));
  if (model_.structure && support_->size() > 0) {
    // The load P w(v) of structureWindPatterns: the patterns once per profile, the weights
    // when the mean wind at the jib height in the slewing frame, v, changes (slewing, a new
    // measured wind); at unit gust (g = 1).
    const double jib = windJibHeight(model_);
    const double alpha = wind_->settings().profile_exponent;
    if (!wind_patterns_ || alpha != wind_patterns_exponent_) {
      wind_patterns_ = structureWindPatterns(*model_.structure, alpha, jib);
      wind_patterns_exponent_ = alpha;
      support_->setExternalLoadPatterns(wind_patterns_->patterns);
      structure_wind_stale_ = true;
    }
    const Eigen::Vector3d v =
        slewRotation(drives_.slewAngle()).transpose() * wind_->meanVelocity(jib);
    if (structure_wind_stale_ || v != wind_v_) {
      support_->setExternalLoadWeights(structureWindWeights(*wind_patterns_, v));
      wind_v_ = v;
      structure_wind_stale_ = false;
    }
    const double g = wind_->gustFactor(t);
    support_->setExternalLoadScale(g * g);
  }
  if (record) wind_3s_ = wind_->recordJibSpeed(t);
}

void SupportedRopeSimulation::resetDrivesAndPose() {
  const Scene& sc = model_.scene;
  drives_.reset();
  piled_ = 0.0;
  hook_resting_ = false;
  holdPose(sc.slew_angle, sc.trolley_radius);
  support_->setSlewMotion(0.0, 0.0);
  // A fresh 3 s history and no measurement: the scene's wind, or none.
  if (sc.wind) {
    wind_.emplace(*sc.wind, windJibHeight(model_));
  } else {
    wind_.reset();
    clearWindLoads();
  }
  structure_wind_stale_ = true;
  wind_3s_ = 0.0;
  updateWind(0.0, Eigen::VectorXd());
}

void SupportedRopeSimulation::clearWindLoads() {
  setRopeWind(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  support_->setExternalLoad(Eigen::VectorXd());
}

void SupportedRopeSimulation::continueDrivesFrom(const SupportedRopeSimulation& o) {
  drives_.assignStateFrom(o.drives_);
  piled_ = o.piled_;
  hook_resting_ = o.hook_resting_;
  holdPose(drives_.slewAngle(), drives_.trolleyRadius());
  support_->setSlewMotion(drives_.slewRate(), drives_.slewAcceleration());
  wind_ = o.wind_;
  wind_3s_ = o.wind_3s_;
  structure_wind_stale_ = true;
  if (!wind_) clearWindLoads();  // no wind there: none of this run's own loads stay
  updateWind(o.state_.t, o.state_.z, false);
}

void SupportedRopeSimulation::setHookResting(const Eigen::Vector3d& payload,
                                             const Eigen::Vector3d& payload_velocity,
                                             double top_tension) {
  if (!ground_) return;
  if (!(ground_->force(payload, payload_velocity).f.z() > 0.0)) {
    hook_resting_ = false;
    return;
  }
  const double g = model_.scene.gravity;
  const double unloaded =
      (model_.rope.mass_per_length * ropeLength() + kRestingLoadFraction * model_.end_mass) * g;
  if (top_tension <= unloaded) hook_resting_ = true;
}

void SupportedRopeSimulation::holdPose(double theta, double radius) {
  support_->setPose(theta, radius);
  support_->setPoseStep(theta, radius, theta, radius);
}

bool SupportedRopeSimulation::advanceDrives(double t, double dt, const Eigen::VectorXd& z) {
  const double before = drives_.hoistLength();
  const double theta0 = drives_.slewAngle(), radius0 = drives_.trolleyRadius();
  const bool moved = drives_.advance(t, dt);
  // Rope lying on the load (docs/model.md "Ground contact"): reeled in first; paid out onto it
  // while the hook rests there.
  const double paid = drives_.hoistLength() - before;
  if (paid < 0.0) piled_ = std::max(0.0, piled_ + paid);
  if (paid > 0.0 && hook_resting_) piled_ += paid;
  updateWind(t + dt, z);
  // (Equal ends where the drives did not move.)
  support_->setPoseStep(theta0, radius0, drives_.slewAngle(), drives_.trolleyRadius());
  if (!moved) return false;
  support_->setPose(drives_.slewAngle(), drives_.trolleyRadius());
  support_->setSlewMotion(drives_.slewRate(), drives_.slewAcceleration());
  return true;
}

CoupledState SupportedRopeSimulation::staticState(Eigen::Vector3d* holding_force) {
  const Scene& sc = model_.scene;
  const CoupledState s = swingEquilibrium(sc.swing_deg * M_PI / 180.0,
                                          sc.swing_azimuth_deg * M_PI / 180.0, holding_force);
  if (ground_) checkRestsClearOfGround(s);
  return s;
}

// docs/scenes.md "initial.mode: landed": the payload at rest on the ground at its static
// penetration, at payload_offset from under the rope's top; a rigging straight and unstretched
// above it; the hoist rope hanging straight from the top to the hook, stretched by its own
// weight with its end unloaded; what rope.length has beyond that lies on the load (piled_).
// The structure at rest under the force the rope's top exerts on it (balanceLandedStructure).
CoupledState SupportedRopeSimulation::landedState() {
  const Scene& sc = model_.scene;
  Eigen::VectorXd z = Eigen::VectorXd::Zero(support_->size());
  if (support_->size() > 0) {
    // First guess: the structure under what hangs from it, vertically (the trolley, the hanging
    // rope, and the hook block with half the rigging on a rigging): z = K_z^-1 D^T f. Two
    // passes: the hanging length depends on where the top sinks to.
    const double hook =
        sc.hasRigging() ? model_.hook_mass + 0.5 * sc.rope.mass_per_length * sc.hook_rigging_length
                        : 0.0;
    for (int pass = 0; pass < 2; ++pass) {
      Eigen::Vector3d dir;
      const double span = landedSpan(support_->point(z), dir);
      // A load above the top: landedStateAt names it, from this top. One out of the rope's reach
      // is named there too: what hangs is then at most the rope there is, not the rope the
      // span would take (a kilometre's weight sank the modal T8036's top by 96 m first).
      if (!(span > 0.0) || !(dir.z() < 0.0)) break;
      const double hanging = std::min(unloadedHangingLength(span), sc.rope.length);
      const double held = model_.trolleyMass() + model_.rope.mass_per_length * hanging + hook;
      support_->setIterationWeights(0.0, 0.0, 1.0);
      z = support_->solvePointForce(Eigen::Vector3d(0.0, 0.0, -held * sc.gravity));
    }
  }
  CoupledState s = landedStateAt(z);
  if (support_->size() > 0) balanceLandedStructure(s);
  return s;
}

// The hoist rope's span from the top to the landed load's hook [m], and its direction.
double SupportedRopeSimulation::landedSpan(const Eigen::Vector3d& top, Eigen::Vector3d& dir) const {
  const Scene& sc = model_.scene;
  const GroundContactParameters& g = ground_->parameters();
  const double sink = model_.end_mass * sc.gravity / g.stiffness;
  const Eigen::Vector3d end(top.x() + sc.payload_offset.x(), top.y() + sc.payload_offset.y(),
                            g.height + g.payload_height - sink);
  dir = (end - top).normalized();
  return (end - top).norm() - (sc.hasRigging() ? sc.hook_rigging_length : 0.0);
}

// The guess leaves the structure out of balance by what the rope's model carries at its top
// differently (a pendulum's bar puts half its weight on the landed end; an inclined rope pulls
// sideways): released, the structure's high modes ring and the top tension read through the
// top's acceleration jumps tenfold. So: from the consistent accelerations at the state, the
// static structure under the same forces, K_z dz = M_z z'', the rope hung again from the moved
// top, until the top's acceleration is below kBalancedTopAcceleration (each pass cuts it by
// about 3.6x on the T8036).
void SupportedRopeSimulation::balanceLandedStructure(CoupledState& s) {
  const Eigen::VectorXd rest = Eigen::VectorXd::Zero(s.z.size());
  for (int it = 0; it < kMaxBalancePasses; ++it) {
    s.t = 0.0;
    initializeAccelerations(s);
    if (support_->pointMotion(s.zdd).norm() < kBalancedTopAcceleration) return;
    const Eigen::VectorXd inertia =
        support_->internalForce(s.z, rest, s.zdd) - support_->internalForce(s.z, rest, rest);
    support_->setIterationWeights(0.0, 0.0, 1.0);
    s = landedStateAt(s.z + support_->solve(inertia));
  }
}

// The landed state with the structure at z (its velocity zero).
CoupledState SupportedRopeSimulation::landedStateAt(const Eigen::VectorXd& z) {
  const Scene& sc = model_.scene;
  CoupledState s;
  s.z = z;
  s.zd = Eigen::VectorXd::Zero(support_->size());
  const double L = sc.rope.length;
  const Eigen::Vector3d top = support_->point(s.z);
  Eigen::Vector3d dir;
  const double span = landedSpan(top, dir);
  if (!(dir.z() < 0.0)) {  // a rope hangs down from its top: the load must rest below it
    const GroundContactParameters& g = ground_->parameters();
    char b[400];
    std::snprintf(b, sizeof b,
                  ": key 'ground.height': %.4g m with payload.height %.4g m puts the landed "
                  "load's top (z = %.4g m) not below the rope's top (z = %.4g m): the rope "
                  "hangs down to the load (initial.mode: landed)",
                  g.height, g.payload_height, g.height + g.payload_height, top.z());
    throw InputError(sc.file + b);
  }
  const double hanging = span > 0.0 ? unloadedHangingLength(span) : 0.0;
  if (!(span > 0.0) || L < hanging) {
    char b[320];
    std::snprintf(b, sizeof b,
                  ": key 'rope.length': %.4g m does not reach from the rope's top (z = %.4g m) "
                  "to the landed load's hook, %.4g m away (%.4g m of rope hang there; "
                  "initial.mode: landed; ground.height, payload.height and the trolley set that "
                  "distance)",
                  L, top.z(), std::max(0.0, span), hanging);
    throw InputError(sc.file + b);
  }
  piled_ = L - hanging;
  hook_resting_ = true;
  s.q = unloadedHangingRope(top, dir);
  s.v = Eigen::VectorXd::Zero(s.q.size());
  return s;
}

// A hanging or released start with a ground: the unstretched rope (and rigging) from the
// undeformed top along the start's direction must leave the load's underside above the ground
// (stretch only lowers it): else the load would start inside the ground, or the static solve
// would press it there.
void SupportedRopeSimulation::checkHangsClearOfGround(const Eigen::Vector3d& dir) const {
  const Scene& sc = model_.scene;
  const GroundContactParameters& g = ground_->parameters();
  const Eigen::Vector3d top = support_->point(Eigen::VectorXd::Zero(support_->size()));
  const double reach = sc.rope.length + (sc.hasRigging() ? sc.hook_rigging_length : 0.0);
  const double underside = top.z() + reach * dir.z() - g.payload_height;
  if (underside > g.height) return;
  char b[400];
  std::snprintf(b, sizeof b,
                ": key 'rope.length': %.4g m of rope from the rope's top (z = %.4g m) puts the "
                "load's underside at z = %.4g m, %.4g m below ground.height %.4g m, before the "
                "rope stretches (initial.mode: %s); a load resting on the ground starts with "
                "initial.mode: landed",
                sc.rope.length, top.z(), underside, g.height - underside, g.height,
                name(sc.initial_mode));
  throw InputError(sc.file + b);
}

// An equilibrium start with a ground: the rope stretched by the load and the structure deflected
// under it must still leave the load's underside above the ground. The unstretched check above
// is necessary, not sufficient: a heavy load far out sinks by the rope's stretch and the jib's
// deflection (a 7.2 t load at 55 m on the T8036: 0.37 m). Else the start would press the load into
// the ground: a static solve that includes the contact rests part of the weight on it, one that
// does not (the pendulum's) starts the load inside the ground, which throws it up.
void SupportedRopeSimulation::checkRestsClearOfGround(const CoupledState& s) const {
  const Scene& sc = model_.scene;
  const double clearance = ground_->clearance(s.q.segment<3>(endPointIndex()));
  if (clearance > 0.0) return;
  char b[480];
  std::snprintf(b, sizeof b,
                ": key 'rope.length': %.4g m of rope put the load's underside at z = %.4g m at "
                "the static equilibrium (the rope stretched by the load, the structure "
                "deflected under it), not above ground.height %.4g m (initial.mode: %s); a "
                "shorter rope.length hangs it clear, and a load resting on the ground starts "
                "with initial.mode: landed",
                sc.rope.length, ground_->parameters().height + clearance,
                ground_->parameters().height, name(sc.initial_mode));
  throw InputError(sc.file + b);
}

CoupledState SupportedRopeSimulation::sceneInitialState() {
  const Scene& sc = model_.scene;
  const double th = sc.swing_deg * M_PI / 180.0, az = sc.swing_azimuth_deg * M_PI / 180.0;
  CoupledState s;
  if (ground_ && sc.initial_mode != InitialMode::landed) {
    checkHangsClearOfGround(swingDirection(th, az));
  }
  if (sc.initial_mode == InitialMode::landed) {
    s = landedState();
  } else if (sc.initial_mode == InitialMode::stress_free) {
    s.z = s.zd = Eigen::VectorXd::Zero(support_->size());
    s.q = straightRope(support_->point(s.z), swingDirection(th, az));
    s.v = Eigen::VectorXd::Zero(s.q.size());
  } else {
    s = staticState();
  }
  s.v.segment<3>(endPointIndex()) += sc.payload_velocity;
  s.t = 0.0;
  initializeAccelerations(s);
  return s;
}

void SupportedRopeSimulation::sample(Eigen::Vector3d& payload, Eigen::Vector3d& cab,
                                     Eigen::Vector3d& jib_tip) const {
  payload = state_.q.segment<3>(endPointIndex());
  cab = support_->cabDisplacement(state_.z);
  jib_tip = support_->jibTipDisplacement(state_.z);
}

SeriesValues SupportedRopeSimulation::seriesOf(const CoupledState& s) const {
  const int e = endPointIndex();
  return seriesWith(s, s.q.segment<3>(e), s.v.segment<3>(e), topTensionOf(s), energyOf(s),
                    ropeLength());
}

SeriesValues SupportedRopeSimulation::seriesWith(const CoupledState& s,
                                                 const Eigen::Vector3d& payload,
                                                 const Eigen::Vector3d& payload_velocity,
                                                 double tension, double energy,
                                                 double rope_length) const {
  SeriesValues v;
  v.t = s.t;
  v.payload = payload;
  v.payload_velocity = payload_velocity;
  v.cab = support_->cabDisplacement(s.z);
  v.jib_tip = support_->jibTipDisplacement(s.z);
  v.trolley = support_->point(s.z);
  v.rope_top_tension = tension;
  v.rope_length = rope_length;
  v.slew_angle = drives_.slewAngle();
  v.trolley_radius = drives_.trolleyRadius();
  v.energy = energy;
  v.constraint_error = constraintError(*support_, s);
  const Eigen::VectorXd sigma = model_.hotSpotStresses(s.z);
  v.stresses.assign(sigma.data(), sigma.data() + sigma.size());
  if (ground_) {
    v.contact_force = ground_->force(payload, payload_velocity).f.z();
    v.payload_landed = v.contact_force > 0.0;
  }
  setCraneWarnings(model_, drives_, v);
  if (wind_) {
    v.wind_3s = wind_3s_;
    if (wind_3s_ > wind_->settings().in_service_limit) v.warnings |= kWindOverInServiceLimit;
  }
  return v;
}

}  // namespace crane_twin
