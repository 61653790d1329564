// The one rule that picks a scene's rope model (ropeModelOf, simulation.hpp): makeSimulation
// builds what it names, and crane_sim info's integrated coordinates are the built run's.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "crane_twin/io/scene.hpp"
#include "crane_twin/simulation/crane_model.hpp"
#include "crane_twin/simulation/crane_simulation.hpp"
#include "crane_twin/simulation/invariant_reduced_simulation.hpp"
#include "crane_twin/simulation/pendulum_crane_simulation.hpp"
#include "crane_twin/simulation/subdomain_reduced_simulation.hpp"

namespace crane_twin {
namespace {

const std::string kScenes = std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/";

CraneModel model(const std::string& scene, std::vector<std::string> sets) {
  sets.push_back("rope.elements=20");
  return buildCraneModel(loadScene(kScenes + scene, sets));
}

TEST(RopeModelChoice, EachSettingBuildsTheModelItNames) {
  struct Case {
    std::vector<std::string> sets;
    RopeModelKind kind;
  };
  const std::vector<Case> cases = {
      {{"rope.model=full"}, RopeModelKind::full},
      {{"rope.model=reduced"}, RopeModelKind::invariant_reduced},
      {{"rope.model=reduced", "rope.reduction=subdomains"}, RopeModelKind::subdomain_reduced},
      {{"rope.model=pendulum"}, RopeModelKind::pendulum},
      // A rigging under the hook block: the default reduced rope carries it, the subdomain
      // reducer runs it at full order.
      {{"rope.model=reduced", "hook.mass=200", "hook.rigging_length=3"},
       RopeModelKind::invariant_reduced},
      {{"rope.model=reduced", "rope.reduction=subdomains", "hook.mass=200",
        "hook.rigging_length=3"},
       RopeModelKind::full},
      {{"rope.model=pendulum", "hook.mass=200", "hook.rigging_length=3"}, RopeModelKind::pendulum},
  };
  for (const Case& c : cases) {
    const CraneModel m = model("t8036_combination1.yaml", c.sets);
    EXPECT_EQ(ropeModelOf(m.scene), c.kind) << c.sets.back();
    std::unique_ptr<Simulation> sim = makeSimulation(m);
    switch (c.kind) {
      case RopeModelKind::full:
        EXPECT_NE(dynamic_cast<CraneSimulation*>(sim.get()), nullptr);
        EXPECT_EQ(integratedRopeCoordinates(m), m.ropeDofs());
        break;
      case RopeModelKind::invariant_reduced: {
        auto* s = dynamic_cast<InvariantReducedSimulation*>(sim.get());
        ASSERT_NE(s, nullptr);
        EXPECT_EQ(integratedRopeCoordinates(m), s->solver().coordinates());
        break;
      }
      case RopeModelKind::subdomain_reduced:
        EXPECT_NE(dynamic_cast<SubdomainReducedSimulation*>(sim.get()), nullptr);
        EXPECT_EQ(integratedRopeCoordinates(m), keptRopeModes(m) + 3);
        break;
      case RopeModelKind::pendulum: {
        EXPECT_NE(dynamic_cast<PendulumCraneSimulation*>(sim.get()), nullptr);
        sim->initialize();
        EXPECT_EQ(integratedRopeCoordinates(m), static_cast<int>(sim->fullState().q.size()));
        break;
      }
    }
  }
}

// An off-centre landed start adds its shapes to the basis (docs/model.md "Reduced rope": a
// landed start's shapes): `crane_sim info` counts the coordinates the run integrates, not the
// scene's basis alone; under the trolley nothing is added.
TEST(RopeModelChoice, IntegratedCoordinatesCountALandedStartsShapes) {
  for (const char* offset : {"initial.payload_offset=[2, 0]", "initial.payload_offset=[0, 0]"}) {
    const CraneModel m = model("t8036_off_centre_lift.yaml", {"rope.model=reduced", offset});
    InvariantReducedSimulation sim(m);
    const int scene_basis = sim.solver().coordinates();
    sim.initialize();
    EXPECT_EQ(integratedRopeCoordinates(m), sim.solver().coordinates()) << offset;
    EXPECT_EQ(sim.solver().coordinates(),
              scene_basis + (std::string(offset).find("[2, 0]") != std::string::npos ? 6 : 0))
        << offset;
  }
}

}  // namespace
}  // namespace crane_twin
