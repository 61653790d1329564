// crane_sim as a user runs it: output formats of docs/cli.md and exit codes.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "crane_twin/simulation/invariant_reduced_simulation.hpp"

namespace {

struct Result {
  int status;
  std::string out;
};

// Run crane_sim with arguments; stderr is merged into the captured output.
Result run(const std::string& args) {
  const std::string cmd = std::string(CRANE_SIM_EXE) + " " + args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  std::string out;
  std::array<char, 4096> buf;
  while (p && fgets(buf.data(), buf.size(), p)) out += buf.data();
  const int st = p ? pclose(p) : -1;
  return {WIFEXITED(st) ? WEXITSTATUS(st) : -1, out};
}

std::vector<std::string> lines(const std::string& s) {
  std::vector<std::string> v;
  std::istringstream in(s);
  for (std::string l; std::getline(in, l);) v.push_back(l);
  return v;
}

const std::string kScene =
    std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/t8036_combination1.yaml";

}  // namespace

TEST(CraneSimCli, InfoPrintsTheSpecKeysInOrder) {
  const Result r = run("info " + kScene);
  ASSERT_EQ(r.status, 0) << r.out;
  const auto l = lines(r.out);
  const char* keys[] = {"structure_nodes", "structure_elements", "structure_dofs", "structure_mass",
                        "rope_elements",   "rope_dofs",          "rope_mass"};
  ASSERT_GE(l.size(), 7u);
  for (int i = 0; i < 7; ++i) EXPECT_EQ(l[i].substr(0, l[i].find(',')), keys[i]);
  EXPECT_EQ(l[4], "rope_elements,120");
  EXPECT_EQ(l[5], "rope_dofs,726");
  // 2 falls x 1.9 kg/m x 60 m.
  EXPECT_NEAR(std::stod(l[6].substr(l[6].find(',') + 1)), 228.0, 1e-9);
}

TEST(CraneSimCli, InfoHonoursOverrides) {
  const Result r = run("info " + kScene + " --set rope.elements=40");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("rope_elements,40\n"), std::string::npos);
  EXPECT_NE(r.out.find("rope_dofs,246\n"), std::string::npos);
}

TEST(CraneSimCli, InfoSaysWhatARunIntegrates) {
  // Combination 1: the subdomain rope keeps mode_fraction 0.5 of its 726 DOF, i.e. 363
  // coordinates (360 modes + the 3 rigid translations, docs/model.md), and 100 structure modes;
  // the default reduced rope integrates 3 coordinates per shape of the basis a run builds;
  // a rigid structure integrates none.
  Result r = run("info " + kScene + " --set rope.reduction=subdomains");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("integrated_structure_coordinates,100\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("integrated_rope_coordinates,363\n"), std::string::npos) << r.out;
  r = run("info " + kScene);
  ASSERT_EQ(r.status, 0) << r.out;
  {
    const crane_twin::InvariantReducedSimulation sim(
        crane_twin::buildCraneModel(crane_twin::loadScene(kScene, {})));
    EXPECT_NE(r.out.find("integrated_rope_coordinates," + std::to_string(3 * sim.basis().shapes()) +
                         "\n"),
              std::string::npos)
        << r.out;
  }
  EXPECT_NE(r.out.find("rope_bending,on\n"), std::string::npos);
  EXPECT_NE(r.out.find("slewing_inertial_loads,off\n"), std::string::npos);
  r = run("info " + kScene +
          " --set structure.model=rigid --set rope.model=full --set rope.bending=false"
          " --set rope.damping=0.01");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("integrated_structure_coordinates,0\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("integrated_rope_coordinates,726\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("rope_bending,off\n"), std::string::npos);
  EXPECT_NE(r.out.find("rope_damping_s,0.01\n"), std::string::npos);
  EXPECT_NE(r.out.find("structural_damping_ratio,0\n"), std::string::npos);
  // The pendulum integrates its two end points and cannot bend.
  r = run("info " + kScene + " --set rope.model=pendulum");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("integrated_rope_coordinates,6\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("rope_bending,off\n"), std::string::npos);
}

TEST(CraneSimCli, StructureModesFormat) {
  const Result r = run("modes " + kScene + " --part structure --count 10");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto l = lines(r.out);
  ASSERT_EQ(l.size(), 11u) << r.out;
  EXPECT_EQ(l[0], "index,frequency_hz");
  double prev = 0.0;
  for (int i = 1; i <= 10; ++i) {
    EXPECT_EQ(std::stoi(l[i].substr(0, l[i].find(','))), i);
    const double f = std::stod(l[i].substr(l[i].find(',') + 1));
    EXPECT_GE(f, prev);
    prev = f;
  }
}

TEST(CraneSimCli, BadInputExitsWithTwoAndNamesTheKey) {
  Result r = run("info " + kScene + " --set rope.elements=0");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("rope.elements"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("t8036_combination1.yaml"), std::string::npos) << r.out;
  r = run("info /nonexistent/scene.yaml");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("/nonexistent/scene.yaml"), std::string::npos) << r.out;
  r = run("modes " + kScene + " --count 0");
  EXPECT_EQ(r.status, 2) << r.out;
  r = run("modes " + kScene + " --part hull");
  EXPECT_EQ(r.status, 2) << r.out;
  r = run("sweep " + kScene + " --quick --reference-dt 0.01");  // coarser than the scene's
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("--reference-dt 0.01 s"), std::string::npos) << r.out;
  r = run("run " + kScene + " --set duration=1e200");  // its step count overflowed before
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("'duration'"), std::string::npos) << r.out;
  // The default reduced rope's 6 transverse modes on a mesh that holds 3: the mesh is named.
  r = run("run " + kScene + " --set rope.model=reduced --set rope.elements=1 --set duration=0.01");
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("'rope.elements'"), std::string::npos) << r.out;
  r = run("frobnicate");
  EXPECT_EQ(r.status, 2) << r.out;
  r = run("");
  EXPECT_EQ(r.status, 2) << r.out;
}

namespace {
const std::string kRope =
    std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/rope_pendulum_chrono.yaml";
}

