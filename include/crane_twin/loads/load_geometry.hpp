// The sizes the package gives the hook block and the payload from their masses (docs/ros.md
// markers, docs/model.md "Ground contact"): the boxes rviz draws and the payload's height above
// its underside, which lands on the ground.
//   hook block: a box a x a/2 x 1.2 a of steel (7850 kg/m^3) filled to one half (sheaves, side
//               plates, hook): m_h = 0.5 * 7850 * 0.6 a^3;
//   payload:    a cube of edge (m_p / 1000 kg/m^3)^(1/3), a mixed construction load (pallets,
//               formwork; a concrete skip is denser: 2400 kg/m^3).
// Each box hangs below the point the model gives its mass: the hook block under the rope's end,
// the payload under the hook block when the model lumps both into one point, else under its
// own point (the rigging's end).
#pragma once

#include <cmath>

namespace crane_twin {

constexpr double kSteelDensity = 7850.0;    ///< [kg/m^3]
constexpr double kHookBlockFill = 0.5;      ///< solid fraction of the hook block's box [-]
constexpr double kPayloadDensity = 1000.0;  ///< mixed construction load [kg/m^3]

/// Edge a of the hook block's box a x a/2 x 1.2 a [m].
inline double hookBlockEdge(double hook_mass) {
  return std::cbrt(hook_mass / (kHookBlockFill * kSteelDensity * 0.6));
}
/// Height 1.2 a of the hook block's box [m].
inline double hookBlockHeight(double hook_mass) { return 1.2 * hookBlockEdge(hook_mass); }
/// Edge of the payload's cube [m].
inline double payloadCubeEdge(double payload_mass) {
  return std::cbrt(payload_mass / kPayloadDensity);
}
/// From the point that carries the payload's mass down to the payload's underside [m]: the
/// hook block's and the cube's heights where both are lumped at the rope's end, the cube's alone
/// on a rigging.
inline double payloadUndersideDepth(double hook_mass, double payload_mass, bool rigging) {
  return payloadCubeEdge(payload_mass) + (rigging ? 0.0 : hookBlockHeight(hook_mass));
}

}  // namespace crane_twin
