#include "crane_twin/integrators/generalized_alpha.hpp"

#include <stdexcept>

namespace crane_twin {

GeneralizedAlpha GeneralizedAlpha::fromRhoInf(double rho) {
  if (!(rho >= 0.0 && rho <= 1.0)) throw std::invalid_argument("rho_inf must be in [0, 1]");
  GeneralizedAlpha g;
  g.alpha_m = (2.0 * rho - 1.0) / (rho + 1.0);
  g.alpha_f = rho / (rho + 1.0);
  g.gamma = 0.5 + g.alpha_f - g.alpha_m;
  g.beta = 0.25 * (g.gamma + 0.5) * (g.gamma + 0.5);
  return g;
}

GeneralizedAlpha GeneralizedAlpha::newmark() { return GeneralizedAlpha{}; }

void GeneralizedAlpha::predict(double h, const Eigen::VectorXd& xdd, const Eigen::VectorXd& a,
                               Eigen::VectorXd& x, Eigen::VectorXd& xd) const {
  const Eigen::VectorXd aNew = (xdd - alpha_m * a) / (1.0 - alpha_m);
  x += h * xd + h * h * ((0.5 - beta) * a + beta * aNew);
  xd += h * ((1.0 - gamma) * a + gamma * aNew);
}

void GeneralizedAlpha::correct(double h, const Eigen::VectorXd& dx, Eigen::VectorXd& x,
                               Eigen::VectorXd& xd, Eigen::VectorXd& xdd) const {
  x += dx;
  xd += gamma / (h * beta) * dx;
  xdd += (1.0 - alpha_m) / (h * h * beta * (1.0 - alpha_f)) * dx;
}

Eigen::VectorXd GeneralizedAlpha::nextA(const Eigen::VectorXd& xdd0, const Eigen::VectorXd& a0,
                                        const Eigen::VectorXd& xdd) const {
  return (alpha_f * xdd0 - alpha_m * a0 + (1.0 - alpha_f) * xdd) / (1.0 - alpha_m);
}

}  // namespace crane_twin
