#include "crane_twin/analysis/crane_snapshot.hpp"

#include <cmath>
#include <stdexcept>

#include "crane_twin/analysis/structure_group_poses.hpp"
#include "crane_twin/drives/crane_drives.hpp"
#include "crane_twin/rope/rope_support.hpp"
#include "crane_twin/solvers/full_order_solver.hpp"
#include "crane_twin/structure/structure_support.hpp"

namespace crane_twin {

namespace {

// Rotation taking the z axis onto the unit vector a.
Eigen::Quaterniond zAxisAlong(const Eigen::Vector3d& a) {
  return Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), a);
}

// Rigid fit of the nodes of the members in one group ("mast", "jib", ...) displaced by
// scale * u, in the slewing frame.
FramePose groupFit(const TowerCraneStructure& structure, const Eigen::VectorXd& u, double scale,
                   const std::string& group) {
  std::vector<Eigen::Vector3d> x, y;
  for (int n : structure.groupNodes(group)) {
    x.push_back(structure.nodes[n]);
    y.push_back(structure.nodes[n] + scale * structure.nodeDisplacement(u, n));
  }
  return rigidFit(x, y);
}

}  // namespace

FramePose rigidFit(const std::vector<Eigen::Vector3d>& undeformed,
                   const std::vector<Eigen::Vector3d>& deformed) {
  if (undeformed.size() < 3 || undeformed.size() != deformed.size()) {
    throw std::invalid_argument(
        "rigid fit needs the same number (>= 3) of undeformed and deformed points");
  }
  const int n = static_cast<int>(undeformed.size());
  Eigen::Matrix3Xd x(3, n), y(3, n);
  for (int i = 0; i < n; ++i) {
    x.col(i) = undeformed[i];
    y.col(i) = deformed[i];
  }
  const Eigen::Matrix4d T = Eigen::umeyama(x, y, false);
  FramePose p;
  p.position = T.block<3, 1>(0, 3);
  p.orientation = Eigen::Quaterniond(Eigen::Matrix3d(T.block<3, 3>(0, 0))).normalized();
  return p;
}

CraneSnapshot snapshotOf(const Simulation& sim, const SnapshotOptions& options) {
  if (!(options.displacement_scale >= 0.0) || !std::isfinite(options.displacement_scale)) {
    throw std::invalid_argument("displacement scale must be finite and >= 0");
  }
  if (options.samples_per_element < 1) {
    throw std::invalid_argument("rope samples per element must be >= 1");
  }
  const CraneDrives& drives = sim.drives();
  const RopeSupport& support = sim.support();
  CraneSnapshot s;
  s.series = sim.series();
  s.slew_angle = drives.slewAngle();
  s.slew_rate = drives.slewRate();
  s.trolley_radius = drives.trolleyRadius();
  s.trolley_speed = drives.trolleySpeed();
  s.rope_length = s.series.rope_length;
  s.hoist_length = drives.hoistLength();
  s.hoist_speed = drives.hoistSpeed();

  s.rope_curve = sim.ropeCurve(options.samples_per_element);
  // The payload's z axis along the chain's last sampled segment, pointing up the rope; the hook
  // block's along the hoist rope's last segment (the same point and frame without a rigging).
  auto alongSegment = [&](std::size_t end) {
    FramePose f;
    f.position = s.rope_curve[end];
    const Eigen::Vector3d up = s.rope_curve[end - 1] - s.rope_curve[end];
    f.orientation = up.norm() > 0.0 ? zAxisAlong(up.normalized()) : Eigen::Quaterniond::Identity();
    return f;
  };
  s.payload = alongSegment(s.rope_curve.size() - 1);
  s.hook =
      sim.hookNode() == sim.ropeNodes() - 1
          ? s.payload
          : alongSegment(static_cast<std::size_t>(sim.hookNode() * options.samples_per_element));

  const Eigen::Matrix3d R = slewRotation(s.slew_angle);
  s.slewing.orientation = Eigen::Quaterniond(R);
  const TowerCraneStructure* structure = support.structure();
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
  const Eigen::VectorXd z = sim.fullState().z;
  const double scale = options.displacement_scale;
  Eigen::VectorXd u;
  if (!options.group_poses || options.structure_segments) u = support.structureDisplacement(z);
  auto fit = [&](const std::string& group) {
    return options.group_poses ? options.group_poses->fit(group, z, scale)
                               : groupFit(*structure, u, scale, group);
  };
  // The rigid parts drawn where the deformed structure is: the mast without the slewing turn,
  // T_world = Rz T_fit Rz^T, the superstructure's parts in the slewing frame.
  const FramePose mast = fit("mast");
  s.mast.position = R * mast.position;
  s.mast.orientation = Eigen::Quaterniond(R) * mast.orientation * Eigen::Quaterniond(R).conjugate();
  s.slewing_unit = fit("slewing");
  s.jib = fit("jib");
  s.counter_jib = fit("counter_jib");
  if (options.structure_segments) {
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
