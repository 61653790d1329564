// crane_sim: the command-line tool of SPEC 3.1 (no ROS). Exit status 0 on success, 2 on bad
// input (message on stderr), 1 on a numerical failure.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "crane_twin/config_reader.hpp"
#include "crane_twin/crane_model.hpp"
#include "crane_twin/modal_analysis.hpp"

namespace ct = crane_twin;

namespace {

struct SceneArgs {
  std::string scene;
  std::vector<std::string> sets;
};

void addSceneArgs(CLI::App* cmd, SceneArgs& a) {
  cmd->add_option("scene", a.scene, "scene file (YAML)")->required();
  cmd->add_option("--set", a.sets, "override a scene key: dotted.path=value (value is YAML)")
      ->take_all();
}

int runInfo(const SceneArgs& a) {
  const ct::CraneModel m = ct::buildCraneModel(ct::loadScene(a.scene, a.sets));
  std::printf("structure_nodes,%d\n", m.structure ? static_cast<int>(m.structure->nodes.size()) : 0);
  std::printf("structure_elements,%d\n",
              m.structure ? static_cast<int>(m.structure->members.size()) : 0);
  std::printf("structure_dofs,%d\n", m.structure ? m.structure->free_dofs : 0);
  std::printf("structure_mass,%.1f\n",
              m.structure ? m.structure->memberMass() + m.structure->lumpedMass() : 0.0);
  std::printf("rope_elements,%d\n", m.scene.rope.elements);
  std::printf("rope_dofs,%d\n", m.ropeDofs());
  std::printf("rope_mass,%.3f\n", m.ropeMass());
  // Beyond SPEC 3.1's required keys: what was built and the static load check of SPEC 1.2.
  std::printf("structure_model,%s\n", m.scene.structure_model.c_str());
  std::printf("rope_model,%s\n", m.scene.rope.model.c_str());
  std::printf("end_mass,%.1f\n", m.end_mass);
  if (m.structure) {
    std::printf("structure_member_mass,%.1f\n", m.structure->memberMass());
    std::printf("structure_lumped_mass,%.1f\n", m.structure->lumpedMass());
    const Eigen::VectorXd u = ct::staticTrolleyLoadDisplacement(
        *m.structure, m.scene.payload_mass, m.scene.trolley_radius, m.scene.gravity);
    std::printf("payload_jib_tip_dz,%.6f\n", ct::jibTipDisplacement(*m.structure, u).z());
    std::printf("payload_jib_bending_dz,%.6f\n", ct::jibBendingTipDz(*m.structure, u));
  }
  return 0;
}

int runModes(const SceneArgs& a, int count, const std::string& part) {
  const ct::CraneModel m = ct::buildCraneModel(ct::loadScene(a.scene, a.sets));
  if (part == "rope") {
    std::cerr << "crane_sim modes: --part rope needs the rope equilibrium solver, which this "
                 "build does not have yet\n";
    return 1;
  }
  if (!m.structure) {
    std::cerr << a.scene << ": key 'crane': scene has no structure (crane: none); "
              << "use --part rope\n";
    return 2;
  }
  if (count < 1 || count >= m.structure->free_dofs) {
    std::cerr << "--count must be in 1.." << m.structure->free_dofs - 1 << ", got " << count
              << "\n";
    return 2;
  }
  ct::ModalOptions opt;
  opt.count = count;
  const ct::ModalBasis b = ct::lowestModes(m.structure->K, m.structure->M, opt);
  std::printf("index,frequency_hz\n");
  for (int i = 0; i < count; ++i) std::printf("%d,%.6f\n", i + 1, b.frequencyHz(i));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"crane_sim: flat-top tower crane multibody simulator (crane_twin)"};
  app.require_subcommand(1);
  SceneArgs infoArgs, modesArgs;
  CLI::App* info = app.add_subcommand("info", "print the model's size as key,value lines");
  addSceneArgs(info, infoArgs);
  CLI::App* modes = app.add_subcommand("modes", "print natural frequencies as index,frequency_hz");
  addSceneArgs(modes, modesArgs);
  int count = 10;
  std::string part = "structure";
  modes->add_option("--count", count, "number of modes");
  modes->add_option("--part", part, "structure or rope")
      ->check(CLI::IsMember({"structure", "rope"}));
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  }
  try {
    if (*info) return runInfo(infoArgs);
    if (*modes) return runModes(modesArgs, count, part);
  } catch (const ct::InputError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "numerical failure: " << e.what() << "\n";
    return 1;
  }
  return 2;
}
