// The state of a rope held by its support, in the rope model's own coordinates q (ANCF
// coordinates, or the pendulum's two points) and the support's coordinates z (modal
// amplitudes, FE displacements, or none for an anchor), with the generalized-alpha
// acceleration-like variables (Arnold & Bruls 2007) and the constraint force.
#pragma once

#include <Eigen/Dense>

namespace crane_twin {

struct CoupledState {
  double t = 0.0;                  ///< time [s]
  Eigen::VectorXd q, v;            ///< rope coordinates and velocities
  Eigen::VectorXd qdd;             ///< true accelerations
  Eigen::VectorXd a;               ///< generalized-alpha acceleration-like variable
  Eigen::VectorXd z, zd, zdd, za;  ///< the same for the support coordinates (empty: anchor)
  Eigen::Vector3d lambda = Eigen::Vector3d::Zero();  ///< force of the rope top on the support [N]
  int newton_iterations = 0;                         ///< iterations of the last step
};

}  // namespace crane_twin
