// Normal stress at the structure's fatigue hot spots (docs/fatigue.md). A hot spot is a
// member's end section (HotSpotSpec: the member along `along` with an end nearest `point`) and
// a point of its tube's outer fibre, (0, y, z) in the member's local axes, toward `fibre`. With
// the section resultants on the face of outward normal +x (N, V_y, V_z, T, M_y, M_z) from the
// element's end forces K_e T u_e (linear theory, the same Timoshenko element as K),
//
//     sigma = N / A + M_y z / I_y - M_z y / I_z    [Pa, tension positive],
//
// a linear function of the free-DOF displacement u: each hot spot is a row s, sigma = s u.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "crane_twin/io/crane_description.hpp"
#include "crane_twin/structure/tower_crane_structure.hpp"

namespace crane_twin {

struct HotSpotRow {
  std::string name;
  double detail_category = 0.0;  ///< [MPa]
  int member = -1;               ///< index into TowerCraneStructure::members
  int node = -1;                 ///< the end whose section it is
  /// sigma = sum coefficient * u(equation) [Pa per m or rad].
  std::vector<std::pair<int, double>> coefficients;
  /// sigma for a free-DOF displacement u [Pa].
  double stress(const Eigen::VectorXd& u) const;
};

/// The rows of the crane's hot spots on structure `s`. Throws InputError naming the hot spot
/// when no member runs along its `along` (within 8 deg).
std::vector<HotSpotRow> hotSpotRows(const TowerCraneStructure& s,
                                    const std::vector<HotSpotSpec>& spots);

}  // namespace crane_twin
