#include "crane_twin/io/config_reader.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace crane_twin {

std::string shownNumber(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

namespace {
std::string shown(const YAML::Node& n) {
  if (!n.IsDefined() || n.IsNull()) return "nothing";
  std::ostringstream s;
  YAML::Emitter e;
  e << YAML::Flow << n;
  s << e.c_str();
  std::string out = s.str();
  if (out.size() > 60) out = out.substr(0, 57) + "...";
  return "'" + out + "'";
}
}  // namespace

std::string Bounds::describe() const {
  const bool hasLo = std::isfinite(lo), hasHi = std::isfinite(hi);
  if (hasLo && hasHi) {
    return std::string("in ") + (lo_open ? "(" : "[") + shownNumber(lo) + ", " + shownNumber(hi) +
           (hi_open ? ")" : "]");
  }
  if (hasLo) return std::string(lo_open ? "> " : ">= ") + shownNumber(lo);
  if (hasHi) return std::string(hi_open ? "< " : "<= ") + shownNumber(hi);
  return "a finite number";
}

bool Bounds::contains(double v) const {
  if (!std::isfinite(v)) return false;
  if (lo_open ? !(v > lo) : !(v >= lo)) return false;
  if (hi_open ? !(v < hi) : !(v <= hi)) return false;
  return true;
}

YAML::Node loadYamlFile(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw InputError(path + ": is a directory, not a YAML file");
  }
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open file (missing or unreadable)");
  std::stringstream buf;
  buf << in.rdbuf();
  if (in.bad()) throw InputError(path + ": read error");
  if (buf.str().find_first_not_of(" \t\r\n") == std::string::npos) {
    throw InputError(path + ": file is empty");
  }
  YAML::Node root;
  try {
    root = YAML::Load(buf.str());
  } catch (const YAML::Exception& e) {
    throw InputError(path + ": YAML syntax error at line " + std::to_string(e.mark.line + 1) +
                     ", column " + std::to_string(e.mark.column + 1) + ": " + e.msg);
  }
  if (!root.IsMap()) throw InputError(path + ": top level must be a map of keys");
  return root;
}

ConfigNode::ConfigNode(YAML::Node node, std::string file, std::string path,
                       std::shared_ptr<const std::map<std::string, std::string>> overrides)
    : node_(std::move(node)),
      file_(std::move(file)),
      path_(std::move(path)),
      overrides_(std::move(overrides)) {}

namespace {
// Levenshtein distance (insertions, deletions, substitutions; a swap of neighbours counts 2).
std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}
// Close enough to be a misspelling: at most 2 edits, and fewer than half the name.
bool nearName(const std::string& a, const std::string& b) {
  const std::size_t d = editDistance(a, b);
  return d > 0 && d <= 2 && 2 * d < std::max(a.size(), b.size());
}
}  // namespace

std::string ConfigNode::nearUnknownKey(const std::string& key) const {
  if (!node_.IsMap()) return "";
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    if (!it->first.IsScalar()) continue;
    const std::string k = it->first.Scalar();
    if (!used_.count(k) && nearName(k, key)) return k;
  }
  return "";
}

