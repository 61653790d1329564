// Wind (docs/model.md "Wind"): the payload's deflection against atan(F / W), the structure's
// static response against a direct K u = F solve, the Kaimal gusts' statistics and seed, the
// 3 s mean and its warning bit, and the scene keys.
#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <cmath>
#include <fstream>
#include <memory>

#include "crane_twin/io/input_error.hpp"
#include "crane_twin/io/scene.hpp"
#include "crane_twin/loads/wind_field.hpp"
#include "crane_twin/loads/wind_loads.hpp"
#include "crane_twin/simulation/crane_model.hpp"
#include "crane_twin/simulation/simulation.hpp"
#include "crane_twin/simulation/supported_rope_simulation.hpp"
#include "crane_twin/structure/structure_support.hpp"

using namespace crane_twin;

namespace {
const std::string kData = std::string(CRANE_TWIN_SOURCE_DIR) + "/test/data/";
const std::string kScenes = std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/";

// An anchored, almost massless rope (mu 1 g/m) with 3.6 t: the chord angle of a steady wind on
// the payload alone is atan(F / W), F = 0.5 rho Cd A U(z_p)^2, z_p = 100 m - 60 m.
std::string payloadWindScene() {
  const std::string path = testing::TempDir() + "wind_payload.yaml";
  std::ofstream(path) << "crane: none\nanchor: [0, 0, 100]\nduration: 2.0\ntime_step: 0.005\n"
                         "rope: {model: full, elements: 20, length: 60.0, falls: 1, "
                         "mass_per_length: 0.001, bending_stiffness: 0}\n"
                         "payload: {mass: 3600.0}\n"
                         "wind: {speed: 20, direction_deg: 30, profile_exponent: 0.14, "
                         "rope_drag_coefficient: 0, payload: {area: 10, drag_coefficient: 1.2}}\n";
  return path;
}
}  // namespace

TEST(Wind, SteadyWindOnThePayloadDeflectsTheRopeByAtanFOverW) {
  const double U = 20.0 * std::pow(40.0 / 10.0, 0.14);
  const double F = 0.5 * 1.25 * 1.2 * 10.0 * U * U, W = 3600.0 * 9.81 + 0.001 * 60.0 * 9.81 / 2;
  for (const char* model : {"full", "pendulum", "reduced"}) {
    SCOPED_TRACE(model);
    std::unique_ptr<Simulation> sim = makeSimulation(
        buildCraneModel(loadScene(payloadWindScene(), {std::string("rope.model=") + model})));
    sim->initialize();
    for (int k = 0; k <= 400; ++k) {
      if (k % 100 == 0) {
        const Eigen::Vector3d p = sim->series().payload;
        const double angle = std::atan2(std::hypot(p.x(), p.y()), 100.0 - p.z());
        EXPECT_NEAR(angle, std::atan(F / W), 2e-6) << "t " << sim->time();  // starts and stays
        EXPECT_NEAR(std::atan2(p.y(), p.x()), M_PI / 6.0, 1e-9);
      }
      sim->step();
    }
  }
}

