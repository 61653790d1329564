// Scene loader validation (docs/scenes.md): each malformed input class is refused with a message
// that names the file and the key.
#include "crane_twin/io/scene.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "crane_twin/io/config_reader.hpp"
#include "crane_twin/io/input_error.hpp"
#include "crane_twin/simulation/crane_model.hpp"

using namespace crane_twin;

namespace {

const std::string kScenes = std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/";

// Write a scene into the test's temporary folder and return its path.
std::string writeScene(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "crane_twin_scene_" + name;
  std::ofstream(path) << text;
  return path;
}

const char* kGood = R"(crane: none
anchor: [0, 0, 0]
duration: 1.0
time_step: 0.01
rope: {model: full, elements: 10, length: 20.0, falls: 1}
payload: {mass: 100.0}
initial: {mode: stress_free, swing_deg: 5.0}
)";

// Expect loadScene(path, overrides) to throw an InputError whose message contains each needle.
void expectRefused(const std::string& path, const std::vector<std::string>& overrides,
                   const std::vector<std::string>& needles) {
  try {
    loadScene(path, overrides);
    FAIL() << "expected InputError for overrides " << ::testing::PrintToString(overrides);
  } catch (const InputError& e) {
    for (const auto& n : needles) {
      EXPECT_NE(std::string(e.what()).find(n), std::string::npos)
          << "message '" << e.what() << "' lacks '" << n << "'";
    }
  }
}

}  // namespace

TEST(Scene, ShippedPaperScenesLoad) {
  for (const char* name : {"t8036_combination1", "t8036_combination1_3deg", "t8036_combination2",
                           "t8036_combination2_3deg", "rope_pendulum_chrono"}) {
    const Scene s = loadScene(kScenes + name + ".yaml");
    EXPECT_GT(s.duration, 0.0) << name;
  }
  const Scene c1 = loadScene(kScenes + "t8036_combination1.yaml");
  ASSERT_TRUE(c1.crane.has_value());
  EXPECT_DOUBLE_EQ(c1.trolley_radius, 80.0);
  EXPECT_DOUBLE_EQ(c1.payload_mass, 3600.0);
  EXPECT_DOUBLE_EQ(c1.hookBlockMass(), 2044.0);
  EXPECT_DOUBLE_EQ(c1.rope.mass_per_length, 1.9);  // default from the crane file
  const Scene c2 = loadScene(kScenes + "t8036_combination2.yaml");
  EXPECT_DOUBLE_EQ(c2.trolley_radius, 32.8);
  EXPECT_DOUBLE_EQ(c2.payload_mass, 12500.0);
}

TEST(Scene, DefaultsAndOverrides) {
  const std::string p = writeScene("good.yaml", kGood);
  const Scene s = loadScene(p, {"rope.elements=40", "initial.payload_velocity=[0,0,3]"});
  EXPECT_EQ(s.rope.elements, 40);
  EXPECT_DOUBLE_EQ(s.payload_velocity.z(), 3.0);
  EXPECT_EQ(s.integrator, IntegratorKind::generalized_alpha);
  EXPECT_DOUBLE_EQ(s.rho_inf, 0.9);
  EXPECT_EQ(s.structure_model, StructureModel::rigid);
  EXPECT_DOUBLE_EQ(s.rope.axial_stiffness, 2.2e7);
}

TEST(Scene, WrongTypeIsRefused) {
  const std::string p = writeScene("good.yaml", kGood);
  expectRefused(p, {"rope.elements=abc"}, {p, "rope.elements", "integer"});
  expectRefused(p, {"duration=[1,2]"}, {p, "duration", "number"});
  expectRefused(p, {"rope.bending=maybe"}, {p, "rope.bending", "true or false"});
  expectRefused(p, {"rope=5"}, {p, "rope", "map"});
  expectRefused(p, {"initial.payload_velocity=[0,0]"},
                {p, "initial.payload_velocity", "3 numbers"});
  expectRefused(p, {"rope.elements=2.5"}, {p, "rope.elements"});
}

