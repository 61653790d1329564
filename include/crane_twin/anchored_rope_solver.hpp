// Full-order (F-ANCF) dynamics and statics of a rope whose top node is held at a fixed anchor
// (scenes with crane: none; SPEC 1.5).
//
// Index-3 DAE:  M q'' + Q(q) - F_g - F_ext + C_q^T lambda = 0,   C(q) = r_0 - r_anchor = 0,
// integrated with generalized-alpha (Arnold & Bruls, Multibody Syst. Dyn. 18, 2007, Alg. 1):
//   alpha_m = (2 rho - 1)/(rho + 1), alpha_f = rho/(rho + 1), gamma = 1/2 + alpha_f - alpha_m,
//   beta = (gamma + 1/2)^2 / 4;  Newmark (average acceleration) is alpha_m = alpha_f = 0.
// Newton on (Delta q, Delta mu) with mu = beta h^2 lambda and the equations scaled by beta h^2
// (Bottasso, Bauchau & Cardona 2008), so the iteration matrix
//   [ (1-alpha_m)/(1-alpha_f) M + beta h^2 K_t    C_q^T ]
//   [ C_q                                          0     ]
// has entries of the order of M whatever the step. The rope block is banded; with the three
// multiplier rows ordered last, a sparse LDL^T in natural order (Eigen's SimplicialLDLT) meets
// the zero diagonal only after the rope block (the pivot is then the negative Schur complement
// -C_q A11^-1 C_q^T) and fills in just those three rows. The pattern is analysed once; the
// values are written in place every iteration and refactorised. Converged when
// max|Delta q| < position_tolerance (default 1e-10 m) and |C| < constraint_tolerance (1e-12 m).
#pragma once

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <stdexcept>
#include <string>

#include "crane_twin/ancf_rope.hpp"

namespace crane_twin {

/// A failure of the numerics (Newton divergence, singular matrix, non-finite state).
class NumericalFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct GeneralizedAlpha {
  double alpha_m = 0.0, alpha_f = 0.0, gamma = 0.5, beta = 0.25;
  static GeneralizedAlpha fromRhoInf(double rho_inf);
  static GeneralizedAlpha newmark();
};

struct RopeState {
  double t = 0.0;
  Eigen::VectorXd q, v;     ///< coordinates and velocities
  Eigen::VectorXd qdd;      ///< true accelerations
  Eigen::VectorXd a;        ///< generalized-alpha acceleration-like variable
  Eigen::Vector3d lambda = Eigen::Vector3d::Zero();  ///< constraint force on the top node [N]
  int newton_iterations = 0;
};

struct NewtonSettings {
  double position_tolerance = 1e-10;
  double constraint_tolerance = 1e-12;
  int max_iterations = 30;
};

class AnchoredRopeSolver {
 public:
  AnchoredRopeSolver(const AncfRope& rope, const Eigen::Vector3d& anchor,
                     const GeneralizedAlpha& scheme, double time_step,
                     NewtonSettings newton = {});

  /// Static equilibrium under gravity and a constant force on the end mass, damped Newton from
  /// q_guess (which must carry tension: see solveSwingEquilibrium). Returns the state at rest
  /// (v = 0); -lambda is the support force on the rope.
  RopeState solveStatic(const Eigen::VectorXd& q_guess, const Eigen::Vector3d& end_force);

  /// Equilibrium whose chord (anchor to end node) makes swing_rad with the vertical at azimuth
  /// az_rad, held by a horizontal force on the end mass (secant on the force). SPEC 2.
  RopeState solveSwingEquilibrium(double swing_rad, double az_rad,
                                  Eigen::Vector3d* holding_force = nullptr);

  /// Consistent accelerations of a state (q, v given) at release: solves the KKT system with
  /// the top node's acceleration held at zero.
  void initializeAccelerations(RopeState& s);

  /// One generalized-alpha step of size h. Throws NumericalFailure.
  void step(RopeState& s);

  /// Total mechanical energy: 1/2 v^T M v + U(q) - F_g^T q (gravity potential, zero at q = 0).
  double energy(const RopeState& s) const;
  /// Support force magnitude = rope top tension [N].
  static double topTension(const RopeState& s) { return s.lambda.norm(); }

  const AncfRope& rope() const { return rope_; }
  double timeStep() const { return h_; }

 private:
  // Fill the values of A_ (fixed pattern) and the elastic force Q.
  void assemble(const Eigen::VectorXd& q, double massWeight, double stiffWeight,
                Eigen::VectorXd& Q);
  // Factorise A_; throws NumericalFailure with `what` on failure.
  void factorize(const std::string& what);
  const AncfRope& rope_;
  Eigen::Vector3d anchor_;
  GeneralizedAlpha ga_;
  double h_;
  NewtonSettings newton_;
  SparseMatrix A_;  ///< KKT iteration matrix, pattern fixed at construction
  std::vector<int> mass_index_;   ///< value slot of each mass entry (in M's order)
  std::vector<double> mass_value_;
  std::vector<int> element_index_;  ///< 144 value slots per element, column-major 12 x 12
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower, Eigen::NaturalOrdering<int>> ldlt_;
};

}  // namespace crane_twin
