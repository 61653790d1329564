#include "node_settings.hpp"

#include <cmath>
#include <sstream>

#include "crane_twin/io/input_error.hpp"
#include "crane_twin/io/site_description.hpp"
#include "node_params.hpp"

namespace crane_twin {

NodeSettings readNodeSettings(const ros::NodeHandle& pnh) {
  NodeSettings s;
  // A crane of a site file (docs/site.md): its scene, overrides, pose and frame prefix.
  std::string site_file, site_crane;
  optionalParam(pnh, "site", site_file, "a string (a site file)");
  optionalParam(pnh, "site_crane", site_crane, "a string (a crane's name in ~site)");
  std::optional<SiteCrane> crane;
  if (!site_file.empty()) {
    if (site_crane.empty()) throw InputError("parameter '~site' needs '~site_crane' (a name)");
    for (const SiteCrane& c : loadSiteDescription(site_file).cranes)
      if (c.name == site_crane) crane = c;
    if (!crane) {
      throw InputError("parameter '~site_crane' '" + site_crane + "': no such crane in " +
                       site_file);
    }
    if (pnh.hasParam("scene")) {
      throw InputError("give '~scene' or '~site' with '~site_crane', not both");
    }
    s.scene = crane->scene;
    s.overrides = crane->overrides;
    s.frame_prefix = crane->name + "/";
    s.base_pose = {crane->position.x(), crane->position.y(), crane->position.z(),
                   crane->yaw_deg * M_PI / 180.0};
  } else if (!site_crane.empty()) {
    throw InputError("parameter '~site_crane' needs '~site' (a site file)");
  } else if (!pnh.getParam("scene", s.scene) || s.scene.empty()) {
    throw InputError("parameter '" + pnh.resolveName("scene") +
                     "' (path of a scene file) is required and must be a string");
  }
  // ~overrides: a list of "key=value" strings, or one such string (after the site's).
  std::string single;
  std::vector<std::string> extra;
  if (pnh.hasParam("overrides") && pnh.getParam("overrides", single)) {
    extra = {single};
  } else {
    optionalParam(pnh, "overrides", extra, "a list of strings key=value");
  }
  s.overrides.insert(s.overrides.end(), extra.begin(), extra.end());
  optionalParam(pnh, "real_time_factor", s.real_time_factor, "a number");
  optionalParam(pnh, "publish_rate", s.publish_rate, "a number");
  optionalParam(pnh, "structure_marker_rate", s.structure_marker_rate, "a number");
  optionalParam(pnh, "command_timeout", s.command_timeout, "a number");
  optionalParam(pnh, "publish_clock", s.publish_clock, "true or false");
  optionalParam(pnh, "duration", s.duration, "a number");
  optionalParam(pnh, "shutdown_at_end", s.shutdown_at_end, "true or false");
  optionalParam(pnh, "start_paused", s.start_paused, "true or false");
  optionalParam(pnh, "command_bag", s.command_bag, "a string");
  optionalParam(pnh, "wait_for_recorder", s.wait_for_recorder, "a node name");
  optionalParam(pnh, "frame_prefix", s.frame_prefix, "a string");
  optionalParam(pnh, "usage_file", s.usage.file, "a file name");
  optionalParam(pnh, "usage_save_period", s.usage.save_period, "a number");
  requireFinite("usage_save_period", s.usage.save_period, 0.0, true);
  if (!s.frame_prefix.empty() && s.frame_prefix.back() != '/') s.frame_prefix += '/';
  if (s.frame_prefix.find_first_of(" \t") != std::string::npos ||
      (!s.frame_prefix.empty() && s.frame_prefix.front() == '/')) {
    throw InputError("parameter '~frame_prefix' '" + s.frame_prefix +
                     "': a frame name has no blanks and no leading '/'");
  }
  optionalParam(pnh, "base_pose", s.base_pose, "a list of 4 numbers [x, y, z, yaw]");
  if (!s.base_pose.empty()) {
    if (s.base_pose.size() != 4) {
      throw InputError(
          "parameter '~base_pose' must be a list of 4 numbers [x, y, z, yaw] (m, rad), got " +
          std::to_string(s.base_pose.size()));
    }
    for (double v : s.base_pose)
      if (!std::isfinite(v)) throw InputError("parameter '~base_pose' must be finite");
  }
  std::string topics;
  if (pnh.hasParam("recorded_topics") && pnh.getParam("recorded_topics", topics)) {
    std::istringstream in(topics);  // one string: names separated by blanks (record.launch)
    for (std::string name; in >> name;) s.recorded_topics.push_back(name);
  } else {
    optionalParam(pnh, "recorded_topics", s.recorded_topics, "a list of topic names");
  }
  if (s.recorded_topics.empty()) s.recorded_topics = {"crane/state"};
  s.twin = readTwinSettings(pnh);
  optionalParam(pnh, "displacement_scale", s.snapshot.displacement_scale, "a number");
  optionalParam(pnh, "rope_samples_per_element", s.snapshot.samples_per_element, "an integer");
  requireFinite("real_time_factor", s.real_time_factor, 0.0, false);
  requireFinite("publish_rate", s.publish_rate, 0.0, true);
  requireFinite("structure_marker_rate", s.structure_marker_rate, 0.0, true);
  requireFinite("command_timeout", s.command_timeout, 0.0, false);
  requireFinite("displacement_scale", s.snapshot.displacement_scale, 0.0, false);
  if (!std::isfinite(s.duration)) throw InputError("parameter '~duration' must be finite");
  if (s.snapshot.samples_per_element < 1 || s.snapshot.samples_per_element > 64) {
    throw InputError("parameter '~rope_samples_per_element' must be in 1..64");
  }
  optionalParam(pnh, "follow_clock", s.follow_clock, "true or false");
  optionalParam(pnh, "clock_followers", s.clock_followers, "a list of crane/state topic names");
  if (s.follow_clock) {
    if (s.publish_clock) {
      throw InputError(
          "parameters '~follow_clock' and '~publish_clock' exclude each other: one "
          "node owns /clock, the others follow it");
    }
    if (!ros::Time::isSimTime()) {
      throw InputError(
          "parameter '~follow_clock' needs /use_sim_time true (set it in the launch "
          "file before the nodes start)");
    }
  } else if (s.real_time_factor == 0.0) {
    s.publish_clock = true;  // docs/ros.md: 0 drives /clock
  }
  if (!s.clock_followers.empty() && !s.publish_clock) {
    throw InputError(
        "parameter '~clock_followers' needs this node to own /clock "
        "(~publish_clock true or ~real_time_factor 0)");
  }
  return s;
}

BasePose basePoseOf(const NodeSettings& settings, const Scene& scene) {
  BasePose p;
  if (settings.base_pose.empty()) {
    p.position = scene.site_position;
    p.yaw = scene.site_yaw_deg * M_PI / 180.0;
  } else {
    const std::vector<double>& b = settings.base_pose;
    p.position = Eigen::Vector3d(b[0], b[1], b[2]);
    p.yaw = b[3];
  }
  return p;
}

PacerSettings pacerSettingsOf(const NodeSettings& settings, double time_step) {
  PacerSettings pacing;
  pacing.real_time_factor = settings.real_time_factor;
  pacing.publish_period = 1.0 / settings.publish_rate;
  pacing.time_step = time_step;
  pacing.follow_clock = settings.follow_clock;
  if (settings.twin.measured_input) pacing.catch_up = settings.twin.catch_up;
  return pacing;
}

}  // namespace crane_twin