std::string ConfigNode::keyPath(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

void ConfigNode::fail(const std::string& key, const std::string& what) const {
  // A required key that is missing because it was misspelt: report the misspelling.
  if (what.rfind("is required", 0) == 0) {
    const std::string typo = nearUnknownKey(key);
    if (!typo.empty()) {
      throw InputError(file_ + ": key '" + keyPath(typo) + "': unknown key (did you mean '" +
                       keyPath(key) + "'?)");
    }
  }
  std::string origin;
  if (overrides_) {  // the override that set this key or a map above it
    for (std::string p = keyPath(key);; p = p.substr(0, p.rfind('.'))) {
      const auto o = overrides_->find(p);
      if (o != overrides_->end()) {
        origin = " (set by the override '" + o->second + "')";
        break;
      }
      if (p.find('.') == std::string::npos) break;
    }
  }
  throw InputError(file_ + ": key '" + keyPath(key) + "': " + what + origin);
}

bool ConfigNode::has(const std::string& key) const {
  return node_.IsMap() && node_[key].IsDefined() && !node_[key].IsNull();
}

YAML::Node ConfigNode::scalarOrNull(const std::string& key) const {
  used_.insert(key);
  if (!node_.IsMap()) return YAML::Node();
  YAML::Node n = node_[key];
  return n;
}

ConfigNode ConfigNode::map(const std::string& key, bool required) {
  YAML::Node n = scalarOrNull(key);
  if (!n.IsDefined() || n.IsNull()) {
    if (required) fail(key, "is required");
    return ConfigNode(YAML::Node(YAML::NodeType::Map), file_, keyPath(key), overrides_);
  }
  if (!n.IsMap()) fail(key, "must be a map of keys, got " + shown(n));
  return ConfigNode(n, file_, keyPath(key), overrides_);
}

std::vector<ConfigNode> ConfigNode::mapList(const std::string& key) {
  YAML::Node n = scalarOrNull(key);
  std::vector<ConfigNode> out;
  if (!n.IsDefined() || n.IsNull()) return out;
  if (!n.IsSequence()) fail(key, "must be a list, got " + shown(n));
  for (std::size_t i = 0; i < n.size(); ++i) {
    if (!n[i].IsMap()) fail(key, "entry " + std::to_string(i) + " must be a map");
    out.emplace_back(n[i], file_, keyPath(key) + "[" + std::to_string(i) + "]", overrides_);
  }
  return out;
}

double ConfigNode::number(const std::string& key, std::optional<double> def, Bounds b) {
  YAML::Node n = scalarOrNull(key);
  if (!n.IsDefined() || n.IsNull()) {
    if (!def) fail(key, "is required (a number " + b.describe() + ")");
    return *def;
  }
  double v = 0.0;
  if (!n.IsScalar()) fail(key, "must be a number, got " + shown(n));
  try {
    v = n.as<double>();
  } catch (const YAML::Exception&) {
    fail(key, "must be a number, got " + shown(n));
  }
  if (!b.contains(v)) fail(key, "must be " + b.describe() + ", got " + shownNumber(v));
  return v;
}

int ConfigNode::integer(const std::string& key, std::optional<int> def, int lo, int hi) {
  YAML::Node n = scalarOrNull(key);
  const std::string range =
      "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  if (!n.IsDefined() || n.IsNull()) {
    if (!def) fail(key, "is required (" + range + ")");
    return *def;
  }
  long long v = 0;
  if (!n.IsScalar()) fail(key, "must be " + range + ", got " + shown(n));
  try {
    v = n.as<long long>();
  } catch (const YAML::Exception&) {
    fail(key, "must be " + range + ", got " + shown(n));
  }
  if (v < lo || v > hi) fail(key, "must be " + range + ", got " + std::to_string(v));
  return static_cast<int>(v);
}

bool ConfigNode::boolean(const std::string& key, std::optional<bool> def) {
  YAML::Node n = scalarOrNull(key);
  if (!n.IsDefined() || n.IsNull()) {
    if (!def) fail(key, "is required (true or false)");
    return *def;
  }
  if (!n.IsScalar()) fail(key, "must be true or false, got " + shown(n));
  try {
    return n.as<bool>();
  } catch (const YAML::Exception&) {
    fail(key, "must be true or false, got " + shown(n));
  }
}

std::string ConfigNode::string(const std::string& key, std::optional<std::string> def,
                               const std::vector<std::string>& allowed) {
  YAML::Node n = scalarOrNull(key);
  std::string v;
  if (!n.IsDefined() || n.IsNull()) {
    if (!def) fail(key, "is required");
    v = *def;
  } else {
    if (!n.IsScalar()) fail(key, "must be a string, got " + shown(n));
    v = n.Scalar();
  }
  if (!allowed.empty()) {
    bool ok = false;
    std::string list;
    for (const auto& a : allowed) {
      ok = ok || (a == v);
      list += (list.empty() ? "" : ", ") + a;
    }
    if (!ok) fail(key, "must be one of " + list + ", got '" + v + "'");
  }
  return v;
}