TEST(Wind, StructuresStaticResponseIsTheDirectSolveOfKuEqualsF) {
  // Wind on the structure alone (no payload area, no rope drag): the jib tip's displacement less
  // the windless run's is T K^-1 F, F from the members' drag, K the structure's stiffness.
  const std::string scene = kScenes + "t8036_wind.yaml";
  const std::vector<std::string> alone = {"wind.payload.area=0", "wind.rope_drag_coefficient=0",
                                          "wind.gust.intensity=0", "duration=0.1"};
  const CraneModel m = buildCraneModel(loadScene(scene, alone));
  const TowerCraneStructure& st = *m.structure;
  const WindField w(*m.scene.wind, 1.0);
  const Eigen::VectorXd F = structureWindLoad(st, w, m.scene.slew_angle);
  Eigen::SimplicialLDLT<SparseMatrix> ldlt(st.K);
  ASSERT_EQ(ldlt.info(), Eigen::Success);
  const Eigen::VectorXd u = ldlt.solve(F);
  Eigen::Vector3d tip = Eigen::Vector3d::Zero();
  for (int n : st.jib_tip_nodes)
    for (int d = 0; d < 3; ++d) tip(d) += u(st.dof_equation[6 * n + d]) / st.jib_tip_nodes.size();
  ASSERT_GT(tip.norm(), 0.1);
  auto tipOf = [&](const std::string& structure, double speed) {
    std::vector<std::string> o = alone;
    o.push_back("structure.model=" + structure);
    o.push_back("wind.speed=" + std::to_string(speed));
    std::unique_ptr<Simulation> sim = makeSimulation(buildCraneModel(loadScene(scene, o)));
    sim->initialize();
    return Eigen::Vector3d(sim->series().jib_tip);
  };
  const Eigen::Vector3d full = tipOf("full", m.scene.wind->speed) - tipOf("full", 0.0);
  EXPECT_LT((full - tip).norm(), 1e-6 * tip.norm())
      << full.transpose() << " vs " << tip.transpose();
  // 100 modes: the static response truncated to the lowest modes.
  const Eigen::Vector3d modal = tipOf("modal", m.scene.wind->speed) - tipOf("modal", 0.0);
  EXPECT_LT((modal - tip).norm(), 1e-3 * tip.norm())
      << modal.transpose() << " vs " << tip.transpose();
  double Fy = 0.0;
  for (std::size_t n = 0; n < st.nodes.size(); ++n)
    if (st.dof_equation[6 * n + 1] >= 0) Fy += F(st.dof_equation[6 * n + 1]);
  std::printf(
      "wind on the structure %.1f kN (free nodes); jib tip K u = F %.4f %.4f %.4f m; "
      "full %.2e, 100 modes %.2e relative\n",
      Fy / 1e3, tip.x(), tip.y(), tip.z(), (full - tip).norm() / tip.norm(),
      (modal - tip).norm() / tip.norm());
}

TEST(Wind, StructuresLoadPatternsGiveTheMembersLoadAtAnySlewingAngleAndWind) {
  // structureWindPatterns: P w(v) against the pass over the members, for the scene's profile
  // and a uniform one, a scene wind and a measured one, at slewing angles all round.
  const CraneModel m = buildCraneModel(loadScene(kScenes + "t8036_wind.yaml", {"duration=0.1"}));
  const TowerCraneStructure& st = *m.structure;
  const double jib = 60.0;
  for (double alpha : {m.scene.wind->profile_exponent, 0.0, 0.3}) {
    WindSettings ws = *m.scene.wind;
    ws.profile_exponent = alpha;
    const StructureWindPatterns p = structureWindPatterns(st, alpha, jib);
    // Members share their axes: a lattice has few directions.
    ASSERT_GT(p.axes.size(), 3u);
    EXPECT_LT(p.axes.size(), st.members.size() / 4) << p.axes.size() << " axes";
    if (alpha == 0.0) std::printf("%zu members on %zu axes\n", st.members.size(), p.axes.size());
    for (int measured = 0; measured < 2; ++measured) {
      WindField w(ws, jib);
      if (measured) w.setMeasured(Eigen::Vector3d(-7.5, 11.0, 0.0));
      for (double theta : {0.0, 0.37, 1.9, -2.6, 3.1}) {
        const Eigen::VectorXd f = structureWindLoad(st, w, theta);
        const Eigen::Vector3d v = slewRotation(theta).transpose() * w.meanVelocity(jib);
        const Eigen::VectorXd g = p.patterns * structureWindWeights(p, v);
        ASSERT_GT(f.norm(), 0.0);
        EXPECT_LT((g - f).norm(), 1e-12 * f.norm())
            << "alpha " << alpha << " measured " << measured << " theta " << theta;
      }
    }
  }
  EXPECT_THROW(structureWindPatterns(st, -0.1, jib), std::invalid_argument);
  EXPECT_THROW(structureWindPatterns(st, 0.14, 0.0), std::invalid_argument);
}

