// Validated access to YAML configuration (scene and crane description files).
//
// Every value is read through a ConfigNode that knows its file and dotted key path, so each
// error names both: "scenes/x.yaml: key 'rope.elements': must be an integer >= 1, got 0".
// Keys that were never read are reported by finish() as unknown keys. Errors are InputError,
// which the CLI maps to exit status 2.
#pragma once

#include <yaml-cpp/yaml.h>

#include <Eigen/Dense>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "crane_twin/io/input_error.hpp"

namespace crane_twin {

/// Open interval / closed interval bounds for numeric keys.
struct Bounds {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false;
  bool hi_open = false;
  static Bounds positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }
  static Bounds nonNegative() {
    return {0.0, std::numeric_limits<double>::infinity(), false, false};
  }
  static Bounds closed(double a, double b) { return {a, b, false, false}; }
  static Bounds any() { return {}; }
  std::string describe() const;
  bool contains(double v) const;
};

/// A number as a message shows it (six significant digits: 65.52, 1e+200).
std::string shownNumber(double v);

/// The rope's section per fall, in a scene's rope.* keys and a crane file's rope: (the largest
/// crane ropes: some 130 mm, 100 kg/m, E A 1e9 N; a solid steel bar of 60 mm has E I 1.3e5
/// N m^2) bounds beyond any of them, refused by name rather than failing numerically.
inline const Bounds kRopeMassPerLength{0.0, 100.0, true, false};       // [kg/m]
inline const Bounds kRopeAxialStiffness{0.0, 1e12, true, false};       // [N]
inline const Bounds kRopeBendingStiffness = Bounds::closed(0.0, 1e8);  // [N m^2]

/// Load a YAML file; InputError names the file on a missing file or a syntax error.
YAML::Node loadYamlFile(const std::string& path);

class ConfigNode {
 public:
  /// `overrides`: key path -> the `key=value` that set it (a message about such a key names the
  /// override, not only the file).
  ConfigNode(YAML::Node node, std::string file, std::string path = "",
             std::shared_ptr<const std::map<std::string, std::string>> overrides = nullptr);

  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }
  bool has(const std::string& key) const;

  /// Sub-map; missing -> empty map if optional, InputError if required.
  ConfigNode map(const std::string& key, bool required = false);
  /// Sequence of maps under key (may be absent -> empty).
  std::vector<ConfigNode> mapList(const std::string& key);

  double number(const std::string& key, std::optional<double> def, Bounds b = Bounds::any());
  int integer(const std::string& key, std::optional<int> def, int lo, int hi);
  bool boolean(const std::string& key, std::optional<bool> def);
  std::string string(const std::string& key, std::optional<std::string> def,
                     const std::vector<std::string>& allowed = {});
  Eigen::Vector3d vec3(const std::string& key, std::optional<Eigen::Vector3d> def);
  /// A required list of 2 finite numbers.
  Eigen::Vector2d vec2(const std::string& key);
  std::vector<double> numberList(const std::string& key, std::size_t size, Bounds b);
  /// A list of numbers of any length within `b`; absent or null: empty.
  std::vector<double> numberList(const std::string& key, Bounds b);
  /// A list of strings; absent or null: empty.
  std::vector<std::string> stringList(const std::string& key);

  /// Throws InputError naming the first key that was not read.
  void finish() const;

  [[noreturn]] void fail(const std::string& key, const std::string& what) const;
  std::string keyPath(const std::string& key) const;

 private:
  YAML::Node scalarOrNull(const std::string& key) const;
  YAML::Node node_;
  std::string file_;
  std::string path_;
  mutable std::set<std::string> used_;
  std::shared_ptr<const std::map<std::string, std::string>> overrides_;
  /// An unknown key of this map within a small edit distance of `key`, or "".
  std::string nearUnknownKey(const std::string& key) const;
};

/// Apply a `--set a.b.c=value` override: value parsed as YAML, intermediate maps created.
/// Throws InputError on a malformed override.
void applyOverride(YAML::Node& root, const std::string& assignment);

}  // namespace crane_twin
