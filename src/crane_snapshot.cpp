#include "crane_twin/crane_snapshot.hpp"

#include <cmath>
#include <stdexcept>

#include "crane_twin/crane_simulation.hpp"
#include "crane_twin/structure_support.hpp"

namespace crane_twin {

// r(xi) = S(xi) e per element (SPEC 1.1), xi = k / per_element.
std::vector<Eigen::Vector3d> sampleRopeCurve(const Eigen::VectorXd& q, double l,
                                             int per_element) {
  if (per_element < 1) throw std::invalid_argument("rope samples per element must be >= 1");
  const int elements = static_cast<int>(q.size()) / 6 - 1;
  std::vector<Eigen::Vector3d> points;
  points.reserve(static_cast<size_t>(elements * per_element + 1));
  for (int k = 0; k < elements; ++k) {
    const Vector12 e = q.segment<12>(6 * k);
    for (int i = 0; i < per_element; ++i)
      points.push_back(ancfPosition(e, static_cast<double>(i) / per_element, l));
  }
  points.push_back(q.segment<3>(6 * elements));
  return points;
}

namespace {

// Rotation taking the z axis onto the unit vector a.
Eigen::Quaterniond zAxisAlong(const Eigen::Vector3d& a) {
  return Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), a);
}

}  // namespace

CraneSnapshot snapshotOf(const Simulation& sim, const SnapshotOptions& options) {
  if (!(options.displacement_scale >= 0.0) || !std::isfinite(options.displacement_scale)) {
    throw std::invalid_argument("displacement scale must be finite and >= 0");
  }
  const CraneSimulation& crane = sim.crane();
  const CoupledState state = sim.fullState();
  CraneSnapshot s;
  s.series = sim.series();
  s.slew_angle = crane.slewAngle();
  s.slew_rate = crane.slewRate();
  s.trolley_radius = crane.trolleyRadius();
  s.trolley_speed = crane.trolleySpeed();
  s.rope_length = crane.ropeLength();
  s.hoist_speed = crane.hoistSpeed();

  const AncfRope& rope = crane.rope();
  s.rope_curve = sampleRopeCurve(state.q, rope.element().length, options.samples_per_element);
  const int end = rope.nodes() - 1;
  const Eigen::Vector3d end_slope = state.q.segment<3>(6 * end + 3);
  s.hook.position = state.q.segment<3>(6 * end);
  s.hook.orientation = end_slope.norm() > 0.0 ? zAxisAlong(-end_slope.normalized())
                                              : Eigen::Quaterniond::Identity();
  s.payload = s.hook;

  const Eigen::Matrix3d R = slewRotation(s.slew_angle);
  s.slewing.orientation = Eigen::Quaterniond(R);
  const TowerCraneStructure* structure = crane.support().structure();
  s.has_crane = structure != nullptr;
  if (!structure) {
    // crane: none: the anchor stands for the trolley, in the world (= slewing) frame.
    s.trolley.position = s.series.trolley;
    return s;
  }
  s.trolley.position = R.transpose() * s.series.trolley;
  Eigen::Vector3d tip0 = Eigen::Vector3d::Zero();
  for (int n : structure->jib_tip_nodes) tip0 += structure->nodes[n];
  tip0 /= static_cast<double>(structure->jib_tip_nodes.size());
  s.jib_tip.position = tip0 + s.series.jib_tip;
  s.cab.position = structure->nodes[structure->cab_node] + s.series.cab;
  if (options.structure_segments) {
    const Eigen::VectorXd u = crane.support().structureDisplacement(state.z);
    const double scale = options.displacement_scale;
    auto world = [&](int n) {
      return Eigen::Vector3d(R * (structure->nodes[n] + scale * structure->nodeDisplacement(u, n)));
    };
    s.structure_segments.reserve(2 * structure->members.size());
    for (const StructureMember& m : structure->members) {
      s.structure_segments.push_back(world(m.node1));
      s.structure_segments.push_back(world(m.node2));
    }
  }
  return s;
}

}  // namespace crane_twin
