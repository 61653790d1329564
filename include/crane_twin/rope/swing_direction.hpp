// Direction of a rope chord swung from the vertical (docs/scenes.md, `initial.swing_deg` and
// `initial.swing_azimuth_deg`; azimuth measured from the jib direction, x).
#pragma once

#include <Eigen/Dense>
#include <cmath>

namespace crane_twin {

/// Unit chord direction at swing_rad from the vertical, azimuth az_rad, pointing down the rope:
/// (sin s cos a, sin s sin a, -cos s).
inline Eigen::Vector3d swingDirection(double swing_rad, double az_rad) {
  return Eigen::Vector3d(std::sin(swing_rad) * std::cos(az_rad),
                         std::sin(swing_rad) * std::sin(az_rad), -std::cos(swing_rad));
}

}  // namespace crane_twin
