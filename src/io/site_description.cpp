#include "crane_twin/io/site_description.hpp"

#include <filesystem>
#include <regex>
#include <set>

#include "crane_twin/io/config_reader.hpp"

namespace crane_twin {

namespace {
std::string resolveScene(const std::string& site_path, const std::string& scene) {
  namespace fs = std::filesystem;
  if (scene.find('/') != std::string::npos ||
      (scene.size() > 5 && scene.substr(scene.size() - 5) == ".yaml")) {
    const fs::path p(scene);
    return p.is_absolute() ? scene : (fs::path(site_path).parent_path() / p).string();
  }
  return (fs::path(site_path).parent_path() / ".." / "scenes" / (scene + ".yaml")).string();
}
}  // namespace

SiteDescription loadSiteDescription(const std::string& path) {
  YAML::Node yaml = loadYamlFile(path);
  ConfigNode root(yaml, path);
  SiteDescription s;
  s.file = path;
  const std::regex name_rule("[A-Za-z][A-Za-z0-9_]*");
  std::set<std::string> names;
  for (ConfigNode c : root.mapList("cranes")) {
    SiteCrane k;
    k.name = c.string("name", std::nullopt);
    if (!std::regex_match(k.name, name_rule)) {
      c.fail("name", "'" + k.name + "' must be a ROS name: a letter, then letters, digits or _");
    }
    if (!names.insert(k.name).second) c.fail("name", "'" + k.name + "' names two cranes");
    k.scene = resolveScene(path, c.string("scene", std::nullopt));
    std::error_code ec;
    if (!std::filesystem::is_regular_file(k.scene, ec)) {
      c.fail("scene", "scene file '" + k.scene + "' does not exist");
    }
    k.overrides = c.stringList("overrides");
    k.position = c.vec3("position", Eigen::Vector3d::Zero());
    k.yaw_deg = c.number("yaw_deg", 0.0, Bounds::closed(-360.0, 360.0));
    c.finish();
    s.cranes.push_back(k);
  }
  if (s.cranes.empty()) root.fail("cranes", "must list at least one crane");
  {
    ConfigNode n = root.map("clearance");
    s.warn_distance = n.number("warn_distance", 10.0, Bounds::positive());
    s.error_distance = n.number("error_distance", 3.0, Bounds::positive());
    s.payload_radius = n.number("payload_radius", 1.0, Bounds::nonNegative());
    s.rate = n.number("rate", 10.0, Bounds::closed(0.1, 1000.0));
    n.finish();
    if (s.error_distance > s.warn_distance) {
      n.fail("error_distance", "must not exceed warn_distance");
    }
  }
  root.finish();
  return s;
}

}  // namespace crane_twin