TEST(Scene, OutOfRangeIsRefused) {
  const std::string p = writeScene("good.yaml", kGood);
  expectRefused(p, {"payload.mass=-1"}, {p, "payload.mass", ">= 0", "-1"});
  expectRefused(p, {"rope.elements=0"}, {p, "rope.elements", "0"});
  expectRefused(p, {"rope.reduction=subdomains", "rope.mode_fraction=0"},
                {p, "rope.mode_fraction", "(0, 1]"});
  expectRefused(p, {"rope.reduction=subdomains", "rope.mode_fraction=1.5"},
                {p, "rope.mode_fraction", "1.5"});
  expectRefused(p, {"time_step=0"}, {p, "time_step"});
  expectRefused(p, {"time_step=.nan"}, {p, "time_step"});
  expectRefused(p, {"duration=.inf"}, {p, "duration"});
  expectRefused(p, {"integrator.rho_inf=1.2"}, {p, "integrator.rho_inf"});
  expectRefused(p, {"rope.model=ancf"}, {p, "rope.model", "pendulum, full, reduced"});
  expectRefused(p, {"rope.subdomain_frame=rotating"},
                {p, "rope.subdomain_frame", "fixed, corotational", "rotating"});
  expectRefused(p, {"rope.subdomain_rotation=0"}, {p, "rope.subdomain_rotation", "0"});
  expectRefused(p, {"time_step=2"}, {p, "time_step", "duration"});
  // Finite but beyond any crane: refused by name, not left to overflow or a numerical failure.
  expectRefused(p, {"duration=1e200"}, {p, "duration", "1e12 steps"});
  expectRefused(p, {"gravity=1e200"}, {p, "gravity", "[0, 100]"});
  expectRefused(p, {"rope.mass_per_length=1e4"}, {p, "rope.mass_per_length", "(0, 100]"});
  expectRefused(p, {"rope.damping=2"}, {p, "rope.damping", "[0, 1]"});
  expectRefused(p, {"rope.bending_stiffness=1e12"}, {p, "rope.bending_stiffness"});
  expectRefused(p, {"wind={speed: 1e200}"}, {p, "wind.speed", "[0, 120]"});
  expectRefused(p, {"wind={speed: 10, payload: {area: 1e200}}"}, {p, "wind.payload.area"});
  expectRefused(p, {"initial.mode=equilibrium", "initial.payload_velocity=[0, 0, 1e3]"},
                {p, "initial.payload_velocity", "50 m/s"});
  const std::string lift = kScenes + "t8036_lift_off_fast.yaml";
  expectRefused(lift, {"initial.payload_offset=[1e200, 0]"},
                {lift, "initial.payload_offset", "1e+200 m", "rope.length", "cannot reach"});
  expectRefused(lift, {"ground.stiffness=1e200"}, {lift, "ground.stiffness", "(0, 1e+14]"});
  // A ground the resting load would sink into by metres (3600 kg and the hook block on 1 N/m).
  expectRefused(lift, {"ground.stiffness=1"}, {lift, "ground.stiffness", "sink", "0.1 m"});
}

TEST(Scene, AHangingWeightNoRopeHoldsIsRefusedNamingItsLargestShare) {
  // W / (n EA) above kMaxStaticStrain (the T8036's rope: 2.2e7 N per fall, 2 falls here).
  const std::string c = kScenes + "t8036_operator_cycle.yaml";
  auto refused = [&](const std::vector<std::string>& sets, const std::string& key) {
    try {
      buildCraneModel(loadScene(c, sets));
      FAIL() << ::testing::PrintToString(sets);
    } catch (const InputError& e) {
      const std::string w = e.what();
      EXPECT_NE(w.find("key '" + key + "'"), std::string::npos) << w;
      EXPECT_NE(w.find("no steel wire rope holds that"), std::string::npos) << w;
    }
  };
  refused({"payload.mass=1e6"}, "payload.mass");
  refused({"hook.mass=1e6"}, "hook.mass");
  refused({"rope.mass_per_length=99", "rope.axial_stiffness=1e5", "payload.mass=0"},
          "rope.mass_per_length");
  // Just under the bound: 10 % of 4.4e7 N is 4.49e5 kg at g = 9.81 (less the hook and rope).
  EXPECT_NO_THROW(buildCraneModel(loadScene(c, {"payload.mass=4e5", "duration=0.1"})));
  refused({"payload.mass=4e5", "rope.falls=1"}, "payload.mass");  // one fall: 18 %
}

