#include "crane_twin/simulation/simulation.hpp"

#include <charconv>
#include <string>

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

namespace {

// A CSV row built in memory: numbers as a stream with std::setprecision(10) prints them (printf's
// %.10g, which std::to_chars's general format with that precision is defined to match), at a
// fraction of the stream's cost per number.
class CsvRow {
 public:
  CsvRow& number(double x) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, x, std::chars_format::general, 10);
    row_.append(buf, r.ptr);
    return *this;
  }
  CsvRow& integer(long x) {
    char buf[24];
    const auto r = std::to_chars(buf, buf + sizeof buf, x);
    row_.append(buf, r.ptr);
    return *this;
  }
  CsvRow& comma() {
    row_ += ',';
    return *this;
  }
  CsvRow& vector(const Eigen::Vector3d& x) {
    return comma().number(x.x()).comma().number(x.y()).comma().number(x.z());
  }
  /// The row and its newline to `out`; the row is emptied for the next one.
  void writeTo(std::ostream& out) {
    row_ += '\n';
    out.write(row_.data(), static_cast<std::streamsize>(row_.size()));
    row_.clear();
  }

 private:
  std::string row_;
};

}  // namespace

void writeSeriesRow(std::ostream& out, const SeriesValues& v) {
  CsvRow row;
  row.number(v.t).vector(v.payload).vector(v.payload_velocity).vector(v.cab).vector(v.jib_tip);
  row.vector(v.trolley).comma().number(v.rope_top_tension).comma().number(v.rope_length);
  row.comma().number(v.slew_angle).comma().number(v.trolley_radius).comma().number(v.energy);
  row.comma().number(v.constraint_error).comma().integer(v.subdomains).comma();
  row.number(v.tension_ratio).comma().number(v.load_chart_ratio).comma().integer(v.warnings);
  row.comma().integer(v.full_order_steps).comma().integer(v.payload_landed ? 1 : 0).comma();
  row.number(v.contact_force);
  for (double sigma : v.stresses) row.comma().number(sigma);
  row.writeTo(out);
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
  CsvRow row;
  for (int j = 0; j < ropeNodes(); ++j) {
    row.number(t).comma().integer(j).vector(ropeNode(j)).writeTo(out);
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
