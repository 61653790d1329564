// Clearance between the cranes of a site (docs/site.md): each crane's parts as capsules in the
// site frame and the smallest distance between two cranes' parts.
//
// Frames: the site frame has z up; crane k's own frame (the `world` of docs/ros.md: origin at
// the centre of the mast base, z up) sits at position p_k with yaw psi_k about z, so a point x
// of the crane is at p_k + Rz(psi_k) x on the site.
#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "crane_twin/io/crane_description.hpp"

namespace crane_twin {

struct SitePose {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< mast foot on the site [m]
  double yaw = 0.0;                                    ///< about z [rad]
  Eigen::Vector3d toSite(const Eigen::Vector3d& x) const {
    return position + Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * x;
  }
};

/// A part as a capsule: the points within `radius` of the segment a-b (site frame) [m].
struct CranePart {
  std::string name;
  Eigen::Vector3d a = Eigen::Vector3d::Zero(), b = Eigen::Vector3d::Zero();
  double radius = 0.0;
};

/// What the clearance needs of a crane's state, in the crane's own frame (CraneState).
struct CraneClearanceState {
  double slew_angle = 0.0;                                         ///< [rad]
  Eigen::Vector3d jib_tip_displacement = Eigen::Vector3d::Zero();  ///< slewing frame [m]
  Eigen::Vector3d trolley = Eigen::Vector3d::Zero();               ///< the rope's top [m]
  Eigen::Vector3d payload = Eigen::Vector3d::Zero();               ///< [m]
};

struct ClearanceSettings {
  double payload_radius = 1.0;  ///< the payload as a sphere [m]
};

/// The parts of a crane on the site: `mast` (base to jib rail, radius the half diagonal of its
/// section), `jib` and `counter_jib` (slewing-axis to tip at mid-height of the lattice, radius
/// half the diagonal of its section; the jib's tip moved by its displacement), `rope` (trolley
/// to payload, radius 0) and `payload` (a sphere).
std::vector<CranePart> cranePartsOnSite(const CraneDescription& crane, const SitePose& pose,
                                        const CraneClearanceState& state,
                                        const ClearanceSettings& settings = {});

struct PartClearance {
  /// Surface distance [m]: axis distance less both radii (negative where capsules overlap).
  double distance = 0.0;
  std::string part_a, part_b;
  Eigen::Vector3d point_a = Eigen::Vector3d::Zero(), point_b = Eigen::Vector3d::Zero();
};

/// OK above warn, WARN from warn down to error, ERROR below error (distances in m).
enum class ClearanceLevel { kOk = 0, kWarn = 1, kError = 2 };
ClearanceLevel clearanceLevel(double distance, double warn_distance, double error_distance);

/// The closest pair of parts of two cranes; the points on the capsules' surfaces facing each
/// other (on the axes where the axes touch). Throws std::invalid_argument for an empty list.
PartClearance minimumClearance(const std::vector<CranePart>& a, const std::vector<CranePart>& b);

/// A crane's predicted payload path (docs/twin.md "Forecast"): times [s, the stamps' clock]
/// and payload positions in the site frame.
struct PayloadPath {
  std::vector<double> t;
  std::vector<Eigen::Vector3d> payload;
};

/// The crane's state a forecast payload position implies: the jib turned to the payload's
/// azimuth about the mast and the trolley at its horizontal distance (the swing, a few metres
/// at 20-80 m, turns the jib by a few degrees at most), the rope's top on the rail, the jib-tip
/// displacement as now. `payload_site` in the site frame.
CraneClearanceState stateFromForecastPayload(const CraneDescription& crane, const SitePose& pose,
                                             const CraneClearanceState& now,
                                             const Eigen::Vector3d& payload_site);

struct ForecastClearance {
  bool valid = false;  ///< the two paths share no instant (within max_gap)
  PartClearance closest;
  double t = 0.0;  ///< when (a's path time) [s]
};

/// The smallest clearance over two cranes' forecasts: at each instant of a's path with a
/// sample of b's within max_gap [s], both cranes' parts from their forecast payloads
/// (stateFromForecastPayload) against each other.
ForecastClearance forecastClearance(const CraneDescription& a, const SitePose& pose_a,
                                    const CraneClearanceState& now_a, const PayloadPath& path_a,
                                    const CraneDescription& b, const SitePose& pose_b,
                                    const CraneClearanceState& now_b, const PayloadPath& path_b,
                                    const ClearanceSettings& settings, double max_gap);

}  // namespace crane_twin