TEST(Scene, SubdomainKeysAreRefusedWhereTheDefaultReducedRopeRuns) {
  // They mean nothing to the rotation-invariant basis: refused, not silently ignored.
  const std::string p = writeScene("good.yaml", kGood);
  for (const char* set : {"rope.mode_fraction=0.5", "rope.subdomain_delta=0.1",
                          "rope.mode_update=cold", "rope.subdomain_residual=10",
                          "rope.subdomain_frame=corotational", "rope.subdomain_rotation=0.2"}) {
    const std::string key = std::string(set).substr(0, std::string(set).find('='));
    expectRefused(p, {"rope.model=reduced", set}, {p, key, "rope.reduction: subdomains"});
    // Taken by the subdomain reduction, and by the models that do not reduce.
    EXPECT_NO_THROW(loadScene(p, {"rope.model=reduced", "rope.reduction=subdomains", set})) << set;
    EXPECT_NO_THROW(loadScene(p, {"rope.model=full", set})) << set;
  }
}

TEST(Scene, UnknownKeyIsRefused) {
  const std::string p = writeScene("good.yaml", kGood);
  expectRefused(p, {"rope.elemnts=10"}, {p, "rope.elemnts", "unknown key"});
  expectRefused(p, {"blizzard=3"}, {p, "blizzard", "unknown key"});
  expectRefused(p, {"payload.mass_kg=3"}, {p, "payload.mass_kg", "unknown key"});
}

TEST(Scene, MissingRequiredKeyIsRefused) {
  const std::string p = writeScene("no_rope.yaml", "crane: none\nduration: 1\ntime_step: 0.01\n");
  expectRefused(p, {}, {p, "rope", "required"});
  const std::string q = writeScene("no_len.yaml", std::string(kGood) + "");
  expectRefused(q, {"rope.length=null"}, {q, "rope.length", "required"});
}

TEST(Scene, MissingEmptyOrBrokenFilesAreRefused) {
  expectRefused(kScenes + "does_not_exist.yaml", {}, {"does_not_exist.yaml", "cannot open"});
  const std::string empty = writeScene("empty.yaml", "");
  expectRefused(empty, {}, {empty, "empty"});
  const std::string broken = writeScene("broken.yaml", "crane: none\nrope: {model: full\n");
  expectRefused(broken, {}, {broken, "syntax error", "line"});
  const std::string crane = writeScene("nocrane.yaml", std::string(kGood));
  expectRefused(crane, {"crane=t9999", "anchor=null", "structure.model=modal"},
                {crane, "crane", "t9999"});
  const std::string list = writeScene("list.yaml", "- 1\n- 2\n");
  expectRefused(list, {}, {list, "map"});
  // Found by scripts/fuzz_scene_loader.sh: a stray comma makes a list a key of the flow map,
  // which escaped as a yaml-cpp conversion error.
  const std::string listKey =
      writeScene("list_key.yaml",
                 "crane: none\nduration: 1\ntime_step: 0.01\n"
                 "rope: {model: full, length: 10}\n"
                 "initial: {mode: stress_free, payload_velocity:, [0, 0, 3]}\n");
  expectRefused(listKey, {}, {listKey, "initial", "not a name"});
  // Also found by fuzzing: a crane name longer than the file system allows threw a
  // std::filesystem error.
  const std::string longName = writeScene("long_crane.yaml", std::string(kGood));
  expectRefused(longName, {"crane=" + std::string(600, 'x'), "anchor=null"},
                {longName, "crane", "does not exist"});
}

