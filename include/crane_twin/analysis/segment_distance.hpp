// Closest points between two line segments in 3D (a point is a segment of zero length).
#pragma once

#include <Eigen/Core>

namespace crane_twin {

struct SegmentClosestPoints {
  double distance = 0.0;  ///< |point_a - point_b| [m]
  Eigen::Vector3d point_a = Eigen::Vector3d::Zero(), point_b = Eigen::Vector3d::Zero();
};

/// Minimise |(a0 + s (a1 - a0)) - (b0 + t (b1 - b0))| over s, t in [0, 1]: the stationary point
/// of the quadratic in (s, t), clamped to the unit square edge by edge (parallel and degenerate
/// segments included).
SegmentClosestPoints closestPointsOfSegments(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                                             const Eigen::Vector3d& b0, const Eigen::Vector3d& b1);

}  // namespace crane_twin
