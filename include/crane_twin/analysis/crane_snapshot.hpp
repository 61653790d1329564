// What a viewer of a running simulation needs at one instant (docs/ros.md), computed without ROS:
// the time-series values, the drive joints, the frames of the crane's reference points at
// their deformed positions, the rope as a curve sampled from its shape functions, and
// the deformed structure as line segments. The ROS node only converts this to messages.
//
// Frames (all right-handed, metres):
//   world                      z up, origin at the centre of the mast base;
//   slewing = Rz(theta)        the superstructure's frame, same origin (docs/model.md);
//   jib_tip, cab, trolley      in the slewing frame: undeformed point + displacement u (no
//                              rotation: the structure is linear, its node rotations small);
//   mast                       in the world frame: the mast's rigid motion (best fit of its
//                              deformed nodes, not turned by the slewing angle);
//   slewing_unit, jib,         in the slewing frame: each part's rigid motion, the least-squares
//   counter_jib                fit (Umeyama, no scaling) of its deformed nodes onto the
//                              undeformed ones, so a rigid picture of the part drawn in
//                              undeformed slewing coordinates sits on the deformed structure;
//   hook, payload              in the world frame, z axis up along the rope's sampled segment
//                              above the point: the payload at the chain's end node, the hook
//                              block at the hoist rope's end. Without a rigging
//                              (hook.rigging_length) the model lumps them into one end mass and
//                              both frames share it.
#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "crane_twin/simulation/simulation.hpp"

namespace crane_twin {

class StructureGroupPoses;

struct SnapshotOptions {
  int samples_per_element = 4;      ///< rope curve points per element (>= 1)
  double displacement_scale = 1.0;  ///< structure displacement magnification (>= 0)
  bool structure_segments = true;   ///< build the structure's line segments
  /// The groups' rigid fits from their moments (set up for the simulation's support), instead of
  /// from the displacement field, which is then built only for the segments; nullptr: the field.
  const StructureGroupPoses* group_poses = nullptr;
};

struct FramePose {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
};

struct CraneSnapshot {
  SeriesValues series;
  // Drive joints: position and speed.
  double slew_angle = 0.0, slew_rate = 0.0;          ///< rad, rad/s
  double trolley_radius = 0.0, trolley_speed = 0.0;  ///< m, m/s
  double rope_length = 0.0, hoist_speed = 0.0;       ///< m, m/s (positive lowers)
  /// The hoist drive's paid-out rope [m]: rope_length (what hangs) plus the rope lying on a
  /// landed load; what a hoist's drum encoder measures (joint_states' `hoist`).
  double hoist_length = 0.0;
  bool has_crane = false;
  FramePose slewing;                         ///< in world
  FramePose jib_tip, cab, trolley;           ///< in slewing
  FramePose mast;                            ///< in world (rigid fit, without the slewing turn)
  FramePose slewing_unit, jib, counter_jib;  ///< in slewing (rigid fits of the deformed parts)
  FramePose hook, payload;                   ///< in world
  std::vector<Eigen::Vector3d> rope_curve;   ///< world, top to end
  std::vector<Eigen::Vector3d> structure_segments;  ///< world, pairs (member ends)
};

/// Rigid motion T (x -> R x + t) that best maps the undeformed points onto the deformed ones in
/// the least-squares sense, min sum |R x_i + t - y_i|^2 (Umeyama 1991, without scaling).
/// Throws std::invalid_argument for fewer than 3 points or sizes that differ.
FramePose rigidFit(const std::vector<Eigen::Vector3d>& undeformed,
                   const std::vector<Eigen::Vector3d>& deformed);

/// Snapshot of a running simulation. Throws std::invalid_argument for bad options.
CraneSnapshot snapshotOf(const Simulation& sim, const SnapshotOptions& options = {});

}  // namespace crane_twin
