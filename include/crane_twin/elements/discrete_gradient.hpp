// Discrete gradients of strain energies over one time step (docs/model.md "Energy-consistent
// step"; Gonzalez, J. Nonlinear Sci. 6, 1996; Simo & Tarnow, ZAMP 43, 1992).
//
// A discrete gradient of U between x0 and x1 is a vector G(x0, x1) with
//   G . (x1 - x0) = U(x1) - U(x0)   exactly,   G(x, x) = grad U(x).
// An implicit step that uses G in place of the force at the step's end makes the work of the
// elastic forces equal the energy change, whatever U is: a one-sided (tension-only) law switching
// from taut to slack inside the step creates no energy.
//
// Energies of a squared length s = |d|^2 (the axial law of a cable point, d = r_x, or of a bar,
// d = r_1 - r_0) take the secant in s: s is quadratic in d, so s1 - s0 = 2 d_m . (d1 - d0) with
// d_m = (d0 + d1) / 2 holds exactly and G = 2 Sbar d_m, Sbar = (W(s1) - W(s0)) / (s1 - s0).
#pragma once

#include <cmath>

namespace crane_twin {

/// The secant of W(s) over s0 -> s1 and its change with s1:
///   slope     Sbar  = (W(s1) - W(s0)) / (s1 - s0),
///   curvature kappa = (W'(s1) - Sbar) / (s1 - s0)    (d Sbar / d s1),
/// or W'(s_m) and W''(s_m) / 2, their limits, where |s1 - s0| <= kSquaredLengthSecantTiny (the
/// difference of W would then be round-off). For a convex W, kappa >= 0.
struct SquaredLengthSecant {
  double slope = 0.0;
  double curvature = 0.0;
};

/// Below this |s1 - s0| [-] the secant is its midpoint limit: the energy error of that is
/// O(W''' ds^3), 1e-24 of W''', while the difference quotient would carry round-off of 1e-16 W /
/// ds.
constexpr double kSquaredLengthSecantTiny = 1e-8;

/// W0 = W(s0), given (the same at every Newton iterate of a step); W, dW, ddW: callables
/// s -> W(s), W'(s), W''(s).
template <class Energy, class Slope, class Curvature>
SquaredLengthSecant squaredLengthSecant(double s0, double W0, double s1, const Energy& W,
                                        const Slope& dW, const Curvature& ddW) {
  SquaredLengthSecant r;
  const double ds = s1 - s0;
  if (std::abs(ds) <= kSquaredLengthSecantTiny) {
    const double sm = 0.5 * (s0 + s1);
    r.slope = dW(sm);
    r.curvature = 0.5 * ddW(sm);
    return r;
  }
  r.slope = (W(s1) - W0) / ds;
  r.curvature = (dW(s1) - r.slope) / ds;
  return r;
}

/// The same with W(s0) evaluated here.
template <class Energy, class Slope, class Curvature>
SquaredLengthSecant squaredLengthSecant(double s0, double s1, const Energy& W, const Slope& dW,
                                        const Curvature& ddW) {
  return squaredLengthSecant(s0, W(s0), s1, W, dW, ddW);
}

}  // namespace crane_twin