TEST(CraneSimCli, NumericalFailureExitsWithOneAndSaysWhenAndWhy) {
  // A 10-element rope with the symmetric axial law thrown at 50 m/s up and sideways from
  // horizontal with 5 s steps: Newton fails in the whirl even with the step halved ten times
  // (the tension-only rope's finer steps carry this one through). Exit 1, the time and the
  // reason on stderr, and the rows written before it finite.
  const std::string csv = ::testing::TempDir() + "crane_sim_failure.csv";
  const Result r = run("run " + kRope +
                       " --set rope.elements=10 --set duration=50"
                       " --set rope.tension_only=false"
                       " --set initial.swing_deg=90 --set time_step=5 --set output_interval=5"
                       " --set initial.payload_velocity=[0,50,50] --quiet --out " +
                       csv);
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_NE(r.out.find("numerical failure: t = "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Newton did not converge"), std::string::npos) << r.out;
  std::ifstream in(csv);
  std::string line;
  int rows = 0;
  while (std::getline(in, line)) {
    ++rows;
    EXPECT_EQ(line.find("nan"), std::string::npos) << line;
    EXPECT_EQ(line.find("inf"), std::string::npos) << line;
  }
  EXPECT_GE(rows, 2);  // header and the state at t = 0
}

TEST(CraneSimCli, SceneThatIsNoFileExitsWithTwo) {
  // A directory, an empty device: refused by name, exit 2 (CI runs as root, so a file without
  // read permission would still be readable there).
  Result r = run("info " + ::testing::TempDir());
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("is a directory"), std::string::npos) << r.out;
  r = run("run /dev/null --quiet");
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("/dev/null: file is empty"), std::string::npos) << r.out;
}

TEST(CraneSimCli, RunWritesSpecColumnsAndSummary) {
  const std::string csv = ::testing::TempDir() + "crane_sim_run.csv";
  const std::string nodes = ::testing::TempDir() + "crane_sim_nodes.csv";
  const Result r = run("run " + kRope + " --set duration=0.1 --set rope.elements=10 --out " + csv +
                       " --nodes " + nodes + " --quiet");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto l = lines(r.out);
  ASSERT_FALSE(l.empty());
  EXPECT_TRUE(l.back().rfind("summary: wall_s=", 0) == 0) << l.back();
  for (const char* k : {" sim_s=0.1 ", " rtf=", " steps=100 ", " subdomains=0 ",
                        " mode_updates_s=", " lift_offs=0 ", " lift_off_factor=0 ",
                        " peak_tension_ratio=", " basis_additions=0"}) {
    EXPECT_NE(l.back().find(k), std::string::npos) << k;
  }
  std::ifstream in(csv);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header,
            "t,payload_x,payload_y,payload_z,payload_vx,payload_vy,payload_vz,cab_dx,cab_dy,cab_dz,"
            "jib_tip_dx,jib_tip_dy,jib_tip_dz,trolley_x,trolley_y,trolley_z,rope_top_tension,"
            "rope_length,slew_angle,trolley_radius,energy,constraint_error,subdomains,"
            "tension_ratio,load_chart_ratio,warnings,full_order_steps,payload_landed,"
            "contact_force");
  int rows = 0;
  for (std::string row; std::getline(in, row);) {
    ++rows;
    EXPECT_EQ(std::count(row.begin(), row.end(), ','), 28) << row;
    EXPECT_EQ(row.find("nan"), std::string::npos) << row;
  }
  EXPECT_EQ(rows, 3);  // t = 0, 0.05, 0.1 at output_interval 0.05
  std::ifstream nin(nodes);
  std::getline(nin, header);
  EXPECT_EQ(header, "t,node,x,y,z");
  int nrows = 0;
  for (std::string row; std::getline(nin, row);) ++nrows;
  EXPECT_EQ(nrows, 3 * 11);
}

TEST(CraneSimCli, StaticPrintsKeys) {
  for (const char* model : {"full", "pendulum"}) {
    const Result r = run("static " + kRope + " --set rope.model=" + model);
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_EQ(r.out.rfind("payload_x,", 0), 0u) << r.out;
    for (const char* k :
         {"payload_y,", "payload_z,", "rope_top_tension,", "jib_tip_dz,", "cab_dx,"}) {
      EXPECT_NE(r.out.find(std::string("\n") + k), std::string::npos) << k << "\n" << r.out;
    }
  }
}

// modes of a landed scene: the hanging rope's, the ground taking no part (as in every static
// solve of the hanging rope); before, full order's static solve with the landed load's ground
// failed ("static solve did not converge").
TEST(CraneSimCli, RopeModesOfALandedSceneAreTheHangingRopes) {
  const std::string lift =
      std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/t8036_lift_off_fast.yaml";
  const Result landed = run("modes " + lift + " --part rope --count 3");
  const Result far = run("modes " + lift + " --part rope --count 3 --set ground.height=-100");
  ASSERT_EQ(landed.status, 0) << landed.out;
  ASSERT_EQ(far.status, 0) << far.out;
  EXPECT_EQ(landed.out, far.out);
}

TEST(CraneSimCli, UnbuiltCombinationsAreRefusedClearly) {
  Result r = run("run " + kRope +
                 " --set rope.model=reduced --set rope.reduction=subdomains"
                 " --set rope.damping=0.01 --quiet");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("rope.damping"), std::string::npos) << r.out;
  r = run("run " + kRope + " --out /nonexistent/dir/x.csv --quiet");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("--out"), std::string::npos) << r.out;
}

// Value of column `name` in a CSV row, by the header.
double column(const std::string& header, const std::string& row, const std::string& name) {
  std::vector<std::string> h, v;
  std::istringstream hs(header), vs(row);
  for (std::string x; std::getline(hs, x, ',');) h.push_back(x);
  for (std::string x; std::getline(vs, x, ',');) v.push_back(x);
  const auto it = std::find(h.begin(), h.end(), name);
  if (it == h.end() || v.size() != h.size()) return NAN;
  return std::stod(v[it - h.begin()]);
}

