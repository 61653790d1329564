#include "crane_twin/integrators/newton_step.hpp"

#include <algorithm>

namespace crane_twin {

Eigen::Vector3d condenseSupport(const RopeSupport& support, const Eigen::Vector3d& rc,
                                const Eigen::VectorXd& rz, Eigen::VectorXd& Azr) {
  Eigen::Vector3d row = rc;
  if (support.size() > 0) {
    Azr = support.solve(rz);
    row += support.pointMotion(Azr);
  }
  return row;
}

double correctSupport(const GeneralizedAlpha& ga, const RopeSupport& support, double h,
                      const Eigen::VectorXd& Azr, const Eigen::Vector3d& dmu, CoupledState& s) {
  if (support.size() == 0) return 0.0;
  const Eigen::VectorXd dz = Azr + support.solvePointForce(dmu);
  ga.correct(h, dz, s.z, s.zd, s.zdd);
  return support.pointMotion(dz).cwiseAbs().maxCoeff();
}

void completeStep(const GeneralizedAlpha& ga, const CoupledState& start, double h, int iterations,
                  CoupledState& s) {
  s.a = ga.nextA(start.qdd, start.a, s.qdd);
  if (s.z.size() > 0) s.za = ga.nextA(start.zdd, start.za, s.zdd);
  s.t += h;
  s.newton_iterations = iterations;
}

void prepareSupportState(const RopeSupport& support, CoupledState& s) {
  const int m = support.size();
  if (s.z.size() != m) s.z = Eigen::VectorXd::Zero(m);
  if (s.zd.size() != m) s.zd = Eigen::VectorXd::Zero(m);
  s.zdd = Eigen::VectorXd::Zero(m);
}

void storeConsistentAccelerations(const RopeSupport& support, const Eigen::VectorXd& qdd,
                                  const Eigen::Vector3d& lambda, const Eigen::VectorXd& Azr,
                                  CoupledState& s) {
  s.qdd = qdd;
  s.a = s.qdd;
  s.lambda = lambda;
  if (support.size() > 0) s.zdd = Azr + support.solvePointForce(s.lambda);
  s.za = s.zdd;
}

double constraintError(const RopeSupport& support, const CoupledState& s) {
  return (s.q.head<3>() - support.point(s.z)).norm();
}

bool newtonStep(const GeneralizedAlpha& ga, RopeSupport& support, const NewtonSettings& newton,
                double h, const RopeIncrement& increment, CoupledState& s, std::string& why,
                NewtonWorkspace& workspace, const Eigen::VectorXd* support_means_z0,
                NewtonMemory* memory) {
  const int m = support.size();
  NewtonWeights w;
  w.mass = ga.massWeight();
  w.damping = ga.gamma * h;
  w.stiffness = ga.beta * h * h;
  const double bh2 = w.stiffness;
  workspace.start = s;  // (assigned into the workspace's storage: no allocation once sized)
  const CoupledState& start = workspace.start;
  ga.predict(h, start.qdd, start.a, s.q, s.v);
  if (m > 0) ga.predict(h, start.zdd, start.za, s.z, s.zd);
  w.G = support_means_z0 ? support.setIterationWeights(1.0, ga.beta * h, 0.5 * bh2)
                         : support.setIterationWeights(w.mass, w.damping, bh2);
  // The step's time for a failure's message (formatted only then: it cost 2 % of a reduced step).
  const auto at = [&] { return "t = " + std::to_string(start.t + h) + " s"; };
  Eigen::VectorXd Azr, dq;
  Eigen::Vector3d dmu;
  Eigen::VectorXd rz;
  double previous = 0.0;        // the previous correction's max |dq|, |D dz| (0: none yet)
  double step_constant = -1.0;  // largest d_k / d_(k-1)^2 so far (negative: none yet)
  double step_rate = -1.0;      // largest d_k / d_(k-1) so far (negative: none yet)
  for (int it = 0; it < newton.max_iterations; ++it) {
    if (m > 0) {
      // The support's equation at the step's end, or at an energy-consistent step's means.
      const Eigen::VectorXd f = support_means_z0
                                    ? support.internalForce(0.5 * (*support_means_z0 + s.z),
                                                            (s.z - *support_means_z0) / h, s.zdd)
                                    : support.internalForce(s.z, s.zd, s.zdd);
      rz = -bh2 * (f - support.pointForceToCoordinates(s.lambda));
    }
    const Eigen::Vector3d rc =
        condenseSupport(support, -(s.q.head<3>() - support.point(s.z)), rz, Azr);
    if (!increment(s, w, rc, dq, dmu, why)) {
      why = at() + ": " + why;
      s = start;
      return false;
    }
    ga.correct(h, dq, s.q, s.v, s.qdd);
    s.lambda += dmu / bh2;
    const double dmax =
        std::max(dq.cwiseAbs().maxCoeff(), correctSupport(ga, support, h, Azr, dmu, s));
    if (!s.q.allFinite() || !s.z.allFinite() || !s.lambda.allFinite()) {
      why = at() + ": non-finite state";
      s = start;
      return false;
    }
    // The step's quadratic constant d_k / d_(k-1)^2 (header), largest of its corrections.
    if (previous > 0.0) {
      step_constant = std::max(step_constant, dmax / (previous * previous));
      step_rate = std::max(step_rate, dmax / previous);
    }
    const auto constraint_met = [&] {
      return constraintError(support, s) < newton.constraint_tolerance;
    };
    if (dmax < newton.position_tolerance && constraint_met()) {
      if (memory && step_constant >= 0.0) memory->quadratic_constant = step_constant;
      if (memory && step_rate >= 0.0) {
        memory->contraction_rate = step_rate;
        memory->foreseen_steps = 0;
      }
      completeStep(ga, start, h, it + 1, s);
      return true;
    }
    // DASSL's test on the first correction (NewtonSettings::accept_foreseen_first_correction):
    // what the remaining corrections add up to, at most rho / (1 - rho) d_0.
    if (it == 0 && newton.accept_foreseen_first_correction && memory &&
        memory->first_correction_kept_branches && memory->foreseen_steps < kMaxForeseenSteps &&
        memory->contraction_rate < 1.0 &&
        memory->contraction_rate / (1.0 - memory->contraction_rate) * dmax <
            newton.position_tolerance &&
        constraint_met()) {
      ++memory->foreseen_steps;
      completeStep(ga, start, h, 1, s);
      return true;
    }
    // Quadratic contraction with the next correction foreseen below the tolerance (header):
    // observed in this step, or after the first correction from the last step's constant.
    const bool foreseen = previous > 0.0 ? dmax <= kKeepMatrixContraction * previous &&
                                               dmax * dmax < newton.position_tolerance * previous
                                         : memory && memory->quadratic_constant * dmax * dmax <
                                                         newton.position_tolerance;
    w.keep_matrix = newton.reuse_matrix_near_convergence && !w.keep_matrix && foreseen;
    w.keep_foreseen_from_last_step = w.keep_matrix && previous == 0.0;
    previous = dmax;
  }
  why = at() + ": Newton did not converge in " + std::to_string(newton.max_iterations) +
        " iterations";
  s = start;
  return false;
}

}  // namespace crane_twin
