// Error metrics of docs/accuracy-vs-time.md between two runs of the same scene (reduced against
// full, or any setting against a reference): payload error, rope RMS error over all nodes (paper
// eq. 18 with its square restored), cab and jib-tip errors, each the max over the common output
// times.
#pragma once

#include <Eigen/Dense>
#include <limits>
#include <string>
#include <vector>

namespace crane_twin {

/// What a run leaves behind at its output times (nodes may be empty).
struct Trajectory {
  std::vector<double> t;
  std::vector<Eigen::Vector3d> payload, cab, jib_tip;
  std::vector<double> tension;                      ///< rope top tension [N]
  std::vector<std::vector<Eigen::Vector3d>> nodes;  ///< per output time, every rope node
  double rope_length = 0.0;                         ///< hanging length at t = 0 [m]

  /// Keeps the first n output times of every series that has more (a series not recorded stays
  /// empty).
  void keepFirst(std::size_t n) {
    const auto shrink = [n](auto& series) {
      if (series.size() > n) series.resize(n);
    };
    shrink(t);
    shrink(payload);
    shrink(cab);
    shrink(jib_tip);
    shrink(tension);
    shrink(nodes);
  }
};

struct ErrorMetrics {
  int common_times = 0;
  double payload_max = 0.0;       ///< max_t |r_p^A - r_p^B| [m]
  double payload_max_at = 0.0;    ///< the first output time of that maximum [s]
  double payload_relative = 0.0;  ///< payload_max / rope length
  double rope_rms_max = -1.0;     ///< max_t sqrt(1/n sum_j |r_j^A - r_j^B|^2) [m]; -1 without nodes
  double rope_rms_max_at = 0.0;   ///< the first output time of that maximum [s]
  double cab_max = 0.0, jib_tip_max = 0.0;  ///< [m]
  double tension_max = 0.0;                 ///< max_t |T^A - T^B| of the rope top tension [N]
  double tension_relative = 0.0;            ///< tension_max / max_t |T^B|
  double rope_length = 0.0;                 ///< the length the relative errors divide by [m]
};

/// The output times a comparison looks at: from <= t <= to [s] (default: all). A window tells
/// the error of one phase of a run (a lift before its set-down, the landed rest after it).
struct TimeWindow {
  double from = -std::numeric_limits<double>::infinity();
  double to = std::numeric_limits<double>::infinity();
};

/// Metrics at the times both trajectories share (matched to 1e-9 s) within `window`. Throws
/// InputError when they share none there, or for a window that is NaN or ends before it begins.
/// Chains of different meshes (a pendulum's 2 or 3 points against an ANCF rope's nodes, two element
/// counts, a rigging's bar after the rope): the coarser chain is interpolated linearly at the finer
/// one's arc-length fractions s_j / s_n (the polygon through its nodes; for a uniform rope the
/// material points j / (n - 1) to its strain's variation), so a rigging's hook and payload meet the
/// other model's; the RMS runs over the finer chain's n nodes. Exact for the pendulum (straight
/// bars); for a coarse ANCF rope it leaves out the curvature between its nodes.
ErrorMetrics compareTrajectories(const Trajectory& a, const Trajectory& b,
                                 const TimeWindow& window = {});

/// Cumulative arc length of the polygon through `nodes` over its total, per node (0 ... 1).
std::vector<double> arcFractions(const std::vector<Eigen::Vector3d>& nodes);
/// The polygon through `nodes` interpolated linearly at arc-length fractions (arcFractions).
/// Throws InputError for fewer than 2 nodes.
std::vector<Eigen::Vector3d> resampleRopeAt(const std::vector<Eigen::Vector3d>& nodes,
                                            const std::vector<double>& fractions);

/// Read a docs/cli.md time-series CSV (and optionally its nodes CSV). Throws InputError naming the
/// file, line and column for a missing column, a malformed number or a ragged row.
Trajectory readTrajectory(const std::string& series_csv, const std::string& nodes_csv = "");

}  // namespace crane_twin
