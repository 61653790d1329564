// site_monitor: the clearance between the cranes of a site (docs/site.md). A thin adapter over
// the core's SiteDescription and cranePartsOnSite / minimumClearance: it subscribes to each
// crane's <name>/crane/state (and <name>/crane/forecast where the crane forecasts, docs/twin.md),
// and at the site's rate publishes one crane_twin/SiteClearance per pair on site/clearance (the
// clearance now and the closest approach along both forecasts), the closest points as markers
// (site/clearance_markers) and one diagnostic status per pair (WARN, ERROR under the site's
// distances, now or predicted).
#include <diagnostic_msgs/DiagnosticArray.h>
#include <nav_msgs/Path.h>
#include <ros/ros.h>
#include <visualization_msgs/MarkerArray.h>

#include <map>
#include <memory>
#include <optional>

#include "crane_twin/CraneState.h"
#include "crane_twin/SiteClearance.h"
#include "crane_twin/analysis/site_clearance.hpp"
#include "crane_twin/io/config_reader.hpp"
#include "crane_twin/io/scene.hpp"
#include "crane_twin/io/site_description.hpp"
#include "ros_messages.hpp"

namespace crane_twin {
namespace {

struct MonitoredCrane {
  SiteCrane site;
  CraneDescription description;
  SitePose pose;
  std::optional<CraneState> state;
  std::optional<PayloadPath> forecast;
  double forecast_start = 0.0;  ///< stamp of the forecast's start [s]
  ros::Subscriber sub, forecast_sub;
};

class SiteMonitor {
 public:
  SiteMonitor(ros::NodeHandle nh, const SiteDescription& site) : nh_(nh), site_(site) {
    for (const SiteCrane& c : site.cranes) {
      const Scene scene = loadScene(c.scene, c.overrides);
      if (!scene.crane) {
        throw InputError(site.file + ": crane '" + c.name +
                         "': its scene has no crane (crane: none)");
      }
      auto m = std::make_unique<MonitoredCrane>();
      m->site = c;
      m->description = *scene.crane;
      m->pose = SitePose{c.position, c.yaw_deg * M_PI / 180.0};
      MonitoredCrane* raw = m.get();
      m->sub = nh_.subscribe<CraneState>(c.name + "/crane/state", 10,
                                         [raw](const CraneState::ConstPtr& s) { raw->state = *s; });
      m->forecast_sub = nh_.subscribe<nav_msgs::Path>(
          c.name + "/crane/forecast", 2, [raw](const nav_msgs::Path::ConstPtr& p) {
            if (p->header.frame_id != "world") return;  // the twin publishes the site frame
            PayloadPath path;
            for (const auto& ps : p->poses) {
              path.t.push_back(ps.header.stamp.toSec());
              path.payload.push_back(fromMsg(ps.pose.position));
            }
            raw->forecast = path;
            raw->forecast_start = p->header.stamp.toSec();
          });
      cranes_.push_back(std::move(m));
    }
    clearance_pub_ = nh_.advertise<SiteClearance>("site/clearance", 10);
    marker_pub_ = nh_.advertise<visualization_msgs::MarkerArray>("site/clearance_markers", 2);
    diag_pub_ = nh_.advertise<diagnostic_msgs::DiagnosticArray>("/diagnostics", 5);
    timer_ = nh_.createWallTimer(ros::WallDuration(1.0 / site.rate),
                                 [this](const ros::WallTimerEvent&) { update(); });
    ROS_INFO("site_monitor: %zu cranes from %s, warn under %g m, error under %g m", cranes_.size(),
             site.file.c_str(), site.warn_distance, site.error_distance);
  }

 private:
  static CraneClearanceState clearanceState(const MonitoredCrane& c) {
    const CraneState& s = *c.state;
    CraneClearanceState k;
    k.slew_angle = s.slew_angle;
    k.jib_tip_displacement = fromMsg(s.jib_tip_displacement);
    k.trolley = fromMsg(s.trolley);
    k.payload = fromMsg(s.payload);
    return k;
  }
  ClearanceSettings settings() const {
    ClearanceSettings settings;
    settings.payload_radius = site_.payload_radius;
    return settings;
  }
  std::vector<CranePart> partsOf(const MonitoredCrane& c) const {
    return cranePartsOnSite(c.description, c.pose, clearanceState(c), settings());
  }

