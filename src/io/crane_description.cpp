#include "crane_twin/io/crane_description.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "crane_twin/io/config_reader.hpp"

namespace crane_twin {

namespace {

// Bounds beyond any tower crane, so that a mistyped figure is refused by name instead of
// meshing a structure that overflows or fails numerically: lengths up to 1000 m, panels from
// 0.1 m, tubes up to 10 m across, moduli up to 1e13 Pa (diamond's is 1.2e12), densities up to
// 1e5 kg/m^3 (osmium's is 22590), masses up to 1e7 kg; the rope as the scene's rope.* keys.
const Bounds kLength{0.0, 1000.0, true, false};
const Bounds kPanel = Bounds::closed(0.1, 1000.0);
const Bounds kTube{0.0, 10.0, true, false};
const Bounds kModulus{0.0, 1e13, true, false};
const Bounds kDensity{0.0, 1e5, true, false};
const Bounds kMass{0.0, 1e7, true, false};

TubeSpec readTube(ConfigNode& parent, const std::string& key) {
  const auto v = parent.numberList(key, 2, kTube);
  if (2.0 * v[1] > v[0]) parent.fail(key, "wall thickness must be at most half the diameter");
  return {v[0], v[1]};
}

LatticeBoomSpec readBoom(ConfigNode n) {
  LatticeBoomSpec b;
  b.length = n.number("length", std::nullopt, kLength);
  b.width = n.number("width", std::nullopt, kLength);
  b.height = n.number("height", std::nullopt, kLength);
  b.panel = n.number("panel", std::nullopt, kPanel);
  if (b.panel > b.length) n.fail("panel", "must not exceed length");
  b.chord_segments = n.integer("chord_segments", 1, 1, 8);
  b.top_chord = readTube(n, "top_chord");
  b.bottom_chord = readTube(n, "bottom_chord");
  b.diagonal = readTube(n, "diagonal");
  b.horizontal = readTube(n, "horizontal");
  n.finish();
  return b;
}

DriveLimits readDrive(ConfigNode n) {
  DriveLimits d;
  d.max_speed = n.number("max_speed", std::nullopt, Bounds::positive());
  d.max_acceleration = n.number("max_acceleration", std::nullopt, Bounds::positive());
  n.finish();
  return d;
}

}  // namespace

BeamSection tubeSection(const CraneDescription& c, const TubeSpec& t) {
  return BeamSection::circularTube(t.outer_diameter, t.wall, c.E, c.G, c.density);
}

CraneDescription loadCraneDescription(const std::string& path) {
  ConfigNode root(loadYamlFile(path), path);
  CraneDescription c;
  c.file = path;
  c.name = root.string("name", std::nullopt);
  {
    ConfigNode m = root.map("material", true);
    c.E = m.number("youngs_modulus", std::nullopt, kModulus);
    c.G = m.number("shear_modulus", std::nullopt, kModulus);
    c.density = m.number("density", std::nullopt, kDensity);
    m.finish();
  }
  {
    ConfigNode m = root.map("mast", true);
    c.mast_height = m.number("height", std::nullopt, kLength);
    c.mast_width = m.number("width", std::nullopt, kLength);
    c.mast_panel = m.number("panel", std::nullopt, kPanel);
    if (c.mast_panel > c.mast_height) m.fail("panel", "must not exceed height");
    c.mast_chord = readTube(m, "chord");
    c.mast_diagonal = readTube(m, "diagonal");
    c.mast_horizontal = readTube(m, "horizontal");
    m.finish();
  }
  {
    ConfigNode m = root.map("slewing_unit", true);
    c.slewing_height = m.number("height", std::nullopt, kLength);
    c.slewing_member = readTube(m, "member");
    c.cab_position = m.vec3("cab_position", std::nullopt);
    m.finish();
  }
  c.jib = readBoom(root.map("jib", true));
  c.counter_jib = readBoom(root.map("counter_jib", true));
  // The booms' bottom chords sit on the slewing unit's corners (TowerCraneStructure).
  for (const auto& [key, boom] : {std::pair<const char*, const LatticeBoomSpec*>{"jib", &c.jib},
                                  {"counter_jib", &c.counter_jib}}) {
    if (std::abs(boom->width - c.mast_width) > 1e-9) {
      throw InputError(path + ": key '" + key + ".width': must equal mast.width (" +
                       shownNumber(c.mast_width) + " m): the boom root sits on the slewing unit");
    }
  }
  for (ConfigNode m : root.mapList("lumped_masses")) {
    LumpedMassSpec l;
    l.name = m.string("name", std::nullopt);
    l.mass = m.number("mass", std::nullopt, kMass);
    l.position = m.vec3("position", std::nullopt);
    l.nodes = m.integer("nodes", 1, 1, 8);
    m.finish();
    c.lumped_masses.push_back(l);
  }
  for (ConfigNode h : root.mapList("hot_spots")) {
    HotSpotSpec spot;
    spot.name = h.string("name", std::nullopt);
    if (spot.name.empty() ||
        spot.name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_") != std::string::npos) {
      h.fail("name", "must be lower-case letters, digits and _ (it names a CSV column)");
    }
    for (const HotSpotSpec& o : c.hot_spots) {
      if (o.name == spot.name) h.fail("name", "'" + spot.name + "' is named twice");
    }
    spot.point = h.vec3("point", std::nullopt);
    spot.along = h.vec3("along", std::nullopt);
    spot.fibre = h.vec3("fibre", std::nullopt);
    spot.detail_category = h.number("detail_category", std::nullopt, Bounds::positive());
    if (!(spot.along.norm() > 0.0)) h.fail("along", "must be a direction (not zero)");
    if (spot.fibre.cross(spot.along).norm() < 1e-6 * spot.fibre.norm() * spot.along.norm() ||
        !(spot.fibre.norm() > 0.0)) {
      h.fail("fibre", "must point across the member (not zero, not along it)");
    }
    h.finish();
    c.hot_spots.push_back(spot);
  }
  c.design_hours = root.number("design_hours", 0.0, Bounds::nonNegative());
  {
    ConfigNode m = root.map("trolley", true);
    c.trolley_mass = m.number("trolley_mass", std::nullopt, Bounds::closed(0.0, kMass.hi));
    c.hook_block_mass = m.number("hook_block_mass", std::nullopt, Bounds::closed(0.0, kMass.hi));
    c.min_radius = m.number("min_radius", std::nullopt, kLength);
    c.max_radius = m.number("max_radius", std::nullopt, kLength);
    if (c.min_radius >= c.max_radius) m.fail("min_radius", "must be below max_radius");
    if (c.max_radius > c.mast_width / 2 + c.jib.length) {
      m.fail("max_radius", "lies beyond the jib tip");
    }
    m.finish();
  }
  {
    ConfigNode m = root.map("load_chart", true);
    c.max_load = m.number("max_load", std::nullopt, Bounds::positive());
    c.rated_moment = m.number("rated_moment", std::nullopt, Bounds::positive());
    c.load_at_max_radius = m.number("load_at_max_radius", std::nullopt, Bounds::positive());
    m.finish();
  }
  {
    ConfigNode m = root.map("drives", true);
    c.slewing = readDrive(m.map("slewing", true));
    c.trolley = readDrive(m.map("trolley", true));
    c.hoist = readDrive(m.map("hoist", true));
    c.min_rope_length = m.number("min_rope_length", std::nullopt, kLength);
    c.max_rope_length = m.number("max_rope_length", std::nullopt, kLength);
    if (c.min_rope_length >= c.max_rope_length) {
      m.fail("min_rope_length", "must be below max_rope_length");
    }
    m.finish();
  }
  {
    ConfigNode m = root.map("rope", true);
    c.rope.mass_per_length = m.number("mass_per_length", std::nullopt, kRopeMassPerLength);
    c.rope.axial_stiffness = m.number("axial_stiffness", std::nullopt, kRopeAxialStiffness);
    c.rope.bending_stiffness = m.number("bending_stiffness", std::nullopt, kRopeBendingStiffness);
    c.rope.breaking_force = m.number("breaking_force", std::nullopt, Bounds::positive());
    c.rope.falls = m.integer("falls", std::nullopt, 1, 12);
    m.finish();
  }
  root.finish();
  return c;
}

double allowedLoad(const CraneDescription& c, double r) {
  const double r1 = c.rated_moment / c.max_load;
  if (r <= r1) return c.max_load;
  const double m1 = c.rated_moment, m2 = c.load_at_max_radius * c.max_radius;
  const double f = std::min(1.0, (r - r1) / (c.max_radius - r1));
  return (m1 + (m2 - m1) * f) / r;
}

}  // namespace crane_twin
