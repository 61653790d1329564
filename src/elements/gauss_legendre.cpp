#include "crane_twin/elements/gauss_legendre.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace crane_twin {

void gaussLegendre01(int n, Eigen::VectorXd& points, Eigen::VectorXd& weights) {
  if (n < 1 || n > 10) {
    throw std::invalid_argument("gauss points must be in 1..10, got " + std::to_string(n));
  }
  // Newton iteration on the Legendre polynomial P_n from the Chebyshev guess; converges to
  // machine precision in a handful of iterations for n <= 10.
  points.resize(n);
  weights.resize(n);
  for (int i = 0; i < n; ++i) {
    double x = std::cos(M_PI * (i + 0.75) / (n + 0.5));
    double dp = 0.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      const double pn = (n == 1) ? x : p1;
      const double pnm1 = (n == 1) ? 1.0 : p0;
      dp = n * (x * pn - pnm1) / (x * x - 1.0);
      const double dx = pn / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    points(i) = 0.5 * (1.0 - x);
    weights(i) = 1.0 / ((1.0 - x * x) * dp * dp);  // 2/((1-x^2)P'^2) scaled by 1/2
  }
}

}  // namespace crane_twin
