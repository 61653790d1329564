// Generalized-alpha time integration of second-order systems (Arnold & Bruls, Multibody Syst.
// Dyn. 18, 2007, Alg. 1), parametrised by the spectral radius at infinity rho_inf:
//   alpha_m = (2 rho - 1)/(rho + 1), alpha_f = rho/(rho + 1), gamma = 1/2 + alpha_f - alpha_m,
//   beta = (gamma + 1/2)^2 / 4;  Newmark (average acceleration) is alpha_m = alpha_f = 0.
// Only the weights and the updates live here: the solvers assemble their own iteration
// matrices with these weights and never know which member of the family runs them.
#pragma once

#include <Eigen/Dense>

namespace crane_twin {

struct GeneralizedAlpha {
  double alpha_m = 0.0, alpha_f = 0.0, gamma = 0.5, beta = 0.25;
  /// Throws std::invalid_argument unless 0 <= rho_inf <= 1.
  static GeneralizedAlpha fromRhoInf(double rho_inf);
  static GeneralizedAlpha newmark();

  /// Predictor of a step of size h with x''_{n+1} = x''_n: advances x and x' in place from
  /// the start values x'' and a (Arnold & Bruls 2007, Alg. 1).
  void predict(double h, const Eigen::VectorXd& xdd, const Eigen::VectorXd& a, Eigen::VectorXd& x,
               Eigen::VectorXd& xd) const;
  /// Corrector: a position increment dx moves x' by gamma/(h beta) dx and x'' by
  /// (1 - alpha_m)/(h^2 beta (1 - alpha_f)) dx.
  void correct(double h, const Eigen::VectorXd& dx, Eigen::VectorXd& x, Eigen::VectorXd& xd,
               Eigen::VectorXd& xdd) const;
  /// The acceleration-like variable at the step's end from its start (xdd0, a0) and x''_{n+1}:
  /// (1 - alpha_m) a_{n+1} = alpha_f x''_n - alpha_m a_n + (1 - alpha_f) x''_{n+1}.
  Eigen::VectorXd nextA(const Eigen::VectorXd& xdd0, const Eigen::VectorXd& a0,
                        const Eigen::VectorXd& xdd) const;
  /// Weight of M in the beta h^2-scaled iteration matrix: (1 - alpha_m)/(1 - alpha_f).
  double massWeight() const { return (1.0 - alpha_m) / (1.0 - alpha_f); }
};

}  // namespace crane_twin