TEST(Scene, CrossKeyLimitsAreRefused) {
  const std::string c1 = kScenes + "t8036_combination1.yaml";
  expectRefused(c1, {"trolley.radius=85"}, {c1, "trolley.radius", "radius limits"});
  expectRefused(c1, {"rope.length=70"}, {c1, "rope.length", "rope length limits"});
  expectRefused(c1, {"anchor=[0,0,1]"}, {c1, "anchor", "crane: none"});
  const std::string p = writeScene("good.yaml", kGood);
  expectRefused(p, {"structure.model=modal"}, {p, "structure.model", "rigid"});
  expectRefused(p, {"initial.mode=equilibrium", "initial.swing_deg=95"}, {p, "initial.swing_deg"});
  expectRefused(p, {"commands=[{t: 1.0}, {t: 0.5}]"}, {p, "commands[1].t", "increasing"});
  expectRefused(p, {"commands=[{t: 0.0, slew: 1}]"}, {p, "commands[0].slew", "unknown key"});
}

TEST(Scene, MalformedOverridesAreRefused) {
  const std::string p = writeScene("good.yaml", kGood);
  expectRefused(p, {"rope.elements"}, {"rope.elements", "key.path=value"});
  expectRefused(p, {"=3"}, {"key.path=value"});
  expectRefused(p, {"rope..elements=3"}, {"empty key"});
  expectRefused(p, {"duration.x=3"}, {"duration", "not a map"});
  expectRefused(p, {"rope.elements=[1, 2"}, {"not valid YAML"});
}

TEST(Scene, SitePoseIsReadAndChecked) {
  const std::string p = writeScene("good.yaml", kGood);
  const Scene def = loadScene(p);
  EXPECT_EQ(def.site_position, Eigen::Vector3d::Zero());
  EXPECT_EQ(def.site_yaw_deg, 0.0);
  const Scene s = loadScene(p, {"site.position=[100, -20, 3.5]", "site.yaw_deg=180"});
  EXPECT_EQ(s.site_position, Eigen::Vector3d(100, -20, 3.5));
  EXPECT_EQ(s.site_yaw_deg, 180.0);
  expectRefused(p, {"site.position=[1, 2]"}, {p, "site.position"});
  expectRefused(p, {"site.position=[1, .nan, 2]"}, {p, "site.position"});
  expectRefused(p, {"site.yaw_deg=400"}, {p, "site.yaw_deg", "400"});
  expectRefused(p, {"site.yaw=3"}, {p, "site.yaw", "unknown key"});
}

TEST(Scene, MisspeltKeysAreNamedWithTheNearestValidKey) {
  // A misspelt required key is an unknown key, not a missing one.
  std::string text = kGood;
  text.replace(text.find("time_step"), 9, "time_stpe");
  const std::string p = writeScene("typo.yaml", text);
  expectRefused(p, {}, {p, "'time_stpe'", "unknown key", "did you mean 'time_step'"});
  const std::string good = writeScene("good.yaml", kGood);
  expectRefused(good, {"rope.elemnts=10"},
                {"'rope.elemnts'", "unknown key", "did you mean 'rope.elements'",
                 "set by the override 'rope.elemnts=10'"});
  // Far from every key: no suggestion.
  try {
    loadScene(good, {"blizzard=3"});
    FAIL() << "blizzard accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).find("did you mean"), std::string::npos) << e.what();
  }
}

TEST(Scene, ErrorsNameTheOverrideThatSetTheValue) {
  const std::string p = writeScene("good.yaml", kGood);
  expectRefused(p, {"payload.mass=-1"}, {"payload.mass", "set by the override 'payload.mass=-1'"});
  expectRefused(p, {"rope={model: full, elements: 0, length: 20.0}"},
                {"rope.elements", "set by the override 'rope={model: full"});
  // A value from the file itself names no override.
  std::string text = kGood;
  text.replace(text.find("mass: 100.0"), 11, "mass: -5.0");
  const std::string bad = writeScene("bad_mass.yaml", text);
  try {
    loadScene(bad, {"duration=2"});
    FAIL() << "negative mass accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).find("override"), std::string::npos) << e.what();
  }
}