// Header and data rows of a CSV file.
std::vector<std::string> csvRows(const std::string& path, std::string& header) {
  std::ifstream in(path);
  std::getline(in, header);
  std::vector<std::string> rows;
  for (std::string row; std::getline(in, row);) rows.push_back(row);
  return rows;
}

// The summary's lift-off factor is the peak of every step, whatever the output interval: a
// 10 t lift-off at 1 m/s on four falls of the rigid crane throws its load and rings undamped,
// and rows every 50 ms read its peak as 2.247 where every step's is 2.331 (before, the factor
// was the rows').
TEST(CraneSimCli, UsageDamageCountsEveryStepWhateverTheOutputInterval) {
  // The hot spots' rainflow count takes every step's stresses (docs/fatigue.md "Usage"): rows
  // every 50 ms and every step give the same damage; the structure rings at periods of a few
  // tenths of a second under a 1 m/s lift-off: counted at its 50 ms rows alone, the damage
  // read 0.35 % to 2.5 % less than at every step.
  const std::string lift =
      std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/t8036_lift_off_fast.yaml";
  const std::string sets = " --set duration=4 --set rope.elements=20 --quiet";
  auto damages = [](const std::string& out) {
    std::vector<double> d;
    for (std::size_t at = out.find("usage_hot_spot:"); at != std::string::npos;
         at = out.find("usage_hot_spot:", at + 1)) {
      const std::size_t v = out.find("damage=", at);
      d.push_back(std::stod(out.substr(v + 7)));
    }
    return d;
  };
  const Result coarse = run("run " + lift + sets + " --set output_interval=0.05");
  const Result fine = run("run " + lift + sets + " --set output_interval=0.001");
  ASSERT_EQ(coarse.status, 0) << coarse.out;
  ASSERT_EQ(fine.status, 0) << fine.out;
  const std::vector<double> a = damages(coarse.out), b = damages(fine.out);
  ASSERT_EQ(a.size(), 4u) << coarse.out;
  ASSERT_EQ(b.size(), a.size()) << fine.out;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_GT(b[i], 0.0) << i;
    // (the block prints 6 significant digits)
    EXPECT_NEAR(a[i], b[i], 1e-5 * b[i]) << i << "\n" << coarse.out << fine.out;
  }
}

TEST(CraneSimCli, LiftOffFactorIsTheStepsPeakWhateverTheOutputInterval) {
  const std::string lift =
      std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/t8036_lift_off_fast.yaml";
  const std::string sets =
      " --set duration=5.3 --set payload.mass=10026 --set trolley.radius=58.9"
      " --set structure.model=rigid --set rope.elements=30 --set rope.falls=4"
      " --set rope.model=reduced --quiet";
  auto factor = [](const std::string& out) {
    const std::size_t at = out.find("lift_off_factor=");
    return at == std::string::npos ? NAN : std::stod(out.substr(at + 16));
  };
  const std::string coarse_csv = testing::TempDir() + "lift_coarse.csv";
  const std::string fine_csv = testing::TempDir() + "lift_fine.csv";
  const Result coarse =
      run("run " + lift + sets + " --set output_interval=0.05 --out " + coarse_csv);
  const Result fine = run("run " + lift + sets + " --set output_interval=0.001 --out " + fine_csv);
  ASSERT_EQ(coarse.status, 0) << coarse.out;
  ASSERT_EQ(fine.status, 0) << fine.out;
  ASSERT_GT(factor(fine.out), 2.0) << fine.out;  // thrown: the case that rings
  EXPECT_EQ(factor(coarse.out), factor(fine.out)) << coarse.out << fine.out;
  // The rows themselves differ: the coarse ones miss the crests in the 3 s after the lift-off.
  auto row_peak = [](const std::string& path) {
    std::string header;
    double lifted_at = NAN, peak = 0.0;
    for (const std::string& row : csvRows(path, header)) {
      const double t = column(header, row, "t");
      if (std::isnan(lifted_at) && column(header, row, "payload_landed") == 0.0) lifted_at = t;
      if (!std::isnan(lifted_at) && t <= lifted_at + 3.0)
        peak = std::max(peak, column(header, row, "rope_top_tension"));
    }
    return peak;
  };
  EXPECT_LT(row_peak(coarse_csv), 0.99 * row_peak(fine_csv));

  // The tension warnings read the same peak: with the working load limit between the coarse
  // rows' largest tension and the steps' (the rows every 1 ms are every step), the coarse run
  // warns although none of its rows' tension_ratio is over the limit.
  auto max_ratio = [](const std::string& path) {
    std::string header;
    double r = 0.0;
    for (const std::string& row : csvRows(path, header))
      r = std::max(r, column(header, row, "tension_ratio"));
    return r;
  };
  const double rows_ratio = max_ratio(coarse_csv), steps_ratio = max_ratio(fine_csv);
  ASSERT_LT(rows_ratio, 0.99 * steps_ratio);
  const double safety = 2.0 / (rows_ratio + steps_ratio);  // 1 / limit halfway between
  ASSERT_GE(safety, 1.0);
  const std::string warned_csv = testing::TempDir() + "lift_warned.csv";
  const Result warned =
      run("run " + lift + sets + " --set output_interval=0.05 --set " +
          "rope.safety_factor=" + std::to_string(safety) + " --out " + warned_csv);
  ASSERT_EQ(warned.status, 0) << warned.out;
  const std::size_t at = warned.out.find("warnings_seen=");
  ASSERT_NE(at, std::string::npos) << warned.out;
  EXPECT_TRUE(std::stoi(warned.out.substr(at + 14)) & 32) << warned.out;
  EXPECT_LT(max_ratio(warned_csv) * safety, 1.0);

  // The summary's peak tension ratio is the steps' too: the same for both intervals, the 1 ms
  // rows' largest (those rows are every step), above the coarse rows'.
  auto peak_ratio = [](const std::string& out) {
    const std::size_t p = out.find("peak_tension_ratio=");
    return p == std::string::npos ? NAN : std::stod(out.substr(p + 19));
  };
  EXPECT_EQ(peak_ratio(coarse.out), peak_ratio(fine.out)) << coarse.out << fine.out;
  EXPECT_NEAR(peak_ratio(fine.out), steps_ratio, 1e-3 * steps_ratio);
  EXPECT_GT(peak_ratio(coarse.out), 1.005 * rows_ratio);
}

