// Boxes that picture the hook block and the payload at the simulated frames (docs/ros.md
// "Frames"), sized from their masses (loads/load_geometry.hpp). Only a picture: the model keeps
// both as point masses (the ground meets the payload's underside at the depth the same sizes
// give). Each box hangs below the point the model gives its mass, along that frame's z axis (up
// the rope): the hook block under the rope's end, the payload under the hook block when the
// model lumps both into one point, else under its own point.
#pragma once

#include "crane_twin/analysis/crane_snapshot.hpp"

namespace crane_twin {

struct LoadBox {
  FramePose pose;                                  ///< box centre, world frame
  Eigen::Vector3d size = Eigen::Vector3d::Zero();  ///< edge lengths along the pose's axes [m]
};

struct LoadShapes {
  LoadBox hook_block, payload;
};

/// Hook block and payload boxes for a snapshot. Throws std::invalid_argument for a negative or
/// non-finite mass (a zero mass gives a zero box).
LoadShapes loadShapes(const CraneSnapshot& s, double hook_block_mass, double payload_mass);

}  // namespace crane_twin
