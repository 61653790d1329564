// Gauss-Legendre quadrature on [0, 1], shared by the ANCF cable and the Timoshenko beam
// element: an n-point rule integrates polynomials of degree 2n - 1 exactly.
#pragma once

#include <Eigen/Dense>

namespace crane_twin {

/// Points x_i in (0, 1) and weights w_i (summing to 1) of the n-point rule, n in 1..10, by
/// Newton iteration on the Legendre polynomial P_n. Throws std::invalid_argument for other n.
void gaussLegendre01(int n, Eigen::VectorXd& points, Eigen::VectorXd& weights);

}  // namespace crane_twin
