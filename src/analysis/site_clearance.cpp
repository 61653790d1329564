#include "crane_twin/analysis/site_clearance.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "crane_twin/analysis/segment_distance.hpp"

namespace crane_twin {

std::vector<CranePart> cranePartsOnSite(const CraneDescription& c, const SitePose& pose,
                                        const CraneClearanceState& s,
                                        const ClearanceSettings& settings) {
  if (!(settings.payload_radius >= 0.0) || !std::isfinite(settings.payload_radius)) {
    throw std::invalid_argument("clearance: payload radius must be finite and >= 0");
  }
  const Eigen::Matrix3d slew = Eigen::AngleAxisd(s.slew_angle, Eigen::Vector3d::UnitZ()).matrix();
  const double rail = c.jibRailHeight(), x0 = c.mast_width / 2.0;
  auto boom = [&](const std::string& name, const LatticeBoomSpec& b, double direction,
                  const Eigen::Vector3d& tip_displacement) {
    const double z = rail + b.height / 2.0;
    const Eigen::Vector3d root(direction * x0, 0.0, z), tip(direction * (x0 + b.length), 0.0, z);
    return CranePart{name, pose.toSite(slew * root), pose.toSite(slew * (tip + tip_displacement)),
                     0.5 * std::hypot(b.width, b.height)};
  };
  std::vector<CranePart> parts;
  parts.push_back({"mast", pose.toSite(Eigen::Vector3d::Zero()),
                   pose.toSite(Eigen::Vector3d(0.0, 0.0, rail)), c.mast_width / std::sqrt(2.0)});
  parts.push_back(boom("jib", c.jib, 1.0, s.jib_tip_displacement));
  parts.push_back(boom("counter_jib", c.counter_jib, -1.0, Eigen::Vector3d::Zero()));
  parts.push_back({"rope", pose.toSite(s.trolley), pose.toSite(s.payload), 0.0});
  parts.push_back(
      {"payload", pose.toSite(s.payload), pose.toSite(s.payload), settings.payload_radius});
  return parts;
}

ClearanceLevel clearanceLevel(double distance, double warn_distance, double error_distance) {
  if (!(distance >= error_distance)) return ClearanceLevel::kError;  // NaN included
  return distance < warn_distance ? ClearanceLevel::kWarn : ClearanceLevel::kOk;
}

PartClearance minimumClearance(const std::vector<CranePart>& a, const std::vector<CranePart>& b) {
  if (a.empty() || b.empty()) throw std::invalid_argument("clearance: a crane without parts");
  PartClearance best;
  best.distance = std::numeric_limits<double>::infinity();
  for (const CranePart& pa : a)
    for (const CranePart& pb : b) {
      const SegmentClosestPoints c = closestPointsOfSegments(pa.a, pa.b, pb.a, pb.b);
      const double d = c.distance - pa.radius - pb.radius;
      if (!(d < best.distance)) continue;
      best.distance = d;
      best.part_a = pa.name;
      best.part_b = pb.name;
      best.point_a = c.point_a;
      best.point_b = c.point_b;
      if (c.distance > 0.0) {  // onto the surfaces, along the line joining the axes
        const Eigen::Vector3d u = (c.point_b - c.point_a) / c.distance;
        best.point_a += pa.radius * u;
        best.point_b -= pb.radius * u;
      }
    }
  return best;
}

CraneClearanceState stateFromForecastPayload(const CraneDescription& crane, const SitePose& pose,
                                             const CraneClearanceState& now,
                                             const Eigen::Vector3d& payload_site) {
  // Into the crane's own frame: x = Rz(-yaw) (p - position).
  const Eigen::Vector3d p =
      Eigen::AngleAxisd(-pose.yaw, Eigen::Vector3d::UnitZ()) * (payload_site - pose.position);
  CraneClearanceState s = now;
  s.payload = p;
  const double r = std::hypot(p.x(), p.y());
  s.slew_angle = r > 0.0 ? std::atan2(p.y(), p.x()) : now.slew_angle;
  s.trolley = Eigen::Vector3d(p.x(), p.y(), crane.jibRailHeight());
  return s;
}

ForecastClearance forecastClearance(const CraneDescription& a, const SitePose& pose_a,
                                    const CraneClearanceState& now_a, const PayloadPath& path_a,
                                    const CraneDescription& b, const SitePose& pose_b,
                                    const CraneClearanceState& now_b, const PayloadPath& path_b,
                                    const ClearanceSettings& settings, double max_gap) {
  if (path_a.t.size() != path_a.payload.size() || path_b.t.size() != path_b.payload.size()) {
    throw std::invalid_argument(
        "forecast clearance: a path's times and positions differ in number");
  }
  ForecastClearance out;
  out.closest.distance = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < path_a.t.size(); ++i) {
    std::size_t best = path_b.t.size();
    double gap = max_gap;
    for (std::size_t j = 0; j < path_b.t.size(); ++j) {
      const double g = std::abs(path_b.t[j] - path_a.t[i]);
      if (g <= gap) {
        gap = g;
        best = j;
      }
    }
    if (best == path_b.t.size()) continue;
    const PartClearance c = minimumClearance(
        cranePartsOnSite(a, pose_a, stateFromForecastPayload(a, pose_a, now_a, path_a.payload[i]),
                         settings),
        cranePartsOnSite(
            b, pose_b, stateFromForecastPayload(b, pose_b, now_b, path_b.payload[best]), settings));
    out.valid = true;
    if (c.distance < out.closest.distance) {
      out.closest = c;
      out.t = path_a.t[i];
    }
  }
  return out;
}

}  // namespace crane_twin