  void update() {
    diagnostic_msgs::DiagnosticArray diag;
    diag.header.stamp = ros::Time::now();
    visualization_msgs::MarkerArray markers;
    int id = 0;
    for (std::size_t i = 0; i < cranes_.size(); ++i)
      for (std::size_t j = i + 1; j < cranes_.size(); ++j) {
        const MonitoredCrane &a = *cranes_[i], &b = *cranes_[j];
        diagnostic_msgs::DiagnosticStatus d;
        d.name = ros::this_node::getName() + ": " + a.site.name + " - " + b.site.name;
        d.hardware_id = site_.file;
        if (!a.state || !b.state) {
          d.level = diagnostic_msgs::DiagnosticStatus::STALE;
          d.message =
              "waiting for " + std::string(!a.state ? a.site.name : b.site.name) + "/crane/state";
          diag.status.push_back(d);
          continue;
        }
        const PartClearance p = minimumClearance(partsOf(a), partsOf(b));
        const ClearanceLevel level =
            clearanceLevel(p.distance, site_.warn_distance, site_.error_distance);
        SiteClearance m;
        m.header.stamp = a.state->header.stamp > b.state->header.stamp ? a.state->header.stamp
                                                                       : b.state->header.stamp;
        m.header.frame_id = "world";
        m.crane_a = a.site.name;
        m.crane_b = b.site.name;
        m.min_distance = p.distance;
        m.part_a = p.part_a;
        m.part_b = p.part_b;
        m.point_a = point(p.point_a);
        m.point_b = point(p.point_b);
        m.level = static_cast<uint8_t>(level);
        m.stamp_gap = std::abs(a.state->t - b.state->t);
        ForecastClearance f;
        if (a.forecast && b.forecast) {
          // Samples of the two paths within half a second of each other count as one instant.
          f = forecastClearance(a.description, a.pose, clearanceState(a), *a.forecast,
                                b.description, b.pose, clearanceState(b), *b.forecast, settings(),
                                0.5);
        }
        m.forecast_valid = f.valid;
        if (f.valid) {
          m.forecast_min_distance = f.closest.distance;
          m.forecast_time_ahead = f.t - std::min(a.forecast_start, b.forecast_start);
          m.forecast_part_a = f.closest.part_a;
          m.forecast_part_b = f.closest.part_b;
          m.forecast_level = static_cast<uint8_t>(
              clearanceLevel(f.closest.distance, site_.warn_distance, site_.error_distance));
        }
        clearance_pub_.publish(m);

        char text[160];
        std::snprintf(text, sizeof text, "%.2f m between %s's %s and %s's %s", p.distance,
                      a.site.name.c_str(), p.part_a.c_str(), b.site.name.c_str(), p.part_b.c_str());
        d.level = level == ClearanceLevel::kError  ? diagnostic_msgs::DiagnosticStatus::ERROR
                  : level == ClearanceLevel::kWarn ? diagnostic_msgs::DiagnosticStatus::WARN
                                                   : diagnostic_msgs::DiagnosticStatus::OK;
        d.message = text;
        if (f.valid && m.forecast_level > m.level) {  // a predicted approach raises the level
          char predicted[200];
          std::snprintf(predicted, sizeof predicted,
                        "; predicted %.2f m between %s's %s and %s's %s in %.0f s",
                        f.closest.distance, a.site.name.c_str(), f.closest.part_a.c_str(),
                        b.site.name.c_str(), f.closest.part_b.c_str(), m.forecast_time_ahead);
          d.message += predicted;
          d.level = m.forecast_level == 2 ? diagnostic_msgs::DiagnosticStatus::ERROR
                                          : diagnostic_msgs::DiagnosticStatus::WARN;
        }
        auto kv = [&](const std::string& k, double v) {
          diagnostic_msgs::KeyValue x;
          x.key = k;
          x.value = std::to_string(v);
          d.values.push_back(x);
        };
        kv("min_distance_m", p.distance);
        kv("warn_distance_m", site_.warn_distance);
        kv("error_distance_m", site_.error_distance);
        kv("stamp_gap_s", m.stamp_gap);
        if (f.valid) {
          kv("forecast_min_distance_m", f.closest.distance);
          kv("forecast_min_in_s", m.forecast_time_ahead);
        }
        diag.status.push_back(d);

        visualization_msgs::Marker line;
        line.header.frame_id = "world";
        line.header.stamp = m.header.stamp;
        line.ns = "clearance";
        line.id = id++;
        line.type = visualization_msgs::Marker::LINE_LIST;
        line.pose.orientation.w = 1.0;
        line.scale.x = 0.3;
        line.color.a = 1.0f;
        line.color.r = level == ClearanceLevel::kOk ? 0.1f : 1.0f;
        line.color.g = level == ClearanceLevel::kError ? 0.1f : 0.8f;
        line.color.b = 0.1f;
        line.points = {m.point_a, m.point_b};
        markers.markers.push_back(line);
        visualization_msgs::Marker label = line;
        label.id = id++;
        label.type = visualization_msgs::Marker::TEXT_VIEW_FACING;
        label.points.clear();
        label.pose.position = point(0.5 * (p.point_a + p.point_b) + Eigen::Vector3d(0, 0, 3));
        label.scale.z = 4.0;
        label.text = text;
        markers.markers.push_back(label);
      }
    diag_pub_.publish(diag);
    marker_pub_.publish(markers);
  }

  ros::NodeHandle nh_;
  SiteDescription site_;
  std::vector<std::unique_ptr<MonitoredCrane>> cranes_;
  ros::Publisher clearance_pub_, marker_pub_, diag_pub_;
  ros::WallTimer timer_;
};

}  // namespace
}  // namespace crane_twin

int main(int argc, char** argv) {
  ros::init(argc, argv, "site_monitor");
  ros::NodeHandle nh, pnh("~");
  try {
    std::string file;
    if (!pnh.getParam("site", file) || file.empty()) {
      throw crane_twin::InputError("parameter '" + pnh.resolveName("site") +
                                   "' is required (a site file, docs/site.md)");
    }
    crane_twin::SiteMonitor monitor(nh, crane_twin::loadSiteDescription(file));
    ros::spin();
  } catch (const crane_twin::InputError& e) {
    ROS_FATAL("site_monitor: %s", e.what());
    return 2;
  } catch (const std::exception& e) {
    ROS_FATAL("site_monitor: %s", e.what());
    return 1;
  }
  return 0;
}
