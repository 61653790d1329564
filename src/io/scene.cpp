#include "crane_twin/io/scene.hpp"

#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <utility>

#include "crane_twin/io/config_reader.hpp"
#include "crane_twin/loads/load_geometry.hpp"

namespace crane_twin {

namespace {

// The most steps a scene may ask for (duration / time_step): a count a run's step counter and
// its summary hold (1e12 steps of 1 ms are 32 years).
constexpr double kMaxSteps = 1e12;
// The fastest initial payload velocity a scene may give, per component [m/s].
constexpr double kMaxPayloadSpeed = 50.0;
// The deepest a resting load may sink into the ground under its weight, m g / ground.stiffness
// [m] (the default 1e8 N/m: 1.2 mm under 12.5 t; soft soil under a load's footprint takes
// centimetres).
constexpr double kMaxGroundSink = 0.1;

// Each model choice's values with the scene file's word for it (docs/scenes.md); the argument
// only picks the choice.
template <typename E, std::size_t N>
using Words = std::array<std::pair<E, const char*>, N>;
const Words<RopeModel, 3>& words(RopeModel) {
  static const Words<RopeModel, 3> w{{{RopeModel::pendulum, "pendulum"},
                                      {RopeModel::full, "full"},
                                      {RopeModel::reduced, "reduced"}}};
  return w;
}
const Words<RopeReduction, 2>& words(RopeReduction) {
  static const Words<RopeReduction, 2> w{
      {{RopeReduction::invariant, "invariant"}, {RopeReduction::subdomains, "subdomains"}}};
  return w;
}
const Words<StructureModel, 3>& words(StructureModel) {
  static const Words<StructureModel, 3> w{{{StructureModel::rigid, "rigid"},
                                           {StructureModel::modal, "modal"},
                                           {StructureModel::full, "full"}}};
  return w;
}
const Words<InitialMode, 3>& words(InitialMode) {
  static const Words<InitialMode, 3> w{{{InitialMode::equilibrium, "equilibrium"},
                                        {InitialMode::stress_free, "stress_free"},
                                        {InitialMode::landed, "landed"}}};
  return w;
}
const Words<IntegratorKind, 2>& words(IntegratorKind) {
  static const Words<IntegratorKind, 2> w{{{IntegratorKind::generalized_alpha, "generalized_alpha"},
                                           {IntegratorKind::newmark, "newmark"}}};
  return w;
}
const Words<SlewDriveModel, 2>& words(SlewDriveModel) {
  static const Words<SlewDriveModel, 2> w{
      {{SlewDriveModel::kinematic, "kinematic"}, {SlewDriveModel::torque, "torque"}}};
  return w;
}

template <typename E>
const char* wordOf(E e) {
  for (const auto& [value, word] : words(e))
    if (value == e) return word;
  return "?";  // not reached: every value has its word
}

// The choice `key` names (default `def`), read once, here: a word not in words() is refused
// with the words allowed.
template <typename E>
E choice(ConfigNode& n, const std::string& key, E def) {
  std::vector<std::string> allowed;
  for (const auto& entry : words(def)) allowed.push_back(entry.second);
  const std::string word = n.string(key, std::string(wordOf(def)), allowed);
  for (const auto& [value, w] : words(def))
    if (word == w) return value;
  return def;  // not reached: string() refuses any other word
}

}  // namespace

const char* name(RopeModel m) { return wordOf(m); }
const char* name(RopeReduction r) { return wordOf(r); }
const char* name(StructureModel m) { return wordOf(m); }
const char* name(InitialMode m) { return wordOf(m); }
const char* name(IntegratorKind i) { return wordOf(i); }
const char* name(SlewDriveModel m) { return wordOf(m); }

namespace {

// A key whose value must lie within a crane's limits [lo, hi] (what names the limits).
void checkWithin(ConfigNode& n, const std::string& key, double value, double lo, double hi,
                 const std::string& what) {
  if (value < lo || value > hi) {
    n.fail(key, "must be within the crane's " + what + " [" + std::to_string(lo) + ", " +
                    std::to_string(hi) + "] m");
  }
}

std::string resolveCraneFile(const std::string& scene_path, const std::string& name) {
  namespace fs = std::filesystem;
  if (name.size() > 5 && name.substr(name.size() - 5) == ".yaml") {
    fs::path p(name);
    if (p.is_relative()) p = fs::path(scene_path).parent_path() / p;
    return p.string();
  }
  return (fs::path(scene_path).parent_path() / ".." / "cranes" / (name + ".yaml")).string();
}

}  // namespace

Scene loadScene(const std::string& path, const std::vector<std::string>& overrides) {
  YAML::Node yaml = loadYamlFile(path);
  auto origins = std::make_shared<std::map<std::string, std::string>>();
  for (const auto& o : overrides) {
    applyOverride(yaml, o);
    (*origins)[o.substr(0, o.find('='))] = o;  // the last one wins, as in the YAML
  }
  ConfigNode root(yaml, path, "", origins);
  Scene s;
  s.file = path;

  s.crane_name = root.string("crane", std::nullopt);
  if (s.crane_name.empty()) root.fail("crane", "must name a crane file or be 'none'");
  if (s.crane_name != "none") {
    const std::string cf = resolveCraneFile(path, s.crane_name);
    std::error_code ec;  // a name too long for the file system is an error, not an exception
    if (!std::filesystem::is_regular_file(cf, ec)) {
      root.fail("crane", "crane file '" + cf + "' does not exist" +
                             (ec ? " (" + ec.message() + ")" : std::string()));
    }
    s.crane = loadCraneDescription(cf);
  }
  s.anchor = root.vec3("anchor", Eigen::Vector3d::Zero());
  if (s.crane && root.has("anchor")) root.fail("anchor", "only allowed with crane: none");

  s.duration = root.number("duration", std::nullopt, Bounds::positive());
  s.time_step = root.number("time_step", std::nullopt, Bounds::positive());
  if (s.time_step > s.duration) root.fail("time_step", "must not exceed duration");
  if (s.duration / s.time_step > kMaxSteps) {
    root.fail("duration",
              "asks for more than 1e12 steps of time_step (" + shownNumber(s.time_step) + " s)");
  }
  s.output_interval = root.number("output_interval", 0.01, Bounds::positive());
  if (s.output_interval < s.time_step * (1.0 - 1e-9)) {
    root.fail("output_interval", "must be at least time_step");
  }
  {
    ConfigNode n = root.map("integrator");
    s.integrator = choice(n, "method", IntegratorKind::generalized_alpha);
    s.rho_inf = n.number("rho_inf", 0.9, Bounds::closed(0.0, 1.0));
    n.finish();
  }
  {
    ConfigNode n = root.map("structure");
    s.structure_model = choice(n, "model", s.crane ? StructureModel::modal : StructureModel::rigid);
    s.structure_modes = n.integer("modes", 100, 1, 100000);
    s.structure_damping_ratio = n.number("damping_ratio", 0.01, Bounds::closed(0.0, 1.0));
    s.structure_geometric_stiffness = n.boolean("geometric_stiffness", false);
    n.finish();
    if (s.structure_geometric_stiffness && s.structure_model == StructureModel::rigid) {
      n.fail("geometric_stiffness",
             "acts on a flexible structure (structure.model: modal or full)");
    }
    if (!s.crane && s.structure_model != StructureModel::rigid) {
      root.fail("structure.model", "must be rigid with crane: none");
    }
  }
  {
    ConfigNode n = root.map("rope", true);
    RopeSettings& r = s.rope;
    const RopeSpec def = s.crane ? s.crane->rope : RopeSpec{};
    r.model = choice(n, "model", RopeModel::reduced);
    r.reduction = choice(n, "reduction", RopeReduction::invariant);
    r.elements = n.integer("elements", 120, 1, 100000);
    r.length = n.number("length", std::nullopt, Bounds::positive());
    r.falls = n.integer("falls", def.falls, 1, 12);
    r.bending = n.boolean("bending", true);
    r.mode_fraction = n.number("mode_fraction", 0.5, {0.0, 1.0, true, false});
    r.mode_count = n.integer("mode_count", 0, 0, 1000000);
    r.subdomain_delta = n.number("subdomain_delta", 0.05, Bounds::positive());
    r.mode_update = n.string("mode_update", "warm", {"cold", "warm"});
    r.subdomain_residual = n.number("subdomain_residual", 0.0, Bounds::nonNegative());
    r.subdomain_frame = n.string("subdomain_frame", "fixed", {"fixed", "corotational"});
    r.subdomain_rotation = n.number("subdomain_rotation", 0.1, Bounds::closed(1e-4, 1.0));
    r.tension_only = n.boolean("tension_only", true);
    // (1 s damps every axial mode of a crane rope far beyond critical)
    r.damping = n.number("damping", 0.0, Bounds::closed(0.0, 1.0));
    r.mass_per_length = n.number("mass_per_length", def.mass_per_length, kRopeMassPerLength);
    r.axial_stiffness = n.number("axial_stiffness", def.axial_stiffness, kRopeAxialStiffness);
    r.bending_stiffness =
        n.number("bending_stiffness", def.bending_stiffness, kRopeBendingStiffness);
    r.breaking_force = n.number("breaking_force", def.breaking_force, Bounds::positive());
    r.safety_factor = n.number("safety_factor", 5.0, Bounds::closed(1.0, 100.0));
    r.reeving_length = n.number("reeving_length", 0.0, Bounds::closed(0.0, 5000.0));
    n.finish();
    // The subdomain reduction's own keys mean nothing to the default reduced rope: refused there
    // rather than silently ignored (docs/scenes.md).
    if (r.model == RopeModel::reduced && r.reduction == RopeReduction::invariant) {
      for (const char* key : {"mode_fraction", "subdomain_delta", "mode_update",
                              "subdomain_residual", "subdomain_frame", "subdomain_rotation"}) {
        if (n.has(key)) {
          n.fail(key,
                 "applies to the subdomain reduction only (rope.reduction: subdomains); the "
                 "default reduced rope (rope.reduction: invariant) takes rope.mode_count");
        }
      }
    }
    if (s.crane) {
      checkWithin(n, "length", r.length, s.crane->min_rope_length, s.crane->max_rope_length,
                  "rope length limits");
    }
  }
  double payload_height = -1.0;  // payload.height; negative: from the drawn boxes
  {
    ConfigNode n = root.map("payload");
    s.payload_mass = n.number("mass", 0.0, Bounds::nonNegative());
    payload_height = n.number("height", -1.0, Bounds::any());
    if (n.has("height") && !(payload_height >= 0.0 && payload_height <= 100.0)) {
      n.fail("height", "must be in [0, 100] m");
    }
    n.finish();
  }
  {
    ConfigNode n = root.map("hook");
    s.hook_mass = n.number("mass", s.crane ? s.crane->hook_block_mass : 0.0, Bounds::nonNegative());
    s.hook_rigging_length = n.number("rigging_length", 0.0, Bounds::closed(0.0, 100.0));
    n.finish();
    if (s.hook_rigging_length > 0.0 && !(s.hook_mass > 0.0)) {
      n.fail("mass",
             "must be > 0 with a rigging_length (the hook block is the rigging's top point)");
    }
    if (s.hook_rigging_length > 0.0 && !(s.payload_mass > 0.0)) {
      n.fail("rigging_length", "needs payload.mass > 0 (the rigging carries the payload)");
    }
  }
  {
    ConfigNode n = root.map("trolley");
    s.trolley_radius = n.number("radius", s.crane ? s.crane->max_radius : 0.0, Bounds::any());
    n.finish();
    if (s.crane) {
      checkWithin(n, "radius", s.trolley_radius, s.crane->min_radius, s.crane->max_radius,
                  "radius limits");
    }
  }
  {
    ConfigNode n = root.map("slewing");
    s.slew_angle = n.number("angle", 0.0, Bounds::any());
    // On by default wherever the structure is flexible: the loads vanish while the crane does
    // not slew, and a node's command may slew any scene.
    s.slew_inertial_loads = n.boolean("inertial_loads", s.structure_model != StructureModel::rigid);
    if (n.has("drive")) {
      ConfigNode d = n.map("drive");
      SlewDriveSettings& dr = s.slew_drive;
      dr.model = choice(d, "model", SlewDriveModel::kinematic);
      if (dr.model == SlewDriveModel::torque) {
        if (!s.crane) d.fail("model", "a slewing drive needs a crane (crane: none has none)");
        dr.max_torque = d.number("max_torque", std::nullopt, Bounds::positive());
        dr.stiffness = d.number("stiffness", 0.0, Bounds::nonNegative());
        dr.damping = d.number("damping", 0.0, Bounds::nonNegative());
      } else {
        for (const char* k : {"max_torque", "stiffness", "damping"}) {
          if (d.has(k)) d.fail(k, "only used with model: torque");
        }
      }
      d.finish();
    }
    n.finish();
  }
  {
    ConfigNode n = root.map("site");
    s.site_position = n.vec3("position", Eigen::Vector3d::Zero());
    s.site_yaw_deg = n.number("yaw_deg", 0.0, Bounds::closed(-360.0, 360.0));
    n.finish();
  }
  {
    ConfigNode n = root.map("initial");
    s.initial_mode = choice(n, "mode", InitialMode::equilibrium);
    s.swing_deg = n.number("swing_deg", 0.0, Bounds::closed(0.0, 180.0));
    s.swing_azimuth_deg = n.number("swing_azimuth_deg", 0.0, Bounds::any());
    s.payload_velocity = n.vec3("payload_velocity", Eigen::Vector3d::Zero());
    if (!(s.payload_velocity.cwiseAbs().maxCoeff() <= kMaxPayloadSpeed)) {
      n.fail("payload_velocity", "must be at most " + shownNumber(kMaxPayloadSpeed) +
                                     " m/s in each component (a load thrown at 180 km/h)");
    }
    if (n.has("payload_offset")) {
      if (s.initial_mode != InitialMode::landed)
        n.fail("payload_offset", "only used with mode: landed");
      s.payload_offset = n.vec2("payload_offset");
      const double off = std::hypot(s.payload_offset.x(), s.payload_offset.y());
      if (!(off < s.rope.length)) {
        n.fail("payload_offset", "lies " + shownNumber(off) +
                                     " m off, not less than rope.length (" +
                                     shownNumber(s.rope.length) + " m): the rope cannot reach");
      }
    }
    if (s.initial_mode == InitialMode::landed) {
      for (const char* k : {"swing_deg", "swing_azimuth_deg", "payload_velocity"}) {
        if (n.has(k)) n.fail(k, "not used with mode: landed (the payload starts at rest)");
      }
      if (!root.has("ground")) {
        n.fail("mode", "landed needs a ground (ground: {height, ...}) to land the payload on");
      }
      if (!s.rope.tension_only) {
        n.fail("mode",
               "landed starts with a slack rope, which needs rope.tension_only: true (the "
               "symmetric law would push the load into the ground)");
      }
    }
    n.finish();
    if (s.initial_mode == InitialMode::equilibrium && s.swing_deg >= 90.0) {
      n.fail("swing_deg", "must be below 90 for an equilibrium start (use mode: stress_free)");
    }
  }
  s.gravity = root.number("gravity", 9.81, Bounds::closed(0.0, 100.0));
  if (root.has("wind")) {
    ConfigNode n = root.map("wind");
    WindSettings w;
    // (above any wind measured at the ground: 113 m/s)
    w.speed = n.number("speed", std::nullopt, Bounds::closed(0.0, 120.0));
    w.direction_deg = n.number("direction_deg", 0.0, Bounds::closed(-360.0, 360.0));
    w.profile_exponent = n.number("profile_exponent", 0.14, Bounds::closed(0.0, 1.0));
    if (n.has("gust")) {
      ConfigNode g = n.map("gust");
      w.gust_intensity = g.number("intensity", std::nullopt, Bounds::closed(0.0, 1.0));
      w.gust_seed = g.integer("seed", 0, 0, std::numeric_limits<int>::max());
      g.finish();
    }
    {
      // Default area: the payload drawn as a cube of 1000 kg/m^3 (docs/ros.md markers).
      ConfigNode p = n.map("payload");
      w.payload_area =
          p.number("area", payloadCubeFaceArea(s.payload_mass), Bounds::closed(0.0, 1000.0));
      w.payload_drag_coefficient = p.number("drag_coefficient", 1.05, Bounds::closed(0.0, 5.0));
      p.finish();
    }
    w.rope_drag_coefficient = n.number("rope_drag_coefficient", 1.2, Bounds::closed(0.0, 5.0));
    w.in_service_limit = n.number("in_service_limit", 20.0, Bounds::positive());
    n.finish();
    if (!s.crane && s.anchor.z() <= 0.0) {
      root.fail("wind",
                "with crane: none the anchor must stand above the ground (z > 0): the "
                "wind's profile is measured from z = 0");
    }
    if (s.rope.model == RopeModel::reduced && s.rope.reduction == RopeReduction::subdomains) {
      root.fail("wind",
                "the subdomain reduced rope (rope.reduction: subdomains) takes no wind; "
                "use rope.reduction: invariant, rope.model: full or pendulum");
    }
    s.wind = w;
  }
  {
    ConfigNode n = root.map("hoist");
    s.hoist_design_phi2 = n.number("design_phi2", 0.0, Bounds::any());
    if (n.has("design_phi2") && !(s.hoist_design_phi2 >= 1.0 && s.hoist_design_phi2 <= 10.0)) {
      n.fail("design_phi2", "must be in [1, 10] (a dynamic factor)");
    }
    n.finish();
  }
  if (root.has("ground")) {
    ConfigNode n = root.map("ground");
    GroundSettings g;
    // (a kilometre above or below the crane's base: beyond any site)
    g.height = n.number("height", 0.0, Bounds::closed(-1000.0, 1000.0));
    // (concrete under a load's footprint is some 1e9 to 1e10 N/m)
    g.stiffness = n.number("stiffness", 1e8, {0.0, 1e14, true, false});
    g.damping_ratio = n.number("damping_ratio", 1.0, Bounds::closed(0.0, 10.0));
    g.friction = n.number("friction", 0.5, Bounds::closed(0.0, 2.0));
    n.finish();
    if (!(s.payload_mass + s.hook_mass > 0.0)) {
      root.fail("ground", "needs a load on the rope (payload.mass or hook.mass > 0) to land");
    }
    if (s.rope.model == RopeModel::reduced && s.rope.reduction == RopeReduction::subdomains) {
      root.fail("ground",
                "the subdomain reduced rope (rope.reduction: subdomains) takes no ground; "
                "use rope.reduction: invariant, rope.model: full or pendulum");
    }
    // A ground the resting load sinks deep into is not the stiff landing surface the penalty
    // law models (docs/model.md "Ground contact"): its static sink m g / k is bounded.
    const double load = s.payload_mass + s.hook_mass, sink = load * s.gravity / g.stiffness;
    if (sink > kMaxGroundSink) {
      n.fail("stiffness", shownNumber(g.stiffness) + " N/m lets the resting load (" +
                              shownNumber(load) + " kg) sink " + shownNumber(sink) +
                              " m into the ground, more than " + shownNumber(kMaxGroundSink) +
                              " m: give at least " +
                              shownNumber(load * s.gravity / kMaxGroundSink) + " N/m");
    }
    s.ground = g;
  }
  // The payload's height: given, or the boxes' (hook block and cube, or the cube alone on a
  // rigging: loads/load_geometry.hpp).
  s.payload_height = payload_height >= 0.0
                         ? payload_height
                         : payloadUndersideDepth(s.hook_mass, s.payload_mass, s.hasRigging());
  double last_t = -1.0;
  for (ConfigNode c : root.mapList("commands")) {
    CommandEntry e;
    e.t = c.number("t", std::nullopt, Bounds::nonNegative());
    if (e.t <= last_t) c.fail("t", "commands must be in increasing time order");
    last_t = e.t;
    e.slew_rate = c.number("slew_rate", 0.0, Bounds::any());
    e.trolley_speed = c.number("trolley_speed", 0.0, Bounds::any());
    e.hoist_speed = c.number("hoist_speed", 0.0, Bounds::any());
    c.finish();
    s.commands.push_back(e);
  }
  if (root.has("random_commands")) {
    ConfigNode n = root.map("random_commands");
    if (!s.commands.empty()) n.fail("seed", "random_commands and commands exclude each other");
    if (!s.crane) n.fail("seed", "random commands need a crane (crane: none has no drives)");
    RandomCommandSpec r;
    r.seed = n.integer("seed", std::nullopt, 0, std::numeric_limits<int>::max());
    r.interval = n.number("interval", std::nullopt, Bounds::positive());
    r.fraction = n.number("fraction", 1.0, {0.0, 1.0, false, true});
    r.slew = n.boolean("slew", true);
    r.trolley = n.boolean("trolley", true);
    r.hoist = n.boolean("hoist", false);
    n.finish();
    s.commands = randomCommandSchedule(*s.crane, r, s.duration);
  }
  root.finish();
  return s;
}

// Entries at t = k interval (k = 0, 1, ... while t < duration), each rate uniform in
// [-fraction v_max, fraction v_max] of its drive (0 for a drive left out). The generator is
// std::mt19937 with the uniform variate built here from its raw output, so a seed gives the
// same schedule with every standard library.
std::vector<CommandEntry> randomCommandSchedule(const CraneDescription& crane,
                                                const RandomCommandSpec& spec, double duration) {
  std::mt19937 gen(static_cast<std::mt19937::result_type>(spec.seed));
  auto uniform = [&gen](double limit) {
    const double u = static_cast<double>(gen()) / 4294967296.0;  // [0, 1)
    return limit * (2.0 * u - 1.0);
  };
  std::vector<CommandEntry> out;
  for (long k = 0;; ++k) {
    CommandEntry e;
    e.t = static_cast<double>(k) * spec.interval;
    if (e.t >= duration) break;
    const double f = spec.fraction;
    e.slew_rate = spec.slew ? uniform(f * crane.slewing.max_speed) : 0.0;
    e.trolley_speed = spec.trolley ? uniform(f * crane.trolley.max_speed) : 0.0;
    e.hoist_speed = spec.hoist ? uniform(f * crane.hoist.max_speed) : 0.0;
    out.push_back(e);
  }
  return out;
}

}  // namespace crane_twin
