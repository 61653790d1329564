#include "crane_twin/structure/hot_spot_stress.hpp"

#include <cmath>
#include <limits>

#include "crane_twin/elements/timoshenko_beam_element.hpp"
#include "crane_twin/io/input_error.hpp"

namespace crane_twin {

double HotSpotRow::stress(const Eigen::VectorXd& u) const {
  double sigma = 0.0;
  for (const auto& [eq, c] : coefficients) sigma += c * u(eq);
  return sigma;
}

std::vector<HotSpotRow> hotSpotRows(const TowerCraneStructure& s,
                                    const std::vector<HotSpotSpec>& spots) {
  std::vector<HotSpotRow> rows;
  const double cos_max = std::cos(8.0 * 3.14159265358979323846 / 180.0);
  for (const HotSpotSpec& spot : spots) {
    HotSpotRow row;
    row.name = spot.name;
    row.detail_category = spot.detail_category;
    double best = std::numeric_limits<double>::infinity();
    const Eigen::Vector3d along = spot.along.normalized();
    for (std::size_t k = 0; k < s.members.size(); ++k) {
      const StructureMember& m = s.members[k];
      const Eigen::Vector3d axis = (s.nodes[m.node2] - s.nodes[m.node1]).normalized();
      if (std::abs(axis.dot(along)) < cos_max) continue;
      for (int node : {m.node1, m.node2}) {
        const double d = (s.nodes[node] - spot.point).norm();
        if (d < best) {
          best = d;
          row.member = static_cast<int>(k);
          row.node = node;
        }
      }
    }
    if (row.member < 0) {
      throw InputError("hot spot '" + spot.name + "': no member runs along 'along'");
    }
    const StructureMember& m = s.members[row.member];
    const BeamSection& sec = s.sections[m.section];
    const Eigen::Vector3d p1 = s.nodes[m.node1], p2 = s.nodes[m.node2];
    const Eigen::Matrix3d R = beamLocalAxes(p1, p2, m.orientation);  // rows: local axes
    // The fibre: the outer radius toward `fibre`, in the section's plane (local y, z).
    const Eigen::Vector3d f = R * spot.fibre;
    const Eigen::Vector2d yz =
        Eigen::Vector2d(f.y(), f.z()).normalized() * (0.5 * sec.outer_diameter);
    if (!(sec.outer_diameter > 0.0) || !yz.allFinite()) {
      throw InputError("hot spot '" + spot.name + "': the member has no tube section");
    }
    // Resultants on the +x face: the end forces at node 2, minus those at node 1.
    const bool end2 = row.node == m.node2;
    Eigen::Matrix<double, 6, 1> w;
    w << 1.0 / sec.area, 0.0, 0.0, 0.0, yz.y() / sec.Iy, -yz.x() / sec.Iz;
    if (!end2) w = -w;
    const Eigen::Matrix<double, 12, 12> Kl = timoshenkoBeamLocal(sec, (p2 - p1).norm()).K;
    Eigen::Matrix<double, 12, 12> T = Eigen::Matrix<double, 12, 12>::Zero();
    for (int b = 0; b < 4; ++b) T.block<3, 3>(3 * b, 3 * b) = R;
    const Eigen::Matrix<double, 1, 12> c = w.transpose() * Kl.middleRows<6>(end2 ? 6 : 0) * T;
    for (int j = 0; j < 12; ++j) {
      const int node = j < 6 ? m.node1 : m.node2;
      const int eq = s.dof_equation[6 * node + j % 6];
      if (eq >= 0 && c(j) != 0.0) row.coefficients.emplace_back(eq, c(j));
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace crane_twin