// static on a scene with a ground: a landed start prints itself (a rest state: the load on the
// ground where `run` starts it, the rope's own weight at the top, in every rope model); an
// equilibrium whose stretched rope puts the load inside the ground is refused as `run` refuses
// it. (Before, full order's static solve with the ground failed on the landed scene and the
// pendulum's printed its hanging load 1.5 m inside the ground.)
TEST(CraneSimCli, StaticOfAGroundSceneIsItsRestingStart) {
  const std::string lift =
      std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/t8036_lift_off_fast.yaml";
  auto value = [](const std::string& out, const std::string& key) {
    const std::size_t at = out.find(key + ",");
    EXPECT_NE(at, std::string::npos) << key << "\n" << out;
    return at == std::string::npos ? NAN : std::stod(out.substr(at + key.size() + 1));
  };
  const Result first =
      run("run " + lift + " --set rope.model=full --set duration=0.01 --set " +
          "output_interval=0.01 --quiet --out " + testing::TempDir() + "landed_start.csv");
  ASSERT_EQ(first.status, 0) << first.out;
  std::ifstream csv(testing::TempDir() + "landed_start.csv");
  std::string header, row;
  std::getline(csv, header);
  std::getline(csv, row);
  const double z_start = column(header, row, "payload_z");
  const double t_start = column(header, row, "rope_top_tension");
  for (const char* model : {"full", "reduced", "pendulum"}) {
    SCOPED_TRACE(model);
    const Result r = run("static " + lift + " --set rope.model=" + model);
    ASSERT_EQ(r.status, 0) << r.out;
    EXPECT_NEAR(value(r.out, "payload_z"), z_start, 1e-6);
    EXPECT_NEAR(value(r.out, "rope_top_tension"), t_start, 1e-3 * t_start);
    EXPECT_EQ(value(r.out, "holding_force_x"), 0.0);
  }
  const std::string down =
      std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/t8036_set_down.yaml";
  for (const char* model : {"full", "pendulum"}) {
    const Result r = run("static " + down + " --set rope.model=" + model +
                         " --set payload.mass=7194 --set trolley.radius=54.9");
    EXPECT_EQ(r.status, 2) << model << ": " << r.out;
    EXPECT_NE(r.out.find("'rope.length'"), std::string::npos) << r.out;
  }
}

TEST(CraneSimCli, T8036RunsAtFullOrderWithStructureOutputs) {
  const std::string csv = ::testing::TempDir() + "crane_sim_t8036.csv";
  for (const char* model : {"modal", "full"}) {
    const Result r = run("run " + kScene + " --set rope.model=full --set structure.model=" + model +
                         " --set structure.modes=10 --set rope.elements=12 --set duration=0.2"
                         " --set output_interval=0.01 --out " +
                         csv + " --quiet");
    ASSERT_EQ(r.status, 0) << r.out;
    std::string header;
    const std::vector<std::string> rows = csvRows(csv, header);
    for (const std::string& row : rows) {
      EXPECT_EQ(row.find("nan"), std::string::npos) << row;
      // The loaded jib bends down and the mast leans out along the jib (x).
      EXPECT_LT(column(header, row, "jib_tip_dz"), -0.5) << model;
      EXPECT_GT(column(header, row, "cab_dx"), 0.1) << model;
      EXPECT_NEAR(column(header, row, "trolley_x"), 80.0, 1.0) << model;
      EXPECT_LT(column(header, row, "constraint_error"), 1e-8) << model;
      EXPECT_EQ(column(header, row, "trolley_radius"), 80.0);
    }
    EXPECT_EQ(rows.size(), 21u) << model;
  }
}

TEST(CraneSimCli, T8036StaticReportsStructureDeflection) {
  const Result r = run("static " + kScene + " --set rope.model=full --set structure.model=full");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto pos = r.out.find("\njib_tip_dz,");
  ASSERT_NE(pos, std::string::npos) << r.out;
  EXPECT_LT(std::stod(r.out.substr(pos + 12)), -0.5) << r.out;
}

TEST(CraneSimCli, ReducedRunCountsSubdomains) {
  const Result r = run("run " + kRope +
                       " --set rope.model=reduced --set rope.reduction=subdomains"
                       " --set rope.mode_count=6 --set rope.elements=10 --set duration=2 --set "
                       "initial.mode=equilibrium"
                       " --set rope.subdomain_delta=0.01 --quiet");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto l = lines(r.out);
  const auto pos = l.back().find(" subdomains=");
  ASSERT_NE(pos, std::string::npos) << l.back();
  EXPECT_GT(std::stoi(l.back().substr(pos + 12)), 1) << l.back();
}

