// Convergence of the full-order model: observed order in the time step (generalized-
// alpha is second order, Arnold & Bruls 2007) for the anchored rope and the rope coupled to the
// T8036 structure, and in the element count for the rope's modes against the Bessel closed
// form. The observed orders are printed; the assertions are the theory's orders.
#include <gtest/gtest.h>

#include <boost/math/special_functions/bessel.hpp>
#include <cmath>
#include <cstdio>
#include <vector>

#include "crane_twin/simulation/crane_simulation.hpp"

using namespace crane_twin;

namespace {
const std::string kScenes = std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/";

// Payload positions every `every` seconds over `duration` at time step dt.
std::vector<Eigen::Vector3d> payloadPath(const std::string& scene, std::vector<std::string> sets,
                                         double dt, double duration, double every) {
  sets.push_back("time_step=" + std::to_string(dt));
  const CraneModel m = buildCraneModel(loadScene(kScenes + scene, sets));
  CraneSimulation sim(m);
  sim.initialize();
  std::vector<Eigen::Vector3d> path;
  const long steps = std::lround(duration / dt), stride = std::lround(every / dt);
  for (long k = 1; k <= steps; ++k) {
    sim.step();
    if (k % stride == 0)
      path.push_back(AncfRope::nodePosition(sim.state().q, sim.rope().nodes() - 1));
  }
  return path;
}

double maxDistance(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b) {
  double e = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) e = std::max(e, (a[i] - b[i]).norm());
  return e;
}

// Errors at dt = h0, h0/2, h0/4 against h0/16; returns the observed orders log2(e(2h)/e(h)).
std::vector<double> timeStepOrders(const std::string& label, const std::string& scene,
                                   const std::vector<std::string>& sets, double h0,
                                   double duration) {
  const auto ref = payloadPath(scene, sets, h0 / 16, duration, h0);
  std::vector<double> err, orders;
  for (double dt : {h0, h0 / 2, h0 / 4}) {
    err.push_back(maxDistance(payloadPath(scene, sets, dt, duration, h0), ref));
  }
  for (std::size_t i = 1; i < err.size(); ++i) orders.push_back(std::log2(err[i - 1] / err[i]));
  std::printf(
      "%s: max payload error %.3g / %.3g / %.3g m at dt %g / %g / %g ms; orders %.2f, %.2f\n",
      label.c_str(), err[0], err[1], err[2], 1e3 * h0, 500 * h0, 250 * h0, orders[0], orders[1]);
  return orders;
}
}  // namespace

TEST(Convergence, TimeStepOrderIsTwoForTheAnchoredRope) {
  const auto orders =
      timeStepOrders("anchored rope (30 elements, 2 s)", "rope_pendulum_chrono.yaml",
                     {"rope.elements=30", "initial.mode=equilibrium"}, 0.008, 2.0);
  for (double p : orders) EXPECT_GT(p, 1.8);
}

TEST(Convergence, TimeStepOrderIsTwoForTheRopeOnTheT8036Structure) {
  const auto orders =
      timeStepOrders("T8036 modal (20 modes, 20 elements, 1 s)", "t8036_combination1.yaml",
                     {"rope.model=full", "structure.modes=20", "rope.elements=20"}, 0.004, 1.0);
  for (double p : orders) EXPECT_GT(p, 1.8);
}

TEST(Convergence, ElementCountOrderOfTheHangingChainModes) {
  // Hanging chain without tip mass or bending: f_n = j0_n / (4 pi) sqrt(g / L). The sixth
  // lateral mode (the 11th eigenvalue: modes come in x/y pairs) resolves a short wave, so its
  // error is well above round-off for 4..32 elements. The closed form is the inextensible
  // chain's and the element's convergence is the point: the symmetric axial law (a tension-only
  // law's band would take the axial stiffness off the unloaded free end).
  const double L = 60.0, g = 9.81;
  const double exact = boost::math::cyl_bessel_j_zero(0.0, 6) / 2.0 * std::sqrt(g / L);
  std::vector<double> err;
  for (int n : {4, 8, 16, 32}) {
    const CraneModel m = buildCraneModel(
        loadScene(kScenes + "rope_pendulum_chrono.yaml",
                  {"payload.mass=0", "rope.bending=false", "rope.tension_only=false",
                   "rope.elements=" + std::to_string(n)}));
    CraneSimulation sim(m);
    const ModalBasis b = sim.ropeModes(12);
    err.push_back(std::abs(std::sqrt(b.omega2(10)) - exact) / exact);
  }
  std::printf(
      "hanging chain 6th mode relative error at 4/8/16/32 elements: %.3g %.3g %.3g %.3g;"
      " orders",
      err[0], err[1], err[2], err[3]);
  for (std::size_t i = 1; i < err.size(); ++i) std::printf(" %.2f", std::log2(err[i - 1] / err[i]));
  std::printf("\n");
  // Cubic Hermite elements for a second-order operator: at least the O(h^2) of linear elements;
  // the zero tension at the free end keeps it below the smooth-problem O(h^6).
  for (std::size_t i = 1; i < err.size(); ++i) EXPECT_GT(std::log2(err[i - 1] / err[i]), 2.0);
  EXPECT_LT(err.back(), 1e-4);
}
