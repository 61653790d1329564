// Dynamics and statics of the pendulum rope (PendulumRope) held by its support: the same
// index-3 DAE, generalized-alpha scheme, scaling, support elimination and Newton loop
// (integrators/newton_step.hpp) as FullOrderSolver, with the rope block a dense 6 x 6:
//   M q'' + Q(q) + Q_d(q, q') - F_g + C_q^T lambda = 0,   C_q = [I 0],
//   M_z z'' + C_z z' + K_z z - D^T lambda = 0,
//   C = r_0 - r_p(z) = 0.
// Newton on (dq, dmu), mu = beta h^2 lambda, with the 9 x 9 iteration matrix
//   [ a M + beta h^2 K + gamma h C_d   C_q^T ]
//   [ C_q                              -G    ],   G = D A_z^-1 D^T,
// solved by a pivoting dense LU. Where Newton fails (a slack rope snapping taut) the step is
// halved, as at full order. Statics are closed form: the bar is straight and the support linear.
//
// With a rigging (setRigging, docs/model.md "Hook block"): a second bar from the hoist bar's end
// (the hook block) to the payload, q = [r_0; r_1; r_2] (9), its mass, load, force and tangent
// added on [r_1; r_2]; the iteration matrix is 12 x 12.
#pragma once

#include <optional>
#include <string>

#include "crane_twin/elements/ground_contact.hpp"
#include "crane_twin/integrators/coupled_state.hpp"
#include "crane_twin/integrators/generalized_alpha.hpp"
#include "crane_twin/integrators/newton_step.hpp"
#include "crane_twin/integrators/numerical_failure.hpp"
#include "crane_twin/rope/pendulum_rope.hpp"

namespace crane_twin {

class PendulumSolver {
 public:
  /// Rope and support are referenced: they must outlive the solver.
  PendulumSolver(const PendulumRope& rope, RopeSupport& support, const GeneralizedAlpha& scheme,
                 double time_step, NewtonSettings newton = {});

  /// Static equilibrium with the chord at swing_rad from the vertical (azimuth az_rad), held by
  /// a horizontal force H on the end point (docs/scenes.md): the end point's balance gives
  /// tan(swing) = H / ((m_end + mu L / 2) g) and T = (m_end + mu L / 2) g / cos(swing); the
  /// support deflects under lambda = F_g,0 + T u (K_z z = D^T lambda). State at rest.
  CoupledState solveSwingEquilibrium(double swing_rad, double az_rad,
                                     Eigen::Vector3d* holding_force = nullptr);
  /// Consistent accelerations (q, v, z, zd given).
  void initializeAccelerations(CoupledState& s);
  /// One step of the time step, halved where Newton fails (kMaxHalvings).
  /// Throws NumericalFailure naming the time and the reason; s is then left unchanged.
  void step(CoupledState& s);
  /// The payload on a rigging bar under the rope's end (its top mass 0, its end mass the
  /// payload's, tension-only), referenced: it must outlive the solver. Before any state is built.
  void setRigging(const PendulumRope* rigging) { rigging_ = rigging; }
  /// Rope coordinates: 6, or 9 with a rigging.
  int dofs() const { return rigging_ ? 9 : 6; }
  /// Axial damping coefficient c [s] (0: none). Throws std::invalid_argument for c < 0.
  void setRopeDamping(double c);
  /// The ground under the end point (the payload; docs/model.md "Ground contact"), its force
  /// with the damping forces, its energy in energy(). Empty: no ground.
  void setGround(std::optional<GroundContact> ground) { ground_ = std::move(ground); }
  static constexpr int kMaxHalvings = 6;
  long halvedSteps() const { return halved_steps_; }
  double timeStep() const { return h_; }

  /// 1/2 v^T M v + U(q) - F_g^T q + the support's energy [J].
  double energy(const CoupledState& s) const;
  /// |lambda + m_top (r_0'' - g)|: the force between rope and trolley [N].
  double topTension(const CoupledState& s) const;
  double constraintError(const CoupledState& s) const;

 private:
  using VectorN = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 9, 1>;
  using MatrixN = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 9, 9>;
  bool tryStep(CoupledState& s, double h, std::string& why);
  /// The chain's mass, applied load, elastic force (tangent into *K) and damping force (dQ_d/dv
  /// into *C): the rope bar on [r_0; r_1], the rigging's on [r_1; r_2].
  MatrixN massMatrix() const;
  VectorN appliedForce() const;
  void forces(const VectorN& q, const VectorN& v, VectorN& Q, VectorN& Qd, MatrixN* K,
              MatrixN* C) const;
  const PendulumRope& rope_;
  const PendulumRope* rigging_ = nullptr;
  RopeSupport& support_;
  GeneralizedAlpha ga_;
  double h_;
  NewtonSettings newton_;
  NewtonWorkspace newton_workspace_;  ///< newtonStep's storage (scratch between steps)
  double damping_ = 0.0;
  std::optional<GroundContact> ground_;
  long halved_steps_ = 0;
};

}  // namespace crane_twin