TEST(CraneSimCli, CompareComputesTheSpecMetrics) {
  const std::string a = ::testing::TempDir() + "cmp_a.csv", b = ::testing::TempDir() + "cmp_b.csv";
  ASSERT_EQ(
      run("run " + kRope + " --set duration=0.1 --set rope.elements=6 --out " + a + " --quiet")
          .status,
      0);
  // B: A with the payload moved by (0.3, 0.4, 0) and the top tension raised by 250 N at the second
  // row: error 0.5 m, 0.5/60 relative, 250 N.
  {
    std::ifstream in(a);
    std::ofstream out(b);
    std::string line;
    for (int i = 0; std::getline(in, line); ++i) {
      if (i == 2) {
        std::vector<std::string> f;
        std::istringstream s(line);
        for (std::string x; std::getline(s, x, ',');) f.push_back(x);
        f[1] = std::to_string(std::stod(f[1]) + 0.3);
        f[2] = std::to_string(std::stod(f[2]) + 0.4);
        f[16] = std::to_string(std::stod(f[16]) + 250.0);  // rope_top_tension
        line.clear();
        for (std::size_t k = 0; k < f.size(); ++k) line += (k ? "," : "") + f[k];
      }
      out << line << "\n";
    }
  }
  const Result r = run("compare " + a + " " + b);
  ASSERT_EQ(r.status, 0) << r.out;
  const auto at = [&](const std::string& key) {
    const auto p = r.out.find(key + ",");
    return p == std::string::npos ? NAN : std::stod(r.out.substr(p + key.size() + 1));
  };
  EXPECT_EQ(at("common_times"), 3);
  EXPECT_NEAR(at("payload_error_max"), 0.5, 1e-5);
  EXPECT_NEAR(at("payload_error_relative"), 0.5 / 60.0, 1e-6);
  EXPECT_EQ(at("cab_error_max"), 0.0);
  EXPECT_NEAR(at("tension_error_max"), 250.0, 1e-3);
  EXPECT_GT(at("tension_error_relative"), 0.0);
  // The time of the largest payload error is the moved row's, and a window without that row sees
  // no error.
  double moved_t = NAN, last_t = NAN;
  {
    std::ifstream in(b);
    std::string line;
    for (int i = 0; std::getline(in, line); ++i) {
      if (i == 0) continue;
      const double t = std::stod(line.substr(0, line.find(',')));
      if (i == 2) moved_t = t;
      last_t = t;
    }
  }
  ASSERT_TRUE(std::isfinite(moved_t));
  ASSERT_GT(last_t, moved_t);
  EXPECT_NEAR(at("payload_error_at"), moved_t, 1e-9);
  const std::string after = std::to_string(0.5 * (moved_t + last_t));
  const Result late = run("compare " + a + " " + b + " --from " + after);
  ASSERT_EQ(late.status, 0) << late.out;
  EXPECT_NE(late.out.find("payload_error_max,0\n"), std::string::npos) << late.out;
  EXPECT_NE(late.out.find("tension_error_max,0\n"), std::string::npos) << late.out;
  const Result upto = run("compare " + a + " " + b + " --to " + std::to_string(moved_t));
  ASSERT_EQ(upto.status, 0) << upto.out;
  EXPECT_NE(upto.out.find("payload_error_max,0.5"), std::string::npos) << upto.out;
  // A window that ends before it begins, or holds no common time, is refused by name.
  const Result bad = run("compare " + a + " " + b + " --from 1 --to 0.5");
  EXPECT_EQ(bad.status, 2) << bad.out;
  EXPECT_NE(bad.out.find("time window"), std::string::npos) << bad.out;
  const Result none = run("compare " + a + " " + b + " --from 1e6");
  EXPECT_EQ(none.status, 2) << none.out;
  EXPECT_NE(none.out.find("no output time in"), std::string::npos) << none.out;
}

TEST(CraneSimCli, CompareRefusesMalformedCsv) {
  const std::string dir = ::testing::TempDir();
  const std::string good = dir + "cmp_good.csv";
  ASSERT_EQ(
      run("run " + kRope + " --set duration=0.1 --set rope.elements=6 --out " + good + " --quiet")
          .status,
      0);
  struct Bad {
    const char* name;
    const char* text;
    const char* expect;
  };
  const Bad cases[] = {
      {"cmp_empty.csv", "", "empty file"},
      {"cmp_nocol.csv", "t,payload_x\n0,1\n", "payload_y"},
      {"cmp_text.csv", nullptr, "not a finite number"},
      {"cmp_ragged.csv", nullptr, "fields"},
      {"cmp_repeated.csv", nullptr, "does not increase"},
  };
  std::string header;
  {
    std::ifstream in(good);
    std::getline(in, header);
  }
  for (const Bad& c : cases) {
    const std::string path = dir + c.name;
    {
      std::ofstream out(path);
      if (c.text) {
        out << c.text;
      } else if (std::string(c.name) == "cmp_text.csv") {
        out << header << "\n0,abc";  // payload_x not a number, the row otherwise complete
        const long fields = std::count(header.begin(), header.end(), ',') + 1;
        for (long k = 2; k < fields; ++k) out << ",0";
        out << "\n";
      } else if (std::string(c.name) == "cmp_repeated.csv") {
        // Two complete rows at the same time: rows are paired by time.
        const long fields = std::count(header.begin(), header.end(), ',') + 1;
        for (int row = 0; row < 2; ++row) {
          out << (row == 0 ? header + "\n" : std::string()) << "0.5";
          for (long k = 1; k < fields; ++k) out << ",0";
          out << "\n";
        }
      } else {
        out << header << "\n0,1,2\n";
      }
    }
    const Result r = run("compare " + path + " " + good);
    EXPECT_EQ(r.status, 2) << c.name << "\n" << r.out;
    EXPECT_NE(r.out.find(path), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(c.expect), std::string::npos) << c.name << "\n" << r.out;
  }
  const Result r = run("compare /nonexistent/a.csv " + good);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("/nonexistent/a.csv"), std::string::npos) << r.out;
}

TEST(CraneSimCli, QuickSweepWritesOneRowPerSetting) {
  const std::string out = ::testing::TempDir() + "sweep.csv";
  const Result r = run("sweep " + kRope +
                       " --set duration=0.4 --set rope.elements=8"
                       " --set initial.mode=equilibrium --quick --out " +
                       out);
  ASSERT_EQ(r.status, 0) << r.out;
  std::ifstream in(out);
  std::string header, row;
  std::getline(in, header);
  EXPECT_EQ(header.rfind("scene,model,time_step,rope_modes,delta", 0), 0u) << header;
  int rows = 0, reference = 0;
  while (std::getline(in, row)) {
    ++rows;
    if (row.find(",reference,") != std::string::npos) ++reference;
    EXPECT_EQ(row.find("nan"), std::string::npos) << row;
  }
  EXPECT_EQ(reference, 1);
  // reference, full at 1 and 10 ms, subdomain-reduced 10 modes x 2 deltas x 2 steps, the
  // invariant reduced rope at 1 and 10 ms, pendulum at 10 ms
  EXPECT_EQ(rows, 1 + 2 + 4 + 2 + 1);
}

