#include "crane_twin/analysis/segment_distance.hpp"

#include <algorithm>

namespace crane_twin {

namespace {
double clamp01(double x) { return std::clamp(x, 0.0, 1.0); }
}  // namespace

SegmentClosestPoints closestPointsOfSegments(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                                             const Eigen::Vector3d& b0, const Eigen::Vector3d& b1) {
  // f(s, t) = |r + s d1 - t d2|^2 with r = a0 - b0: grad f = 0 gives
  //   a s - b t = -c,  b s - e t = -f   (a = d1.d1, b = d1.d2, c = d1.r, e = d2.d2, f = d2.r).
  // On each clamped edge the other parameter is the projection, clamped again.
  const Eigen::Vector3d d1 = a1 - a0, d2 = b1 - b0, r = a0 - b0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  constexpr double kTiny = 1e-24;  // [m^2]: a segment shorter than 1e-12 m is a point
  double s = 0.0, t = 0.0;
  if (a <= kTiny && e <= kTiny) {
    s = t = 0.0;
  } else if (a <= kTiny) {
    t = clamp01(f / e);
  } else {
    const double c = d1.dot(r);
    if (e <= kTiny) {
      s = clamp01(-c / a);
    } else {
      const double b = d1.dot(d2), denom = a * e - b * b;
      // Parallel segments (denom 0): any s; take s = 0 and let the clamping below decide.
      s = denom > kTiny * (a * e) ? clamp01((b * f - c * e) / denom) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = clamp01(-c / a);
      } else if (t > 1.0) {
        t = 1.0;
        s = clamp01((b - c) / a);
      }
    }
  }
  SegmentClosestPoints out;
  out.point_a = a0 + s * d1;
  out.point_b = b0 + t * d2;
  out.distance = (out.point_a - out.point_b).norm();
  return out;
}

}  // namespace crane_twin
