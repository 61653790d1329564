#include "crane_twin/analysis/accuracy_sweep.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "crane_twin/io/config_reader.hpp"
#include "crane_twin/simulation/simulation.hpp"
#include "crane_twin/simulation/speculation_follower.hpp"
#include "crane_twin/simulation/subdomain_reduced_simulation.hpp"

namespace crane_twin {

Trajectory recordRun(const CraneModel& model, double interval, double* wall_s, int* subdomains,
                     double* mode_updates_s) {
  const Scene& sc = model.scene;
  const long every = std::lround(interval / sc.time_step);
  if (every < 1 || std::abs(every * sc.time_step - interval) > 1e-9) {
    throw InputError(sc.file + ": key 'time_step': " + std::to_string(sc.time_step) +
                     " s does not divide the sampling interval " + std::to_string(interval) + " s");
  }
  const std::unique_ptr<Simulation> sim = makeSimulation(model);
  sim->initialize();
  Trajectory tr;
  tr.rope_length = sc.rope.length;
  auto record = [&]() {
    Eigen::Vector3d p, c, j;
    sim->sample(p, c, j);
    tr.t.push_back(sim->time());
    tr.payload.push_back(p);
    tr.cab.push_back(c);
    tr.jib_tip.push_back(j);
    std::vector<Eigen::Vector3d> nodes(sim->ropeNodes());
    for (int k = 0; k < sim->ropeNodes(); ++k) nodes[k] = sim->ropeNode(k);
    tr.nodes.push_back(std::move(nodes));
  };
  // A speculation's samples (SpeculationFollower): where it is taken back, the samples from its
  // checkpoint on are those of full order's re-integrated steps (docs/cli.md "Rows of a
  // speculation"), as crane_sim run writes them.
  std::size_t held_from = 0;  // samples before the open speculation
  SpeculationFollower follower(*sim, {[&](long k) {
                                        if (k % every == 0) record();
                                      },
                                      [&] { held_from = tr.t.size(); },
                                      {},
                                      [&] { tr.keepFirst(held_from); }});
  follower.start();
  const long steps = std::lround(sc.duration / sc.time_step);
  double wall = 0.0;
  for (long k = 1; k <= steps; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    sim->step();
    wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    follower.step(k);
  }
  if (wall_s) *wall_s = wall;
  if (subdomains) *subdomains = sim->statistics().subdomains;
  if (mode_updates_s) *mode_updates_s = sim->statistics().mode_update_seconds;
  return tr;
}

namespace {
std::string num(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}
}  // namespace

std::vector<SweepCase> sweepGrid(const Scene& scene, bool quick) {
  std::vector<SweepCase> g;
  const std::vector<double> fullSteps =
      quick ? std::vector<double>{0.001, 0.01}
            : std::vector<double>{0.001, 0.002, 0.005, 0.01, 0.02, 0.05, 0.1};
  for (double dt : fullSteps) {
    g.push_back({"full",
                 {"rope.model=full", "time_step=" + num(dt)},
                 dt,
                 0,
                 0.0,
                 scene.structure_modes,
                 scene.structure_model});
  }
  const std::vector<int> modes = quick ? std::vector<int>{10} : std::vector<int>{6, 10, 20};
  const std::vector<double> deltas =
      quick ? std::vector<double>{0.05, 0.5} : std::vector<double>{0.05, 0.2, 0.5};
  const std::vector<double> steps =
      quick ? std::vector<double>{0.001, 0.01} : std::vector<double>{0.001, 0.005, 0.01};
  // The subdomain rungs run in the rope chord's frame (docs/accuracy-vs-time.md), unless the
  // scene itself chooses the subdomain reduction and its frame.
  const std::string frame = scene.rope.reduction == RopeReduction::subdomains
                                ? scene.rope.subdomain_frame
                                : "corotational";
  for (int m : modes)
    for (double d : deltas)
      for (double dt : steps) {
        g.push_back({"reduced",
                     {"rope.model=reduced", "rope.reduction=subdomains",
                      "rope.mode_count=" + std::to_string(m), "rope.subdomain_delta=" + num(d),
                      "time_step=" + num(dt)},
                     dt,
                     m,
                     d,
                     scene.structure_modes,
                     scene.structure_model,
                     frame});
      }
  if (!quick) {
    for (double dt : {0.02, 0.05}) {
      g.push_back({"reduced",
                   {"rope.model=reduced", "rope.reduction=subdomains", "rope.mode_count=10",
                    "rope.subdomain_delta=0.05", "time_step=" + num(dt)},
                   dt,
                   10,
                   0.05,
                   scene.structure_modes,
                   scene.structure_model,
                   frame});
    }
  }
  if (!quick && frame != "fixed") {
    for (double d : deltas) {
      g.push_back(
          {"reduced",
           {"rope.model=reduced", "rope.reduction=subdomains", "rope.mode_count=10",
            "rope.subdomain_delta=" + num(d), "time_step=0.005", "rope.subdomain_frame=fixed"},
           0.005,
           10,
           d,
           scene.structure_modes,
           scene.structure_model,
           "fixed"});
    }
  }
  if (!quick) {
    // The paper's setting: half of the rope DOF, the scene's delta and step.
    Scene half = scene;
    half.rope.mode_count = 0;
    half.rope.mode_fraction = 0.5;
    g.push_back({"reduced",
                 {"rope.model=reduced", "rope.reduction=subdomains", "rope.mode_count=0",
                  "rope.mode_fraction=0.5", "time_step=" + num(scene.time_step)},
                 scene.time_step,
                 keptRopeModes(half),
                 scene.rope.subdomain_delta,
                 scene.structure_modes,
                 scene.structure_model,
                 frame});
    if (frame != "fixed") {
      g.push_back({"reduced",
                   {"rope.model=reduced", "rope.reduction=subdomains", "rope.mode_count=0",
                    "rope.mode_fraction=0.5", "time_step=" + num(scene.time_step),
                    "rope.subdomain_frame=fixed"},
                   scene.time_step,
                   keptRopeModes(half),
                   scene.rope.subdomain_delta,
                   scene.structure_modes,
                   scene.structure_model,
                   "fixed"});
    }
    if (scene.crane && scene.structure_model == StructureModel::modal) {
      g.push_back({"reduced",
                   {"rope.model=reduced", "rope.reduction=subdomains", "rope.mode_count=10",
                    "rope.subdomain_delta=0.2", "time_step=0.005", "structure.modes=20"},
                   0.005,
                   10,
                   0.2,
                   20,
                   StructureModel::modal,
                   frame});
    }
  }
  // The default reduced rope (rotation-invariant basis, docs/model.md) at the full model's steps.
  for (double dt :
       quick ? std::vector<double>{0.001, 0.01} : std::vector<double>{0.001, 0.005, 0.01, 0.05}) {
    g.push_back({"invariant",
                 {"rope.model=reduced", "rope.reduction=invariant", "time_step=" + num(dt)},
                 dt,
                 0,
                 0.0,
                 scene.structure_modes,
                 scene.structure_model});
  }
  // The fidelity ladder: the pendulum rope, and the rigid structure under each rope model.
  auto pendulum = [&](double dt, int structureModes, StructureModel structure) {
    std::vector<std::string> o = {"rope.model=pendulum", "time_step=" + num(dt),
                                  std::string("structure.model=") + name(structure)};
    const bool rigid = structure == StructureModel::rigid;
    if (!rigid) o.push_back("structure.modes=" + std::to_string(structureModes));
    g.push_back({"pendulum", o, dt, 0, 0.0, rigid ? 0 : structureModes, structure});
  };
  const bool flexible = scene.crane && scene.structure_model != StructureModel::rigid;
  for (double dt : quick ? std::vector<double>{0.01} : std::vector<double>{0.001, 0.01, 0.05}) {
    pendulum(dt, scene.structure_modes, scene.structure_model);
  }
  if (!quick && flexible) {
    if (scene.structure_model == StructureModel::modal) pendulum(0.01, 20, StructureModel::modal);
    pendulum(0.001, 0, StructureModel::rigid);
    pendulum(0.01, 0, StructureModel::rigid);
    g.push_back({"full",
                 {"rope.model=full", "time_step=0.01", "structure.model=rigid"},
                 0.01,
                 0,
                 0.0,
                 0,
                 StructureModel::rigid});
    g.push_back({"reduced",
                 {"rope.model=reduced", "rope.reduction=subdomains", "rope.mode_count=10",
                  "rope.subdomain_delta=0.2", "time_step=0.005", "structure.model=rigid"},
                 0.005,
                 10,
                 0.2,
                 0,
                 StructureModel::rigid,
                 frame});
  }
  // Every subdomain rung names its frame (a scene of the default reduced rope sets none).
  for (SweepCase& c : g) {
    const auto& o = c.overrides;
    const bool subdomains = std::find(o.begin(), o.end(), "rope.reduction=subdomains") != o.end();
    const bool framed = std::any_of(o.begin(), o.end(), [](const std::string& x) {
      return x.rfind("rope.subdomain_frame=", 0) == 0;
    });
    if (subdomains && !framed) c.overrides.push_back("rope.subdomain_frame=" + frame);
  }
  return g;
}

std::vector<SweepResult> runSweep(const std::string& scene_file,
                                  const std::vector<std::string>& overrides,
                                  const std::vector<SweepCase>& cases, double reference_dt,
                                  double interval,
                                  const std::function<void(const SweepResult&)>& progress) {
  auto modelWith = [&](const std::vector<std::string>& extra) {
    std::vector<std::string> sets = overrides;
    // The scene's CSV output interval must not be below a step (recordRun samples on its own);
    // a case may set its own (later overrides win).
    sets.push_back("output_interval=" + num(interval));
    sets.insert(sets.end(), extra.begin(), extra.end());
    return buildCraneModel(loadScene(scene_file, sets));
  };
  const CraneModel refModel = modelWith({"rope.model=full", "time_step=" + num(reference_dt)});
  SweepResult ref;
  ref.setting = {"reference",
                 {},
                 reference_dt,
                 0,
                 0.0,
                 refModel.scene.structure_modes,
                 refModel.scene.structure_model};
  const Trajectory reference = recordRun(refModel, interval, &ref.wall_s);
  ref.rtf = refModel.scene.duration / ref.wall_s;
  std::vector<SweepResult> out{ref};
  if (progress) progress(ref);
  for (const SweepCase& c : cases) {
    SweepResult r;
    r.setting = c;
    // Steps longer than the sampling interval sample at their own step; the comparison then
    // uses the times both runs share.
    const double every = std::max(interval, c.time_step);
    std::vector<std::string> sets = c.overrides;
    sets.push_back("output_interval=" + num(every));
    const CraneModel m = modelWith(sets);
    const Trajectory t = recordRun(m, every, &r.wall_s, &r.subdomains, &r.mode_updates_s);
    r.rtf = m.scene.duration / r.wall_s;
    r.error = compareTrajectories(t, reference);
    out.push_back(r);
    if (progress) progress(r);
  }
  return out;
}

const char* const kSweepHeader =
    "scene,model,time_step,rope_modes,delta,structure_modes,wall_s,rtf,subdomains,"
    "mode_updates_s,payload_error_max,rope_rms_max,cab_error_max,jib_tip_error_max,"
    "structure_model,subdomain_frame";

std::string sweepRow(const std::string& scene, const SweepResult& r) {
  std::ostringstream s;
  s.precision(6);
  const SweepCase& c = r.setting;
  s << scene << ',' << c.model << ',' << c.time_step << ',' << c.rope_modes << ',' << c.delta << ','
    << c.structure_modes << ',' << r.wall_s << ',' << r.rtf << ',' << r.subdomains << ','
    << r.mode_updates_s << ',' << r.error.payload_max << ',' << r.error.rope_rms_max << ','
    << r.error.cab_max << ',' << r.error.jib_tip_max << ',' << name(c.structure_model) << ','
    << c.frame;
  return s.str();
}

}  // namespace crane_twin