TEST(CraneSimCli, PhysicalWarningsReachTheCsvAndStderr) {
  // 5 t at 80 m is over the chart's 3.6 t there: every row carries bit 2 and its ratio 5/3.6,
  // and stderr says so once, with a count at the end.
  const std::string csv = ::testing::TempDir() + "crane_sim_warn.csv";
  const Result r = run("run " + kScene +
                       " --set rope.model=full --set structure.model=rigid"
                       " --set rope.elements=10 --set duration=0.1 --set payload.mass=5000"
                       " --out " +
                       csv + " --quiet");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("warning: t = 0.000 s: load outside the load chart"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("load outside the load chart at this radius in 11 output rows"),
            std::string::npos)
      << r.out;
  std::string header;
  const std::vector<std::string> rows = csvRows(csv, header);
  for (const std::string& row : rows) {
    EXPECT_NEAR(column(header, row, "load_chart_ratio"), 5000.0 / 3600.0, 1e-9);
    EXPECT_EQ(static_cast<int>(column(header, row, "warnings")) & 2, 2);
    // Tension ratio: (5000 + 2044 + 228) g / (2 x 345 kN), about 0.10.
    EXPECT_NEAR(column(header, row, "tension_ratio"), (7044.0 + 228.0) * 9.81 / 690e3, 0.01);
  }
  EXPECT_EQ(rows.size(), 11u);
  // Within the chart: no warning.
  const Result ok = run("run " + kScene +
                        " --set rope.model=full --set structure.model=rigid"
                        " --set rope.elements=10 --set duration=0.1 --quiet");
  EXPECT_EQ(ok.out.find("warning:"), std::string::npos) << ok.out;
  EXPECT_NE(ok.out.find("warnings_seen=0 warning_rows=none"), std::string::npos) << ok.out;
  // The working load limit: the same run's tension ratio (about 0.10) over 1 / 12 of the
  // breaking force, not over 1 / 5.
  const Result wll =
      run("run " + kScene +
          " --set rope.model=full --set structure.model=rigid"
          " --set rope.elements=10 --set duration=0.1 --quiet --set rope.safety_factor=12");
  EXPECT_NE(wll.out.find("warning: t = 0.000 s: rope tension over its working load limit"),
            std::string::npos)
      << wll.out;
  EXPECT_NE(wll.out.find("warnings_seen=32 warning_rows=32:11"), std::string::npos) << wll.out;
  EXPECT_EQ(run("run " + kScene + " --set rope.safety_factor=0.5 --quiet").status, 2);
}

TEST(CraneSimCli, SummaryCountsEnergyConsistentSteps) {
  // docs/cli.md: the summary's energy_consistent_steps and halved_steps. A taut rope takes none;
  // the shipped slack throw (its first 0.6 s: thrown up, slack, snatched) takes them.
  const Result taut = run("run " + kScene +
                          " --set rope.model=full --set structure.model=rigid"
                          " --set rope.elements=10 --set duration=0.1 --quiet");
  EXPECT_NE(taut.out.find(" energy_consistent_steps=0 halved_steps=0 "), std::string::npos)
      << taut.out;
  const Result slack = run("run " + std::string(CRANE_TWIN_SOURCE_DIR) +
                           "/config/scenes/hard_slack_throw.yaml --set rope.elements=20"
                           " --set structure.model=rigid --set duration=0.6 --quiet");
  ASSERT_EQ(slack.status, 0) << slack.out;
  const std::size_t at = slack.out.find(" energy_consistent_steps=");
  ASSERT_NE(at, std::string::npos) << slack.out;
  EXPECT_GT(std::stol(slack.out.substr(at + 25)), 0) << slack.out;
}

// A lift-off above the scene's design factor (hoist.design_phi2) sets warning bit 128 in the
// rows of its window and the summary; below it, nothing. The pendulum rope runs the shipped
// fast lift-off (phi_2 about 1.83) in a fraction of a second.
TEST(CraneSimCli, LiftOffOverTheDesignFactorIsAWarning) {
  const std::string scene = std::string(CRANE_TWIN_SOURCE_DIR) +
                            "/config/scenes/t8036_lift_off_fast.yaml --set rope.model=pendulum "
                            "--set duration=6 --quiet";
  Result r = run("run " + scene + " --set hoist.design_phi2=1.5");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find(" lift_offs=1 "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("warnings_seen=128 "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("lift-off dynamic factor over hoist.design_phi2"), std::string::npos);
  r = run("run " + scene + " --set hoist.design_phi2=2.5");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find(" lift_offs=1 "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("warnings_seen=0 "), std::string::npos) << r.out;
  r = run("run " + scene + " --set hoist.design_phi2=0.5");
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("hoist.design_phi2"), std::string::npos) << r.out;
}

TEST(CraneSimCli, RainflowCountsAColumnAndSumsTheDamage) {
  // The ASTM E1049-85 example in MPa as a stress_ column in Pa: the standard's counts, then
  // Miner's sum on category 71 by hand: sum count (ds / 71)^3 / 2e6 = 1094 / (71^3 2e6).
  const std::string csv = ::testing::TempDir() + "rainflow.csv";
  {
    std::ofstream f(csv);
    f << "t,stress_mast_foot,other\n";
    const double s[] = {-2, 1, -3, 5, -1, 3, -4, 4, -2};
    for (int i = 0; i < 9; ++i) f << i << ',' << s[i] * 1e6 << ",0\n";
  }
  const Result r = run("rainflow " + csv + " --column stress_mast_foot --detail-category 71");
  ASSERT_EQ(r.status, 0) << r.out;
  const std::vector<std::string> l = lines(r.out);
  ASSERT_EQ(l.size(), 9u) << r.out;
  EXPECT_EQ(l[0], "range,mean,count");
  EXPECT_EQ(l[1], "4000000,1000000,1");
  std::map<double, double> counts;
  for (std::size_t i = 1; i + 1 < l.size(); ++i) {
    double range = 0.0, mean = 0.0, count = 0.0;
    ASSERT_EQ(std::sscanf(l[i].c_str(), "%lf,%lf,%lf", &range, &mean, &count), 3) << l[i];
    counts[range * 1e-6] += count;
  }
  const std::map<double, double> table = {{3, 0.5}, {4, 1.5}, {6, 0.5}, {8, 1.0}, {9, 0.5}};
  EXPECT_EQ(counts, table);
  double damage = 0.0;
  ASSERT_EQ(std::sscanf(l.back().c_str(), "damage,%lf", &damage), 1) << l.back();
  const double closed = 1094.0 / (71.0 * 71.0 * 71.0 * 2e6);
  EXPECT_NEAR(damage, closed, 1e-9 * closed);
  // gamma_Mf 1.25 scales every range: the damage by 1.25^3.
  const Result g =
      run("rainflow " + csv + " --column stress_mast_foot --detail-category 71 --gamma-mf 1.25");
  ASSERT_EQ(g.status, 0) << g.out;
  ASSERT_EQ(std::sscanf(lines(g.out).back().c_str(), "damage,%lf", &damage), 1);
  EXPECT_NEAR(damage, closed * 1.953125, 1e-9 * closed);
  // Bad input: exit 2, what is wrong named.
  const Result col = run("rainflow " + csv + " --column stress_jib_root");
  EXPECT_EQ(col.status, 2);
  EXPECT_NE(col.out.find("stress_jib_root"), std::string::npos) << col.out;
  const Result lone = run("rainflow " + csv + " --column stress_mast_foot --gamma-mf 1.1");
  EXPECT_EQ(lone.status, 2);
  EXPECT_NE(lone.out.find("--detail-category"), std::string::npos) << lone.out;
  const Result neg = run("rainflow " + csv + " --column stress_mast_foot --detail-category -71");
  EXPECT_EQ(neg.status, 2);
  EXPECT_NE(neg.out.find("--detail-category"), std::string::npos) << neg.out;
}