TEST(Wind, ASlewingCranesStructureLoadIsTheMembersAtItsAngle) {
  // The simulation's external load while it slews in wind: T^T f(theta), f the members' drag at
  // the drives' slewing angle of the step (unit gust), for the full structure (T = I) and the
  // modal one (T = Phi).
  for (const char* model : {"full", "modal"}) {
    SCOPED_TRACE(model);
    const CraneModel m = buildCraneModel(
        loadScene(kScenes + "t8036_slew90.yaml",
                  {"duration=1", "rope.elements=10", "rope.model=pendulum", "wind.speed=14",
                   "wind.direction_deg=75", "wind.gust.intensity=0",
                   std::string("structure.model=") + model}));
    std::unique_ptr<Simulation> sim = makeSimulation(m);
    sim->initialize();
    const WindField w(*m.scene.wind, windJibHeight(m));
    const auto* support = dynamic_cast<const StructureSupportBase*>(&sim->support());
    ASSERT_NE(support, nullptr);
    double turned = 0.0;
    for (int k = 0; k < 400; ++k) {
      sim->step();
      if (k % 50 != 49) continue;
      const double theta = sim->drives().slewAngle();
      turned = std::max(turned, std::abs(theta - m.scene.slew_angle));
      Eigen::VectorXd f = structureWindLoad(*m.structure, w, theta);
      if (m.structure_modal_basis && m.scene.structure_model == StructureModel::modal)
        f = m.structure_modal_basis->phi.transpose() * f;
      ASSERT_EQ(support->externalLoad().size(), f.size());
      EXPECT_LT((support->externalLoad() - f).norm(), 1e-12 * f.norm()) << "t " << sim->time();
    }
    EXPECT_GT(turned, 0.01);  // it slewed
  }
}

TEST(Wind, ReducedRopeFollowsTheFullOrderOneInWindOnAFlexibleCrane) {
  // Gusty wind on the structure, rope and payload while the load swings 20 deg: the wind is
  // taken where the reduced run's own support stands (it was taken at the full model's idle
  // state once, 9 mm apart after 20 s and 1.9 cm after 60 s).
  const std::vector<std::string> o = {"duration=20", "rope.elements=40", "initial.swing_deg=20",
                                      "payload.mass=8000", "trolley.radius=50"};
  auto run = [&](const char* model) {
    std::vector<std::string> oo = o;
    oo.push_back(std::string("rope.model=") + model);
    std::unique_ptr<Simulation> sim =
        makeSimulation(buildCraneModel(loadScene(kScenes + "t8036_wind.yaml", oo)));
    sim->initialize();
    std::vector<Eigen::Vector3d> p;
    for (int k = 0; k < 4000; ++k) {
      sim->step();
      if (k % 100 == 99) p.push_back(sim->series().payload);
    }
    return p;
  };
  const std::vector<Eigen::Vector3d> full = run("full"), reduced = run("reduced");
  double worst = 0.0;
  for (std::size_t i = 0; i < full.size(); ++i)
    worst = std::max(worst, (full[i] - reduced[i]).norm());
  EXPECT_LT(worst, 1e-4) << "reduced against full payload";
}

TEST(Wind, KaimalGustsHaveUnitVarianceTheSpectrumsShapeAndTheirSeed) {
  WindSettings s;
  s.speed = 12.0;
  s.gust_intensity = 0.15;
  s.gust_seed = 7;
  const WindField w(s, 60.0), again(s, 60.0);
  s.gust_seed = 8;
  const WindField other(s, 60.0);
  const int N = kGustSamples;
  double mean = 0.0, var = 0.0, diff = 0.0;
  for (int j = 0; j < N; ++j) {
    const double n = w.gust(j * kGustSampleStep);
    mean += n / N;
    var += n * n / N;
    EXPECT_EQ(n, again.gust(j * kGustSampleStep));
    diff += std::abs(n - other.gust(j * kGustSampleStep)) / N;
  }
  EXPECT_NEAR(mean, 0.0, 1e-12);
  EXPECT_NEAR(var, 1.0, 1e-9);  // Parseval over one period: the discrete spectrum sums to 1
  EXPECT_GT(diff, 0.3);         // another seed, another series
  const double U = w.meanSpeed(60.0);
  // The structure function at lag tau against its spectral closed form
  // D(tau) = 2 int S(f) (1 - cos 2 pi f tau) df over the synthesised band, S normalised there.
  for (double tau : {0.5, 5.0, 50.0}) {
    double D = 0.0;
    const int lag = static_cast<int>(std::round(tau / kGustSampleStep));
    for (int j = 0; j < N; ++j) {
      const double d = w.gust((j + lag) * kGustSampleStep) - w.gust(j * kGustSampleStep);
      D += d * d / N;
    }
    double expect = 0.0, total = 0.0;
    const double df = 1.0 / (N * kGustSampleStep);
    for (int k = 1; k < N / 2; ++k) {
      const double f = k * df, S = w.kaimal(f);
      expect += 2.0 * S * (1.0 - std::cos(2.0 * M_PI * f * tau)) * df;
      total += S * df;
    }
    expect /= total;
    SCOPED_TRACE(tau);
    EXPECT_NEAR(D, expect, 0.15 * expect);  // one realisation: its own scatter
  }
  // The wind itself: U(z) (1 + I n(t)) along the direction.
  EXPECT_NEAR(w.velocity(60.0, 3.3).x(), U * (1.0 + 0.15 * w.gust(3.3)), 1e-12);
}

