#include "crane_twin/analysis/usage_store.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>

#include "crane_twin/io/config_reader.hpp"
#include "crane_twin/io/input_error.hpp"

namespace crane_twin {

void saveUsageState(const UsageState& s, const std::string& path) {
  YAML::Emitter out;
  out.SetDoublePrecision(17);  // the counts read back exactly
  out << YAML::Comment("crane_twin usage count (docs/fatigue.md \"Lifetime counts\")");
  out << YAML::BeginMap;
  out << YAML::Key << "hours" << YAML::Value << s.hours;
  out << YAML::Key << "lifts" << YAML::Value << s.lift_count;
  out << YAML::Key << "max_load" << YAML::Value << s.max_load;
  out << YAML::Key << "mass_ratio_cubed_sum" << YAML::Value << s.mass_ratio_cubed_sum;
  out << YAML::Key << "recent_lifts" << YAML::Value << YAML::BeginSeq;
  for (const LiftRecord& l : s.recent_lifts) {
    out << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "lift_off" << YAML::Value << l.lift_off;
    if (!std::isnan(l.set_down)) out << YAML::Key << "set_down" << YAML::Value << l.set_down;
    out << YAML::Key << "mass" << YAML::Value << l.mass;
    out << YAML::Key << "phi_2" << YAML::Value << l.dynamic_factor;
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
  out << YAML::Key << "hot_spots" << YAML::Value << YAML::BeginSeq;
  for (const UsageState::HotSpot& h : s.hot_spots) {
    out << YAML::BeginMap;
    out << YAML::Key << "name" << YAML::Value << h.name;
    out << YAML::Key << "detail_category" << YAML::Value << h.detail_category;
    out << YAML::Key << "closed_cycles_damage" << YAML::Value << h.closed_damage;
    out << YAML::Key << "turning_points" << YAML::Value << YAML::Flow << h.counter.turning_points;
    out << YAML::Key << "pending" << YAML::Value << YAML::Flow << h.counter.pending;
    out << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap;
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp);
    f << out.c_str() << "\n";
    if (!f.good()) throw InputError("usage file '" + path + "': cannot write " + tmp);
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw InputError("usage file '" + path + "': cannot replace it");
  }
}

UsageState loadUsageState(const std::string& path) {
  ConfigNode root(loadYamlFile(path), path);
  UsageState s;
  s.hours = root.number("hours", std::nullopt, Bounds::nonNegative());
  s.lift_count = root.integer("lifts", std::nullopt, 0, std::numeric_limits<int>::max());
  s.max_load = root.number("max_load", std::nullopt, Bounds::nonNegative());
  s.mass_ratio_cubed_sum = root.number("mass_ratio_cubed_sum", std::nullopt, Bounds::nonNegative());
  for (ConfigNode l : root.mapList("recent_lifts")) {
    LiftRecord r;
    r.lift_off = l.number("lift_off", std::nullopt);
    if (l.has("set_down")) r.set_down = l.number("set_down", std::nullopt);
    r.mass = l.number("mass", std::nullopt, Bounds::nonNegative());
    r.dynamic_factor = l.number("phi_2", std::nullopt, Bounds::nonNegative());
    l.finish();
    s.recent_lifts.push_back(r);
  }
  for (ConfigNode h : root.mapList("hot_spots")) {
    UsageState::HotSpot spot;
    spot.name = h.string("name", std::nullopt);
    spot.detail_category = h.number("detail_category", std::nullopt, Bounds::positive());
    spot.closed_damage = h.number("closed_cycles_damage", std::nullopt, Bounds::nonNegative());
    spot.counter.turning_points = h.numberList("turning_points", Bounds::any());
    spot.counter.pending = h.numberList("pending", Bounds::any());
    if (spot.counter.pending.size() > 2) h.fail("pending", "holds at most two values");
    h.finish();
    s.hot_spots.push_back(spot);
  }
  root.finish();
  return s;
}

}  // namespace crane_twin
