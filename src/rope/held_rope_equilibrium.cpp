#include "crane_twin/rope/held_rope_equilibrium.hpp"

#include <Eigen/SparseCholesky>
#include <cmath>
#include <string>
#include <vector>

#include "crane_twin/integrators/numerical_failure.hpp"

namespace crane_twin {

namespace {

// The free coordinates' index in the system they form (-1: held): the top node's position and
// the chain's end (the hook node; with a rigging the payload point).
std::vector<int> freeIndex(const AncfRope& rope, int& free_count) {
  std::vector<int> index(rope.dofs(), 0);
  const auto hold = [&](int first) {
    for (int i = 0; i < 3; ++i) index[first + i] = -1;
  };
  hold(rope.positionIndex(0));
  hold(rope.positionIndex(rope.nodes() - 1));
  free_count = 0;
  for (int& i : index)
    if (i == 0) i = free_count++;
  return index;
}

// Below this largest correction [m] Newton steps without a line search.
constexpr double kLineSearchBelow = 1e-6;

double potential(const AncfRope& rope, const Eigen::VectorXd& q) {
  return rope.elasticEnergy(q) - rope.gravityForce().dot(q);
}

}  // namespace

int settleBetweenHeldEnds(const AncfRope& rope, Eigen::VectorXd& q,
                          const HeldRopeSettings& settings) {
  int n = 0;
  const std::vector<int> index = freeIndex(rope, n);
  const Eigen::VectorXd& Fg = rope.gravityForce();
  // The residual's scale: the weight on the free coordinates.
  double weight = 0.0;
  for (int i = 0; i < rope.dofs(); ++i)
    if (index[i] >= 0) weight += std::abs(Fg(i));
  Eigen::VectorXd x = q;
  Eigen::SimplicialLDLT<SparseMatrix> ldlt;
  for (int it = 0; it < settings.max_iterations; ++it) {
    Eigen::VectorXd Q;
    const SparseMatrix K = rope.tangentStiffness(x, &Q);
    Eigen::VectorXd r(n);  // -grad_f Pi
    for (int i = 0; i < rope.dofs(); ++i)
      if (index[i] >= 0) r(index[i]) = Fg(i) - Q(i);
    if (!r.allFinite()) break;
    if (r.lpNorm<1>() <= 1e-10 * weight) {
      q = x;
      return it;
    }
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(K.nonZeros());
    for (int k = 0; k < K.outerSize(); ++k)
      for (SparseMatrix::InnerIterator e(K, k); e; ++e)
        if (index[e.row()] >= 0 && index[e.col()] >= 0)
          t.emplace_back(index[e.row()], index[e.col()], e.value());
    SparseMatrix A(n, n);
    A.setFromTriplets(t.begin(), t.end());
    // Newton's direction where K_ff is positive definite; else shifted towards the gradient
    // (a slack or sharply bent point), which keeps it a descent direction of Pi.
    Eigen::VectorXd d;
    const double scale = A.diagonal().cwiseAbs().maxCoeff();
    for (double shift = 0.0; shift <= scale; shift = shift > 0.0 ? 10.0 * shift : 1e-10 * scale) {
      SparseMatrix As = A;
      if (shift > 0.0) {
        SparseMatrix I(n, n);
        I.setIdentity();
        As += shift * I;
      }
      ldlt.compute(As);
      if (ldlt.info() != Eigen::Success || (ldlt.vectorD().array() <= 0.0).any()) continue;
      d = ldlt.solve(r);
      if (d.allFinite() && d.dot(r) > 0.0) break;
      d.resize(0);
    }
    if (d.size() == 0) break;
    // Backtracking on Pi (Armijo), the full step first; within kLineSearchBelow of the
    // minimum, where Pi's change drowns in its round-off, the full Newton step.
    Eigen::VectorXd trial = x;
    double step = 1.0;
    const bool near = d.cwiseAbs().maxCoeff() < kLineSearchBelow;
    const double pi0 = near ? 0.0 : potential(rope, x), slope = -d.dot(r);
    bool accepted = near;
    for (int k = 0; k < 40; ++k, step *= 0.5) {
      for (int i = 0; i < rope.dofs(); ++i)
        if (index[i] >= 0) trial(i) = x(i) + step * d(index[i]);
      if (near) break;
      const double pi = potential(rope, trial);
      if (std::isfinite(pi) && pi <= pi0 + 1e-4 * step * slope) {
        accepted = true;
        break;
      }
    }
    if (!accepted) break;
    x = trial;
    if (step == 1.0 && d.cwiseAbs().maxCoeff() < settings.position_tolerance) {
      q = x;
      return it + 1;
    }
  }
  throw NumericalFailure(
      "the rope between its held top and hook (initial.mode: landed) did not settle into its "
      "static equilibrium in " +
      std::to_string(settings.max_iterations) + " Newton iterations");
}

}  // namespace crane_twin