TEST(Wind, ThreeSecondMeanAtTheJibAndItsWarning) {
  WindSettings s;
  s.speed = 20.0;
  s.profile_exponent = 0.0;
  WindField w(s, 50.0);
  double m = 0.0;
  for (int k = 0; k <= 500; ++k) m = w.recordJibSpeed(0.01 * k);
  EXPECT_NEAR(m, 20.0, 1e-12);
  // A measured 30 m/s from t = 5 s: after 1.5 s the 3 s mean is halfway between.
  w.setMeasured(Eigen::Vector3d(0.0, 30.0, 0.0));
  for (int k = 1; k <= 150; ++k) m = w.recordJibSpeed(5.0 + 0.01 * k);
  EXPECT_NEAR(m, (151 * 20.0 + 150 * 30.0) / 301.0, 1e-9);
  // In a run: over the 20 m/s limit at the jib the bit is set, under it not.
  for (double speed : {14.0, 18.0}) {
    const std::vector<std::string> o = {"wind.speed=" + std::to_string(speed),
                                        "wind.gust.intensity=0", "duration=0.1"};
    std::unique_ptr<Simulation> sim =
        makeSimulation(buildCraneModel(loadScene(kScenes + "t8036_wind.yaml", o)));
    sim->initialize();
    sim->step();
    const SeriesValues v = sim->series();
    const double jib = speed * std::pow(v.trolley.z() / 10.0, 0.14);
    SCOPED_TRACE(speed);
    EXPECT_GT(v.wind_3s, 0.9 * jib);
    EXPECT_EQ((v.warnings & kWindOverInServiceLimit) != 0, v.wind_3s > 20.0);
  }
}

TEST(Wind, MeasuredWindReplacesTheScenesAndBadInputIsRefused) {
  std::unique_ptr<Simulation> sim = makeSimulation(buildCraneModel(loadScene(payloadWindScene())));
  sim->initialize();
  MeasuredWindInput& wind = requireCapability<MeasuredWindInput>(*sim);
  EXPECT_THROW(wind.setMeasuredWind(Eigen::Vector3d(std::nan(""), 0, 0)), std::invalid_argument);
  wind.setMeasuredWind(Eigen::Vector3d(0.0, 0.0, 0.0));  // calm: the payload swings back
  for (int k = 0; k < 200; ++k) sim->step();
  EXPECT_LT(sim->series().payload_velocity.norm(), 5.0);
  const std::string p = payloadWindScene();
  EXPECT_THROW(loadScene(p, {"wind.speed=-1"}), InputError);
  EXPECT_THROW(loadScene(p, {"wind.gust.intensity=2"}), InputError);
  EXPECT_THROW(loadScene(p, {"wind.gust.seed=1"}), InputError);  // intensity is required
  EXPECT_THROW(loadScene(p, {"wind.speeed=1"}), InputError);
  EXPECT_THROW(loadScene(p, {"anchor=[0, 0, 0]"}), InputError);
  EXPECT_THROW(
      loadScene(kScenes + "t8036_wind.yaml", {"rope.model=reduced", "rope.reduction=subdomains"}),
      InputError);
  EXPECT_THROW(WindField(WindSettings{}, 0.0), std::invalid_argument);
}
