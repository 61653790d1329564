#include "crane_twin/analysis/load_shapes.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "crane_twin/loads/load_geometry.hpp"

namespace crane_twin {

namespace {

void checkMass(double m, const char* what) {
  if (!std::isfinite(m) || m < 0.0) {
    throw std::invalid_argument(std::string(what) + " mass must be finite and >= 0, got " +
                                std::to_string(m));
  }
}

// Centre of a box of height h hanging below `top` along the frame's z axis (up the rope).
FramePose hangingBelow(const FramePose& top, double h) {
  FramePose p = top;
  p.position = top.position - top.orientation * Eigen::Vector3d(0.0, 0.0, 0.5 * h);
  return p;
}

}  // namespace

LoadShapes loadShapes(const CraneSnapshot& s, double hook_block_mass, double payload_mass) {
  checkMass(hook_block_mass, "hook block");
  checkMass(payload_mass, "payload");
  LoadShapes out;
  const double a = hookBlockEdge(hook_block_mass);
  out.hook_block.size = Eigen::Vector3d(a, 0.5 * a, 1.2 * a);
  out.hook_block.pose = hangingBelow(s.hook, out.hook_block.size.z());
  const double e = payloadCubeEdge(payload_mass);
  out.payload.size = Eigen::Vector3d::Constant(e);
  FramePose top = s.payload;
  if ((s.payload.position - s.hook.position).norm() < 1e-9) {
    top.position =
        s.hook.position - s.hook.orientation * Eigen::Vector3d(0.0, 0.0, out.hook_block.size.z());
  }
  out.payload.pose = hangingBelow(top, e);
  return out;
}

}  // namespace crane_twin
