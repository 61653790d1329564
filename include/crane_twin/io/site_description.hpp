// A construction site (docs/site.md): the cranes that stand on it, each with its scene and
// pose, and the clearance monitor's distances.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace crane_twin {

struct SiteCrane {
  std::string name;                    ///< namespace and frame prefix (`name/`)
  std::string scene;                   ///< scene file (resolved: absolute or relative to cwd)
  std::vector<std::string> overrides;  ///< `key=value`, like crane_sim --set
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< mast foot on the site [m]
  double yaw_deg = 0.0;                                ///< about z [deg]
};

struct SiteDescription {
  std::string file;
  std::vector<SiteCrane> cranes;
  double warn_distance = 10.0;  ///< [m] clearance under which the monitor warns
  double error_distance = 3.0;  ///< [m] clearance under which it reports an error
  double payload_radius = 1.0;  ///< [m] the payload as a sphere
  double rate = 10.0;           ///< [Hz] of wall time, clearance messages per pair
};

/// Read and validate a site file: at least one crane, names unique and usable as ROS names
/// ([A-Za-z][A-Za-z0-9_]*), scenes that exist (a bare name is looked up in <site dir>/../scenes/
/// with .yaml added), 0 < error_distance <= warn_distance. Throws InputError naming file and key.
SiteDescription loadSiteDescription(const std::string& path);

}  // namespace crane_twin
