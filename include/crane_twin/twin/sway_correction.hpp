// The estimator's correction carried into a running simulation (docs/twin.md): the rope turned
// rigidly about its top node (the trolley point) so that its end moves by dp, and given the
// rigid rotation rate that adds dv to the end's velocity; the support, the drives and the
// rope's shape relative to the chord are unchanged. ANCF coordinates (positions r_j and slopes
// r'_j per node): with rho = r_end - r_top, theta = rho x dp / |rho|^2, R = exp(theta),
//   r_j -> r_top + R (r_j - r_top),   r'_j -> R r'_j,
//   v_j -> v_top + R (v_j - v_top) + w x R (r_j - r_top),   v'_j -> R v'_j + w x R r'_j,
// w = R rho x u / |rho|^2 with u = dv - (R - I)(v_end - v_top) (the end's velocity gains dv).
// Components of dp and dv along the rope (stretching it) are not applied.
#pragma once

#include <Eigen/Dense>

#include "crane_twin/simulation/simulation.hpp"

namespace crane_twin {

/// The rope's full coordinates (q, v) after the correction (q, v of an ANCF rope, 6 per node).
/// Throws std::invalid_argument for sizes that are not 6 per node (>= 2 nodes).
void rotateRopeAboutTop(Eigen::VectorXd& q, Eigen::VectorXd& v, const Eigen::Vector3d& dp,
                        const Eigen::Vector3d& dv);

/// Apply it to a simulation (Simulation::setRopeMotion). Throws what that throws.
void applySwayCorrection(Simulation& sim, const Eigen::Vector3d& dp, const Eigen::Vector3d& dv);

}  // namespace crane_twin
