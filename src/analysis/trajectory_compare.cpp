#include "crane_twin/analysis/trajectory_compare.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "crane_twin/io/config_reader.hpp"
#include "crane_twin/io/csv_columns.hpp"

namespace crane_twin {

Trajectory readTrajectory(const std::string& series_csv, const std::string& nodes_csv) {
  const auto rows = readCsvColumns(
      series_csv, {"t", "payload_x", "payload_y", "payload_z", "cab_dx", "cab_dy", "cab_dz",
                   "jib_tip_dx", "jib_tip_dy", "jib_tip_dz", "rope_length", "rope_top_tension"});
  Trajectory tr;
  for (const auto& r : rows) {
    // Rows are matched by time: a time that does not increase would pair the wrong rows.
    if (!tr.t.empty() && !(r[0] > tr.t.back())) {
      throw InputError(series_csv + ": line " + std::to_string(tr.t.size() + 2) +
                       ": t = " + shownNumber(r[0]) +
                       " s does not increase (the row before: " + shownNumber(tr.t.back()) + " s)");
    }
    tr.t.push_back(r[0]);
    tr.payload.emplace_back(r[1], r[2], r[3]);
    tr.cab.emplace_back(r[4], r[5], r[6]);
    tr.jib_tip.emplace_back(r[7], r[8], r[9]);
    tr.tension.push_back(r[11]);
  }
  tr.rope_length = rows.front()[10];
  if (nodes_csv.empty()) return tr;
  const auto nrows = readCsvColumns(nodes_csv, {"t", "node", "x", "y", "z"});
  std::map<long, std::vector<Eigen::Vector3d>> byTime;
  for (const auto& r : nrows) {
    auto& v = byTime[std::lround(r[0] * 1e9)];
    if (r[1] != static_cast<double>(v.size())) {
      throw InputError(nodes_csv + ": nodes at t = " + std::to_string(r[0]) +
                       " are not numbered 0, 1, 2, ... in order");
    }
    v.emplace_back(r[2], r[3], r[4]);
  }
  for (double t : tr.t) {
    const auto it = byTime.find(std::lround(t * 1e9));
    if (it == byTime.end()) {
      throw InputError(nodes_csv + ": no nodes at t = " + std::to_string(t) + " of " + series_csv);
    }
    tr.nodes.push_back(it->second);
  }
  return tr;
}

std::vector<double> arcFractions(const std::vector<Eigen::Vector3d>& nodes) {
  std::vector<double> s(nodes.size(), 0.0);
  for (std::size_t k = 1; k < nodes.size(); ++k) s[k] = s[k - 1] + (nodes[k] - nodes[k - 1]).norm();
  const double total = s.empty() ? 0.0 : s.back();
  for (std::size_t k = 0; k < s.size(); ++k) {
    s[k] = total > 0.0 ? s[k] / total
                       : static_cast<double>(k) /
                             static_cast<double>(std::max<std::size_t>(1, s.size() - 1));
  }
  return s;
}

std::vector<Eigen::Vector3d> resampleRopeAt(const std::vector<Eigen::Vector3d>& nodes,
                                            const std::vector<double>& fractions) {
  if (nodes.size() < 2) {
    throw InputError("a rope needs at least 2 nodes to compare, got " +
                     std::to_string(nodes.size()));
  }
  const std::vector<double> s = arcFractions(nodes);
  std::vector<Eigen::Vector3d> out;
  out.reserve(fractions.size());
  std::size_t k = 0;
  for (double f : fractions) {
    while (k + 2 < nodes.size() && s[k + 1] < f) ++k;
    const double span = s[k + 1] - s[k];
    const double w = span > 0.0 ? std::clamp((f - s[k]) / span, 0.0, 1.0) : 0.0;
    out.push_back((1.0 - w) * nodes[k] + w * nodes[k + 1]);
  }
  return out;
}

ErrorMetrics compareTrajectories(const Trajectory& a, const Trajectory& b,
                                 const TimeWindow& window) {
  const std::string window_text =
      "[" + std::to_string(window.from) + ", " + std::to_string(window.to) + "] s";
  if (std::isnan(window.from) || std::isnan(window.to) || window.to < window.from) {
    throw InputError("the comparison's time window " + window_text +
                     " ends before it begins or is not a number");
  }
  std::map<long, std::size_t> bIndex;
  for (std::size_t i = 0; i < b.t.size(); ++i) bIndex[std::lround(b.t[i] * 1e9)] = i;
  const bool withNodes = !a.nodes.empty() && !b.nodes.empty();
  ErrorMetrics m;
  double tension_scale = 0.0;
  if (withNodes) m.rope_rms_max = 0.0;
  for (std::size_t i = 0; i < a.t.size(); ++i) {
    const auto it = bIndex.find(std::lround(a.t[i] * 1e9));
    if (it == bIndex.end() || a.t[i] < window.from || a.t[i] > window.to) continue;
    const std::size_t j = it->second;
    ++m.common_times;
    const double ep = (a.payload[i] - b.payload[j]).norm();
    if (ep > m.payload_max || m.common_times == 1) {
      m.payload_max = ep;
      m.payload_max_at = a.t[i];
    }
    m.cab_max = std::max(m.cab_max, (a.cab[i] - b.cab[j]).norm());
    m.jib_tip_max = std::max(m.jib_tip_max, (a.jib_tip[i] - b.jib_tip[j]).norm());
    if (i < a.tension.size() && j < b.tension.size()) {
      m.tension_max = std::max(m.tension_max, std::abs(a.tension[i] - b.tension[j]));
      tension_scale = std::max(tension_scale, std::abs(b.tension[j]));
    }
    if (withNodes) {
      // The coarser chain at the finer one's arc-length fractions (header).
      const auto& na = a.nodes[i];
      const auto& nb = b.nodes[j];
      const auto ra = na.size() < nb.size() ? resampleRopeAt(na, arcFractions(nb)) : na;
      const auto rb = nb.size() < na.size() ? resampleRopeAt(nb, arcFractions(na)) : nb;
      const std::size_t n = ra.size();
      double s = 0.0;
      for (std::size_t k = 0; k < n; ++k) s += (ra[k] - rb[k]).squaredNorm();
      const double rms = std::sqrt(s / n);
      if (rms > m.rope_rms_max || m.common_times == 1) {
        m.rope_rms_max = rms;
        m.rope_rms_max_at = a.t[i];
      }
    }
  }
  if (m.common_times == 0) {
    const bool all = std::isinf(window.from) && std::isinf(window.to);
    throw InputError(all ? std::string("the two runs share no output time")
                         : "the two runs share no output time in " + window_text);
  }
  const double L = b.rope_length > 0.0 ? b.rope_length : a.rope_length;
  m.rope_length = L;
  m.payload_relative = L > 0.0 ? m.payload_max / L : 0.0;
  m.tension_relative = tension_scale > 0.0 ? m.tension_max / tension_scale : 0.0;
  return m;
}

}  // namespace crane_twin