TEST(CraneSimCli, T8036HotSpotStressesReachStaticAndTheRunsColumns) {
  // static: the four hot spots' keys, the jib's top chord pulled and the mast's jib-side chord
  // pushed; a heavier load pushes the mast foot harder (docs/fatigue.md).
  auto stressOf = [](const std::string& out, const std::string& name) {
    const auto pos = out.find("\nstress_" + name + ",");
    return pos == std::string::npos ? std::nan("") : std::stod(out.substr(pos + 9 + name.size()));
  };
  const Result a = run("static " + kScene + " --set rope.elements=10");
  const Result b = run("static " + kScene + " --set rope.elements=10 --set payload.mass=8000");
  ASSERT_EQ(a.status, 0) << a.out;
  ASSERT_EQ(b.status, 0) << b.out;
  EXPECT_GT(stressOf(a.out, "jib_root"), 0.0) << a.out;
  EXPECT_LT(stressOf(a.out, "mast_foot"), 0.0) << a.out;
  EXPECT_LT(stressOf(b.out, "mast_foot"), stressOf(a.out, "mast_foot") - 1e6);
  EXPECT_FALSE(std::isnan(stressOf(a.out, "counter_jib_root")));
  EXPECT_FALSE(std::isnan(stressOf(a.out, "mast_top")));
  // run: the columns after contact_force, one value per row.
  const std::string csv = ::testing::TempDir() + "stresses.csv";
  const Result r = run("run " + kScene + " --set rope.elements=10 --set duration=0.05 --out " +
                       csv + " --quiet");
  ASSERT_EQ(r.status, 0) << r.out;
  std::ifstream in(csv);
  std::string header, row;
  std::getline(in, header);
  std::getline(in, row);
  EXPECT_NE(header.find(",contact_force,stress_mast_foot,stress_mast_top,stress_jib_root,"
                        "stress_counter_jib_root"),
            std::string::npos)
      << header;
  EXPECT_EQ(std::count(header.begin(), header.end(), ','), std::count(row.begin(), row.end(), ','));
  // A rigid structure has none.
  const Result g = run("static " + kScene + " --set rope.elements=10 --set structure.model=rigid");
  ASSERT_EQ(g.status, 0) << g.out;
  EXPECT_EQ(g.out.find("stress_"), std::string::npos) << g.out;
}

TEST(CraneSimCli, RunPrintsTheUsageBlockBeforeTheSummary) {
  // A lift-off on the T8036 (docs/cli.md "The usage block"): one lift of the scene's 3.6 t,
  // k_Q = (3600 / 12500)^3, four hot spots, the summary still last.
  const std::string scene =
      std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/t8036_lift_off_slow.yaml";
  const Result r = run("run " + scene + " --set rope.elements=20 --set duration=8 --quiet");
  ASSERT_EQ(r.status, 0) << r.out;
  const std::vector<std::string> l = lines(r.out);
  ASSERT_GE(l.size(), 7u);
  EXPECT_EQ(l.back().rfind("summary: ", 0), 0u) << l.back();
  std::size_t at = l.size();
  for (std::size_t i = 0; i < l.size(); ++i)
    if (l[i].rfind("usage: ", 0) == 0) at = i;
  ASSERT_LT(at, l.size()) << r.out;
  double hours = 0.0, kq = 0.0;
  int lifts = 0;
  char u[16] = {}, q[16] = {};
  ASSERT_EQ(
      std::sscanf(l[at].c_str(), "usage: hours=%lf lifts=%d k_Q=%lf u_class=%15s q_class=%15s",
                  &hours, &lifts, &kq, u, q),
      5)
      << l[at];
  EXPECT_EQ(lifts, 1);
  EXPECT_NEAR(hours, 8.0 / 3600.0, 1e-6);
  EXPECT_NEAR(kq, std::pow(3600.0 / 12500.0, 3), 1e-5);
  EXPECT_STREQ(u, "U0");  // 1 lift
  EXPECT_STREQ(q, "Q0");  // 0.0239 <= 0.0313
  // The crane file's 20000 design hours at one lift in 8 s: 9e6 lifts, beyond U9's 8e6.
  double design = 0.0, projected = 0.0;
  ASSERT_EQ(
      std::sscanf(l[at + 1].c_str(), "usage_design: design_hours=%lf lifts_in_design_life=%lf",
                  &design, &projected),
      2)
      << l[at + 1];
  EXPECT_EQ(design, 20000.0);
  EXPECT_NEAR(projected, 20000.0 * 3600.0 / 8.0, 1e-5 * projected);
  EXPECT_NE(l[at + 1].find("u_class=above_U9"), std::string::npos) << l[at + 1];
  EXPECT_EQ(l[at + 2].rfind("usage_lift: lift_off_s=", 0), 0u) << l[at + 2];
  for (std::size_t i = at + 3; i < at + 7; ++i) {
    EXPECT_EQ(l[i].rfind("usage_hot_spot: name=", 0), 0u) << l[i];
  }
}

