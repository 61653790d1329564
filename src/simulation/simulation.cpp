#include "crane_twin/simulation/simulation.hpp"

#include <iomanip>

#include "crane_twin/io/config_reader.hpp"
#include "crane_twin/simulation/crane_simulation.hpp"
#include "crane_twin/simulation/invariant_reduced_simulation.hpp"
#include "crane_twin/simulation/pendulum_crane_simulation.hpp"
#include "crane_twin/simulation/simulation_capabilities.hpp"
#include "crane_twin/simulation/subdomain_reduced_simulation.hpp"

namespace crane_twin {

const char* const kSeriesHeader =
    "t,payload_x,payload_y,payload_z,payload_vx,payload_vy,payload_vz,cab_dx,cab_dy,cab_dz,"
    "jib_tip_dx,jib_tip_dy,jib_tip_dz,trolley_x,trolley_y,trolley_z,rope_top_tension,"
    "rope_length,slew_angle,trolley_radius,energy,constraint_error,subdomains,"
    "tension_ratio,load_chart_ratio,warnings,full_order_steps,payload_landed,contact_force";

std::string seriesHeader(const CraneModel& model) {
  std::string h = kSeriesHeader;
  if (model.hot_spots) {
    for (const HotSpotRow& r : model.hot_spots->rows) h += ",stress_" + r.name;
  }
  return h;
}

const char* warningName(int bit) {
  switch (bit) {
    case kTensionOverBreakingForce:
      return "rope tension over its breaking force";
    case kOutsideLoadChart:
      return "load outside the load chart at this radius";
    case kRopeLengthAtLimit:
      return "rope length at its limit";
    case kTrolleyAtLimit:
      return "trolley at its radius limit";
    case kCommandLimited:
      return "command above a drive's speed limit, limited";
    case kLiftOffOverDesignFactor:
      return "lift-off dynamic factor over hoist.design_phi2";
    case kWindOverInServiceLimit:
      return "3 s mean wind at the jib over the in-service limit";
    case kTensionOverWorkingLoadLimit:
      return "rope tension over its working load limit (breaking force / safety factor)";
    default:
      return "unknown warning";
  }
}

void writeSeriesRow(std::ostream& out, const SeriesValues& v) {
  auto put = [&out](const Eigen::Vector3d& x) {
    out << ',' << x.x() << ',' << x.y() << ',' << x.z();
  };
  out << std::setprecision(10) << v.t;
  put(v.payload);
  put(v.payload_velocity);
  put(v.cab);
  put(v.jib_tip);
  put(v.trolley);
  out << ',' << v.rope_top_tension << ',' << v.rope_length << ',' << v.slew_angle << ','
      << v.trolley_radius << ',' << v.energy << ',' << v.constraint_error << ',' << v.subdomains
      << ',' << v.tension_ratio << ',' << v.load_chart_ratio << ',' << v.warnings << ','
      << v.full_order_steps << ',' << (v.payload_landed ? 1 : 0) << ',' << v.contact_force;
  for (double sigma : v.stresses) out << ',' << sigma;
  out << '\n';
}

void Simulation::checkMotionSizes(const CoupledState& m, const CoupledState& like) {
  if (m.q.size() != like.q.size() || m.v.size() != like.v.size() || m.z.size() != like.z.size() ||
      m.zd.size() != like.zd.size()) {
    throw std::invalid_argument(
        "setMotion: " + std::to_string(m.q.size()) + " rope and " + std::to_string(m.z.size()) +
        " support coordinates, the model has " + std::to_string(like.q.size()) + " and " +
        std::to_string(like.z.size()));
  }
}

void Simulation::writeNodeRows(std::ostream& out) const {
  const double t = time();
  for (int j = 0; j < ropeNodes(); ++j) {
    const Eigen::Vector3d r = ropeNode(j);
    out << std::setprecision(10) << t << ',' << j << ',' << r.x() << ',' << r.y() << ',' << r.z()
        << '\n';
  }
}

std::vector<bool> Simulation::fullStatePositionBlocks() const {
  std::vector<bool> b(2 * static_cast<std::size_t>(ropeNodes()));
  for (std::size_t k = 0; k < b.size(); k += 2) b[k] = true;
  return b;
}

RopeModelKind ropeModelOf(const Scene& sc) {
  if (sc.rope.model == RopeModel::full) return RopeModelKind::full;
  if (sc.rope.model == RopeModel::pendulum) return RopeModelKind::pendulum;
  if (sc.rope.reduction != RopeReduction::subdomains) return RopeModelKind::invariant_reduced;
  // The subdomain reducer's basis carries no rigging: a scene with one runs at full order, the
  // answer the reduced rope must give (docs/model.md "Hook block").
  return sc.hasRigging() ? RopeModelKind::full : RopeModelKind::subdomain_reduced;
}

int integratedRopeCoordinates(const CraneModel& m) {
  switch (ropeModelOf(m.scene)) {
    case RopeModelKind::pendulum:
      return PendulumRope::kDofs + (m.scene.hasRigging() ? 3 : 0);
    case RopeModelKind::subdomain_reduced:
      return keptRopeModes(m) + 3;
    case RopeModelKind::invariant_reduced:
      return invariantRopeCoordinates(m);
    case RopeModelKind::full:
      break;
  }
  return m.ropeDofs();
}

std::unique_ptr<Simulation> makeSimulation(const CraneModel& model) {
  switch (ropeModelOf(model.scene)) {
    case RopeModelKind::full:
      return std::make_unique<CraneSimulation>(model);
    case RopeModelKind::invariant_reduced:
      return std::make_unique<InvariantReducedSimulation>(model);
    case RopeModelKind::subdomain_reduced:
      return std::make_unique<SubdomainReducedSimulation>(model);
    case RopeModelKind::pendulum:
      break;
  }
  return std::make_unique<PendulumCraneSimulation>(model);
}

std::unique_ptr<Simulation> continueWithModel(const CraneModel& model, const Simulation& from) {
  std::unique_ptr<Simulation> sim = makeSimulation(model);
  sim->initialize();
  requireCapability<ContinuableRun>(*sim).continueFrom(from);
  return sim;
}

}  // namespace crane_twin
