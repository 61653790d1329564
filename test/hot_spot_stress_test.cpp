// Stresses at the crane's hot spots (include/crane_twin/structure/hot_spot_stress.hpp,
// docs/fatigue.md) against the lattice's closed forms, and as a run reads them.
#include "crane_twin/structure/hot_spot_stress.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "crane_twin/io/input_error.hpp"
#include "crane_twin/io/scene.hpp"
#include "crane_twin/simulation/crane_model.hpp"
#include "crane_twin/structure/geometric_stiffness.hpp"

namespace crane_twin {
namespace {

const std::string kCrane = std::string(CRANE_TWIN_SOURCE_DIR) + "/config/cranes/t8036.yaml";
constexpr double kPi = 3.14159265358979323846;

HotSpotSpec spot(const std::string& name, const Eigen::Vector3d& point,
                 const Eigen::Vector3d& along, const Eigen::Vector3d& fibre) {
  HotSpotSpec s;
  s.name = name;
  s.point = point;
  s.along = along;
  s.fibre = fibre;
  s.detail_category = 71.0;
  return s;
}

// The structure's displacement under a weight F [N] hanging at the trolley at radius R.
Eigen::VectorXd underTrolleyLoad(const TowerCraneStructure& st, double F, double R) {
  return staticDisplacement(st, st.pointForce(st.trolleyWeights(R), Eigen::Vector3d(0, 0, -F)));
}

TEST(HotSpotStress, TheMastFootChordCarriesTheLoadMomentAsTheLatticeClosedForm) {
  // A weight F at radius R: the mast's moment M = F R is carried by its chords, b apart, the
  // two jib-side ones each compressed by M / (2 b) and all four by F / 4:
  //   d sigma_axial = -F R / (2 b A) - F / (4 A).
  // The chord's axial stress is the mean over two opposite fibres. The outer fibre adds the
  // chord's own bending as it curves with the mast (rigid joints): kappa = M / (E I_mast),
  // I_mast = A b^2, so E kappa (D / 2) = sigma_axial (D / 2) / (b / 2) (11 % for the T8036).
  const CraneDescription crane = loadCraneDescription(kCrane);
  const TowerCraneStructure st = TowerCraneStructure::build(crane);
  const double b = crane.mast_width, D = crane.mast_chord.outer_diameter;
  const double t = crane.mast_chord.wall;
  const double A = 0.25 * kPi * (D * D - (D - 2 * t) * (D - 2 * t));
  const Eigen::Vector3d foot(0.5 * b, 0.5 * b, 0.0);
  const std::vector<HotSpotRow> rows =
      hotSpotRows(st, {spot("outer", foot, Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX()),
                       spot("inner", foot, Eigen::Vector3d::UnitZ(), -Eigen::Vector3d::UnitX())});
  for (double R : {30.0, 80.0}) {
    const double F = 4000.0 * 9.81;
    const Eigen::VectorXd u = underTrolleyLoad(st, F, R);
    const double outer = rows[0].stress(u), inner = rows[1].stress(u);
    const double axial = 0.5 * (outer + inner);
    const double closed = -F * R / (2.0 * b * A) - F / (4.0 * A);
    std::printf("mast foot, %g m: axial %.3f MPa, closed form %.3f MPa; outer fibre %.3f MPa\n", R,
                axial * 1e-6, closed * 1e-6, outer * 1e-6);
    EXPECT_NEAR(axial, closed, 0.1 * std::abs(closed)) << R;
    const double bending = outer - axial, expected = axial * (0.5 * D) / (0.5 * b);
    EXPECT_NEAR(bending, expected, 0.25 * std::abs(expected)) << R;
  }
}

TEST(HotSpotStress, TheJibsTopChordPullsAndTheMastsJibSideChordsPush) {
  const CraneDescription crane = loadCraneDescription(kCrane);
  const TowerCraneStructure st = TowerCraneStructure::build(crane);
  ASSERT_EQ(crane.hot_spots.size(), 4u);
  const std::vector<HotSpotRow> rows = hotSpotRows(st, crane.hot_spots);
  const Eigen::VectorXd u = underTrolleyLoad(st, 4000.0 * 9.81, 40.0);
  for (const HotSpotRow& r : rows) {
    const double sigma = r.stress(u);
    if (r.name == "jib_root") {
      EXPECT_GT(sigma, 1e6) << r.name;
    }
    if (r.name == "mast_foot" || r.name == "mast_top") {
      EXPECT_LT(sigma, -1e6) << r.name;
    }
    EXPECT_TRUE(std::isfinite(sigma));
    EXPECT_EQ(r.detail_category, 71.0);
  }
}

TEST(HotSpotStress, ARunReadsThemFromItsCoordinatesAsTheRowsDoFromTheDisplacement) {
  // The model's table (sigma_sw + S Phi z for the modal structure, sigma_sw + S z for the full
  // one) against the rows on the displacement Phi z plus the self-weight's.
  for (const char* structure : {"modal", "full"}) {
    const CraneModel m = buildCraneModel(
        loadScene(std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/t8036_live.yaml",
                  {std::string("structure.model=") + structure, "rope.elements=10"}));
    ASSERT_TRUE(m.hot_spots) << structure;
    const TowerCraneStructure& st = *m.structure;
    const bool modal = std::string(structure) == "modal";
    const int n = modal ? static_cast<int>(m.structure_modal_basis->phi.cols()) : st.free_dofs;
    Eigen::VectorXd z = Eigen::VectorXd::LinSpaced(n, -1e-3, 2e-3);
    const Eigen::VectorXd u = (modal ? Eigen::VectorXd(m.structure_modal_basis->phi * z) : z) +
                              staticDisplacement(st, selfWeightLoad(st, m.scene.gravity));
    const Eigen::VectorXd table = m.hot_spots->stresses(z);
    for (std::size_t i = 0; i < m.hot_spots->rows.size(); ++i) {
      const double direct = m.hot_spots->rows[i].stress(u);
      EXPECT_NEAR(table(i), direct, 1e-9 * std::abs(direct) + 1e-3) << structure << " " << i;
    }
  }
  // A rigid structure has no stresses to give.
  const CraneModel rigid = buildCraneModel(
      loadScene(std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/t8036_live.yaml",
                {"structure.model=rigid", "rope.elements=10"}));
  EXPECT_FALSE(rigid.hot_spots);
}

TEST(HotSpotStress, AHotSpotWithoutAMemberIsRefusedByName) {
  const TowerCraneStructure st = TowerCraneStructure::build(loadCraneDescription(kCrane));
  try {
    hotSpotRows(st, {spot("nowhere", Eigen::Vector3d(0, 0, 10), Eigen::Vector3d(0.3, 0.2, 0.93),
                          Eigen::Vector3d::UnitX())});
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("nowhere"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace crane_twin