namespace {

// The lines of a file, the CSV column `drop` (0-based; -1: none) taken out of each.
std::vector<std::string> fileRows(const std::string& path, int drop = -1) {
  std::ifstream in(path);
  std::vector<std::string> rows;
  for (std::string line; std::getline(in, line);) {
    if (drop >= 0) {
      std::vector<std::string> cells;
      std::istringstream cs(line);
      for (std::string c; std::getline(cs, c, ',');) cells.push_back(c);
      cells.erase(cells.begin() + drop);
      line.clear();
      for (const std::string& c : cells) line += c + ",";
    }
    rows.push_back(line);
  }
  return rows;
}

}  // namespace

TEST(CraneSimCli, RowsOfASpeculationTakenBackAreFullOrdersOwn) {
  // Chrono's stress-free release on 20 elements: the reduced rope starts speculatively (its
  // tension touches zero at each bounce), is taken back, hands back later and is taken back
  // again, so every one of its 3000 steps is full order's in the end (docs/cli.md "Rows of a
  // speculation"). Its rows, node rows, warnings and summary are then full order's own run's,
  // digit for digit, but the full_order_steps column.
  const std::string scene = std::string(CRANE_TWIN_SOURCE_DIR) +
                            "/config/scenes/rope_pendulum_chrono.yaml --set duration=3 "
                            "--set rope.elements=20 --set output_interval=0.01 --quiet";
  std::map<std::string, Result> runs;
  for (const char* model : {"full", "reduced"}) {
    const std::string base = ::testing::TempDir() + "speculation_" + model;
    runs[model] = run("run " + scene + " --set rope.model=" + model + " --out " + base +
                      ".csv --nodes " + base + "_nodes.csv");
    ASSERT_EQ(runs[model].status, 0) << runs[model].out;
  }
  const std::string summary = lines(runs["reduced"].out).back();
  ASSERT_NE(summary.find(" taken_back=2 "), std::string::npos) << summary;
  ASSERT_NE(summary.find(" full_order_steps=3000 "), std::string::npos) << summary;
  const auto header = fileRows(::testing::TempDir() + "speculation_full.csv").front();
  const int column = static_cast<int>(
      std::count(header.begin(), header.begin() + header.find("full_order_steps"), ','));
  const auto full = fileRows(::testing::TempDir() + "speculation_full.csv", column);
  const auto reduced = fileRows(::testing::TempDir() + "speculation_reduced.csv", column);
  ASSERT_EQ(full.size(), 302u);  // header, t = 0, 0.01, ..., 3
  ASSERT_EQ(reduced.size(), full.size());
  for (std::size_t i = 0; i < full.size(); ++i) ASSERT_EQ(reduced[i], full[i]) << "row " << i;
  EXPECT_EQ(fileRows(::testing::TempDir() + "speculation_reduced_nodes.csv"),
            fileRows(::testing::TempDir() + "speculation_full_nodes.csv"));
  // What stderr and the summary say of the rows: warnings, lift-offs, the tension's peak.
  const auto summaryTail = [](const std::string& line) {
    return line.substr(line.find(" warnings_seen="),
                       line.find(" energy_consistent_steps=") - line.find(" warnings_seen=")) +
           line.substr(line.find(" lift_offs="),
                       line.find(" basis_additions=") - line.find(" lift_offs="));
  };
  const std::string full_summary = lines(runs["full"].out).back();
  EXPECT_EQ(summaryTail(summary), summaryTail(full_summary));
  EXPECT_EQ(runs["reduced"].out.substr(0, runs["reduced"].out.find("summary:")),
            runs["full"].out.substr(0, runs["full"].out.find("summary:")));
}

TEST(CraneSimCli, RowsOfASpeculationKeptAreTheReducedRunsInOrder) {
  // 12.5 t released stress-free from a rigid anchor: the reduced rope hands back speculatively
  // at its first step and keeps the hand-back after the 10 s window. crane_sim run holds the
  // rows back that long and then writes them as they were: every row, in order, the reduced
  // run's own (the same run stepped here, its rows' first seven columns written alike).
  const std::vector<std::string> sets = {"structure.model=rigid", "rope.elements=30",
                                         "time_step=0.002",       "duration=12",
                                         "output_interval=0.1",   "rope.model=reduced"};
  const std::string scene =
      std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/hard_stress_free_heavy.yaml";
  std::string args = "run " + scene + " --quiet";
  for (const std::string& s : sets) args += " --set " + s;
  const std::string csv = ::testing::TempDir() + "speculation_kept.csv";
  const Result r = run(args + " --out " + csv);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find(" taken_back=0 "), std::string::npos) << r.out;
  const auto rows = fileRows(csv);
  ASSERT_EQ(rows.size(), 122u);  // header, t = 0, 0.1, ..., 12
  crane_twin::InvariantReducedSimulation sim(
      crane_twin::buildCraneModel(crane_twin::loadScene(scene, sets)));
  sim.initialize();
  ASSERT_TRUE(sim.speculating()) << "no speculation at the start: the test tests nothing";
  const auto firstColumns = [](const std::string& row) {
    std::size_t at = 0;
    for (int c = 0; c < 7; ++c) at = row.find(',', at) + 1;
    return row.substr(0, at);
  };
  bool kept = false;
  for (int k = 0; k <= 6000; ++k) {
    if (k > 0) sim.step();
    kept = kept || (k > 0 && !sim.speculating());
    if (k % 50 != 0) continue;
    std::ostringstream own;
    crane_twin::writeSeriesRow(own, sim.series());
    ASSERT_EQ(firstColumns(rows[1 + k / 50]), firstColumns(own.str())) << "row at step " << k;
  }
  EXPECT_TRUE(kept) << "the speculation was not kept within the run";
  EXPECT_EQ(sim.handBacksTakenBack(), 0);
}