std::vector<double> ConfigNode::numberList(const std::string& key, std::size_t size, Bounds b) {
  YAML::Node n = scalarOrNull(key);
  const std::string want = "a list of " + std::to_string(size) + " numbers";
  if (!n.IsDefined() || n.IsNull()) fail(key, "is required (" + want + ")");
  if (!n.IsSequence() || n.size() != size) fail(key, "must be " + want + ", got " + shown(n));
  std::vector<double> out(size);
  for (std::size_t i = 0; i < size; ++i) {
    try {
      if (!n[i].IsScalar()) throw YAML::Exception(YAML::Mark(), "");
      out[i] = n[i].as<double>();
    } catch (const YAML::Exception&) {
      fail(key, "must be " + want + ", got " + shown(n));
    }
    if (!b.contains(out[i])) {
      fail(key, "entry " + std::to_string(i) + " must be " + b.describe() + ", got " +
                    shownNumber(out[i]));
    }
  }
  return out;
}

std::vector<double> ConfigNode::numberList(const std::string& key, Bounds b) {
  YAML::Node n = scalarOrNull(key);
  if (!n.IsDefined() || n.IsNull()) return {};
  if (!n.IsSequence()) fail(key, "must be a list of numbers, got " + shown(n));
  return numberList(key, n.size(), b);
}

std::vector<std::string> ConfigNode::stringList(const std::string& key) {
  YAML::Node n = scalarOrNull(key);
  std::vector<std::string> out;
  if (!n.IsDefined() || n.IsNull()) return out;
  if (!n.IsSequence()) fail(key, "must be a list of strings, got " + shown(n));
  for (std::size_t i = 0; i < n.size(); ++i) {
    if (!n[i].IsScalar()) fail(key, "entry " + std::to_string(i) + " must be a string");
    out.push_back(n[i].Scalar());
  }
  return out;
}

Eigen::Vector3d ConfigNode::vec3(const std::string& key, std::optional<Eigen::Vector3d> def) {
  if (!has(key)) {
    used_.insert(key);
    if (!def) fail(key, "is required (a list of 3 numbers)");
    return *def;
  }
  const auto v = numberList(key, 3, Bounds::any());
  return {v[0], v[1], v[2]};
}

Eigen::Vector2d ConfigNode::vec2(const std::string& key) {
  if (!has(key)) fail(key, "is required (a list of 2 numbers)");
  const auto v = numberList(key, 2, Bounds::any());
  return {v[0], v[1]};
}

void ConfigNode::finish() const {
  if (!node_.IsMap()) return;
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    if (!it->first.IsScalar()) {  // e.g. `{a:, [0, 0, 3]}`: a list used as a key
      throw InputError(file_ + ": " + (path_.empty() ? "the top level" : "key '" + path_ + "'") +
                       " holds a key that is not a name (a list or map used as a key)");
    }
    const std::string k = it->first.Scalar();
    if (!used_.count(k)) {
      std::string hint;
      for (const std::string& known : used_)
        if (nearName(k, known)) hint = " (did you mean '" + keyPath(known) + "'?)";
      std::string origin;
      if (overrides_) {
        const auto o = overrides_->find(keyPath(k));
        if (o != overrides_->end()) origin = " (set by the override '" + o->second + "')";
      }
      throw InputError(file_ + ": key '" + keyPath(k) + "': unknown key" + hint + origin);
    }
  }
}

void applyOverride(YAML::Node& root, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw InputError("--set '" + assignment + "': expected key.path=value");
  }
  const std::string path = assignment.substr(0, eq);
  const std::string text = assignment.substr(eq + 1);
  YAML::Node value;
  try {
    value = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError("--set '" + assignment + "': value is not valid YAML: " + e.msg);
  }
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const auto dot = path.find('.', start);
    parts.push_back(path.substr(start, dot - start));
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  for (const auto& p : parts) {
    if (p.empty()) throw InputError("--set '" + assignment + "': empty key in path '" + path + "'");
  }
  // Walk with explicit node copies (yaml-cpp nodes are references into the tree).
  std::vector<YAML::Node> chain{root};
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    YAML::Node cur = chain.back();
    YAML::Node next = cur[parts[i]];
    if (!next.IsDefined() || next.IsNull()) {
      cur[parts[i]] = YAML::Node(YAML::NodeType::Map);
      next = cur[parts[i]];
    } else if (!next.IsMap()) {
      throw InputError("--set '" + assignment + "': key '" + parts[i] + "' is not a map");
    }
    chain.push_back(next);
  }
  chain.back()[parts.back()] = value;
}

}  // namespace crane_twin
