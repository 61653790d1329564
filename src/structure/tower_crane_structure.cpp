#include "crane_twin/structure/tower_crane_structure.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <numeric>
#include <stdexcept>

#include "crane_twin/io/config_reader.hpp"

namespace crane_twin {

int TowerCraneStructure::addNode(const Eigen::Vector3d& p) {
  // Reuse a coincident node so that booms and the slewing unit share their joints.
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if ((nodes[i] - p).norm() < 1e-6) return static_cast<int>(i);
  }
  nodes.push_back(p);
  clamped.push_back(false);
  return static_cast<int>(nodes.size()) - 1;
}

void TowerCraneStructure::addMember(int a, int b, int section, const std::string& group) {
  StructureMember m;
  m.node1 = a;
  m.node2 = b;
  m.section = section;
  m.group = group;
  const Eigen::Vector3d axis = (nodes[b] - nodes[a]).normalized();
  // Tubes are axisymmetric; the orientation vector only has to be off-axis.
  m.orientation = std::abs(axis.z()) > 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitZ();
  members.push_back(m);
}

void TowerCraneStructure::addBoom(const CraneDescription& c, const LatticeBoomSpec& b,
                                  double direction, const std::string& group, int first_section) {
  // Sections: top chord, bottom chord, diagonal, horizontal.
  const int sTop = first_section, sBot = first_section + 1, sDia = first_section + 2,
            sHor = first_section + 3;
  const int panels = std::max(1, static_cast<int>(std::lround(b.length / b.panel)));
  const double dx = b.length / panels;
  const double x0 = c.mast_width / 2.0, z = c.jibRailHeight();
  std::vector<int> L(panels + 1), R(panels + 1), T(panels + 1);
  for (int j = 0; j <= panels; ++j) {
    const double x = direction * (x0 + j * dx);
    L[j] = addNode({x, b.width / 2.0, z});
    R[j] = addNode({x, -b.width / 2.0, z});
    T[j] = addNode({x, 0.0, z + b.height});
    // The root frame carries the boom's bending moment into the slewing unit: tower-head
    // members there, lattice horizontals elsewhere.
    const int sFrame = (j == 0) ? 3 : sHor;
    addMember(L[j], R[j], sFrame, group);
    addMember(L[j], T[j], sFrame, group);
    addMember(R[j], T[j], sFrame, group);
    if (direction > 0) rail.push_back({x, L[j], R[j]});
  }
  auto chord = [&](int a, int bnode, int section) {
    int prev = a;
    for (int k = 1; k < b.chord_segments; ++k) {
      const double t = static_cast<double>(k) / b.chord_segments;
      const int mid = addNode((1.0 - t) * nodes[a] + t * nodes[bnode]);
      addMember(prev, mid, section, group);
      prev = mid;
    }
    addMember(prev, bnode, section, group);
  };
  for (int j = 0; j < panels; ++j) {
    chord(L[j], L[j + 1], sBot);
    chord(R[j], R[j + 1], sBot);
    chord(T[j], T[j + 1], sTop);
    const bool even = (j % 2 == 0);
    addMember(even ? L[j] : T[j], even ? T[j + 1] : L[j + 1], sDia, group);
    addMember(even ? R[j] : T[j], even ? T[j + 1] : R[j + 1], sDia, group);
    addMember(even ? L[j] : R[j], even ? R[j + 1] : L[j + 1], sDia, group);
  }
  if (direction > 0) {
    jib_tip_nodes = {L[panels], R[panels]};
  }
}

TowerCraneStructure TowerCraneStructure::build(const CraneDescription& c) {
  TowerCraneStructure s;
  // Sections: 0 mast chord, 1 mast diagonal, 2 mast horizontal, 3 slewing member,
  // 4..7 jib (top, bottom, diagonal, horizontal), 8..11 counter-jib.
  for (const TubeSpec* t :
       {&c.mast_chord, &c.mast_diagonal, &c.mast_horizontal, &c.slewing_member, &c.jib.top_chord,
        &c.jib.bottom_chord, &c.jib.diagonal, &c.jib.horizontal, &c.counter_jib.top_chord,
        &c.counter_jib.bottom_chord, &c.counter_jib.diagonal, &c.counter_jib.horizontal}) {
    s.sections.push_back(tubeSection(c, *t));
  }

  // Mast: corners CCW from (+,+); chevron diagonals meet at mid-panel chord nodes.
  const int levels = std::max(1, static_cast<int>(std::lround(c.mast_height / c.mast_panel)));
  const double dz = c.mast_height / levels, hw = c.mast_width / 2.0;
  const double cx[4] = {hw, -hw, -hw, hw}, cy[4] = {hw, hw, -hw, -hw};
  std::vector<std::array<int, 4>> corner(levels + 1), mid(levels);
  for (int k = 0; k <= levels; ++k) {
    for (int i = 0; i < 4; ++i) corner[k][i] = s.addNode({cx[i], cy[i], k * dz});
    if (k > 0) {
      for (int i = 0; i < 4; ++i) s.addMember(corner[k][i], corner[k][(i + 1) % 4], 2, "mast");
    }
  }
  for (int i = 0; i < 4; ++i) s.clamped[corner[0][i]] = true;
  for (int k = 0; k < levels; ++k) {
    for (int i = 0; i < 4; ++i) mid[k][i] = s.addNode({cx[i], cy[i], (k + 0.5) * dz});
    for (int i = 0; i < 4; ++i) {
      s.addMember(corner[k][i], mid[k][i], 0, "mast");
      s.addMember(mid[k][i], corner[k + 1][i], 0, "mast");
      const int j = (i + 1) % 4;  // face between corner i and corner j
      s.addMember(corner[k][i], mid[k][j], 1, "mast");
      s.addMember(mid[k][j], corner[k + 1][i], 1, "mast");
    }
  }

  // Slewing unit: box from the mast top to the rail level.
  std::array<int, 4> top;
  for (int i = 0; i < 4; ++i) top[i] = s.addNode({cx[i], cy[i], c.jibRailHeight()});
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 1) % 4;
    s.addMember(corner[levels][i], top[i], 3, "slewing");
    s.addMember(top[i], top[j], 3, "slewing");
    s.addMember(corner[levels][i], top[j], 3, "slewing");
  }

  s.addBoom(c, c.jib, +1.0, "jib", 4);
  s.addBoom(c, c.counter_jib, -1.0, "counter_jib", 8);
  // Tower-head tie between the top chords' root nodes.
  const int jibTopRoot = s.addNode({hw, 0.0, c.jibRailHeight() + c.jib.height});
  const int cjTopRoot = s.addNode({-hw, 0.0, c.jibRailHeight() + c.counter_jib.height});
  s.addMember(jibTopRoot, cjTopRoot, 3, "slewing");
  // Tower-head A-frame: each top-chord root is braced down to the far slewing-unit corners.
  s.addMember(jibTopRoot, top[1], 3, "slewing");
  s.addMember(jibTopRoot, top[2], 3, "slewing");
  s.addMember(cjTopRoot, top[0], 3, "slewing");
  s.addMember(cjTopRoot, top[3], 3, "slewing");

  // Cab: one node tied to the two nearest slewing-unit top nodes.
  s.cab_node = s.addNode(c.cab_position);
  std::vector<int> order = {0, 1, 2, 3};
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return (s.nodes[top[a]] - c.cab_position).norm() < (s.nodes[top[b]] - c.cab_position).norm();
  });
  for (int q = 0; q < 2; ++q) {
    if ((s.nodes[top[order[q]]] - c.cab_position).norm() < 1e-3) {
      throw InputError(c.file +
                       ": key 'slewing_unit.cab_position': coincides with the slewing unit");
    }
    s.addMember(top[order[q]], s.cab_node, 3, "cab");
  }

  // Lumped masses shared by the nearest nodes.
  for (const auto& lm : c.lumped_masses) {
    std::vector<int> idx(s.nodes.size());
    std::iota(idx.begin(), idx.end(), 0);
    std::partial_sort(idx.begin(), idx.begin() + lm.nodes, idx.end(), [&](int a, int b) {
      return (s.nodes[a] - lm.position).norm() < (s.nodes[b] - lm.position).norm();
    });
    for (int q = 0; q < lm.nodes; ++q) s.lumped_masses.emplace_back(idx[q], lm.mass / lm.nodes);
    s.lumped_mass_ += lm.mass;
  }

  // Every node must hang together with the clamped base, or K is singular.
  std::vector<int> parent(s.nodes.size());
  std::iota(parent.begin(), parent.end(), 0);
  std::function<int(int)> findRoot = [&](int a) {
    return parent[a] == a ? a : parent[a] = findRoot(parent[a]);
  };
  for (const auto& m : s.members) parent[findRoot(m.node1)] = findRoot(m.node2);
  for (std::size_t n = 0; n < s.nodes.size(); ++n) {
    if (findRoot(static_cast<int>(n)) != findRoot(corner[0][0])) {
      throw InputError(c.file +
                       ": the structure is not connected (check that jib.width and "
                       "counter_jib.width equal mast.width, so the booms sit on the slewing unit)");
    }
  }

  // DOF numbering.
  s.dof_equation.assign(6 * s.nodes.size(), -1);
  for (std::size_t n = 0; n < s.nodes.size(); ++n) {
    if (s.clamped[n]) continue;
    for (int d = 0; d < 6; ++d) s.dof_equation[6 * n + d] = s.free_dofs++;
  }

  SparseAssembler KA(s.free_dofs), MA(s.free_dofs);
  std::vector<int> eq(12);
  for (const auto& m : s.members) {
    const BeamSection& sec = s.sections[m.section];
    const auto em = timoshenkoBeamGlobal(sec, s.nodes[m.node1], s.nodes[m.node2], m.orientation);
    for (int d = 0; d < 6; ++d) {
      eq[d] = s.dof_equation[6 * m.node1 + d];
      eq[6 + d] = s.dof_equation[6 * m.node2 + d];
    }
    KA.add(em.K, eq);
    MA.add(em.M, eq);
    s.member_mass_ += sec.density * sec.area * (s.nodes[m.node2] - s.nodes[m.node1]).norm();
  }
  for (const auto& [node, mass] : s.lumped_masses) {
    for (int d = 0; d < 3; ++d) {
      const int e = s.dof_equation[6 * node + d];
      if (e >= 0) MA.addEntry(e, e, mass);
    }
  }
  s.K = KA.build();
  s.M = MA.build();
  s.rail_height = c.jibRailHeight();
  return s;
}

std::vector<NodeLoad> TowerCraneStructure::trolleyWeights(double radius) const {
  if (rail.size() < 2 || radius < rail.front().x - 1e-9 || radius > rail.back().x + 1e-9) {
    throw std::out_of_range("trolley radius " + std::to_string(radius) + " m is off the jib rail");
  }
  std::size_t j = 0;
  while (j + 2 < rail.size() && rail[j + 1].x < radius) ++j;
  const double t = std::clamp((radius - rail[j].x) / (rail[j + 1].x - rail[j].x), 0.0, 1.0);
  return {{rail[j].left, 0.5 * (1.0 - t)},
          {rail[j].right, 0.5 * (1.0 - t)},
          {rail[j + 1].left, 0.5 * t},
          {rail[j + 1].right, 0.5 * t}};
}

Eigen::VectorXd TowerCraneStructure::pointForce(const std::vector<NodeLoad>& at,
                                                const Eigen::Vector3d& f) const {
  Eigen::VectorXd F = Eigen::VectorXd::Zero(free_dofs);
  for (const auto& w : at) {
    for (int d = 0; d < 3; ++d) {
      const int e = dof_equation[6 * w.node + d];
      if (e >= 0) F(e) += w.weight * f(d);
    }
  }
  return F;
}

std::vector<int> TowerCraneStructure::groupNodes(const std::string& group) const {
  std::vector<bool> in(nodes.size(), false);
  for (const StructureMember& m : members)
    if (m.group == group) in[m.node1] = in[m.node2] = true;
  std::vector<int> out;
  for (std::size_t n = 0; n < in.size(); ++n)
    if (in[n]) out.push_back(static_cast<int>(n));
  return out;
}

Eigen::Vector3d TowerCraneStructure::nodeDisplacement(const Eigen::VectorXd& u, int node) const {
  Eigen::Vector3d d = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) {
    const int e = dof_equation[6 * node + k];
    if (e >= 0) d(k) = u(e);
  }
  return d;
}

}  // namespace crane_twin

#include <Eigen/CholmodSupport>

namespace crane_twin {

Eigen::VectorXd staticTrolleyLoadDisplacement(const TowerCraneStructure& s, double mass,
                                              double radius, double gravity) {
  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> solver(s.K);
  if (solver.info() != Eigen::Success) {
    throw std::runtime_error("structure stiffness factorisation failed (singular K?)");
  }
  const Eigen::VectorXd F =
      s.pointForce(s.trolleyWeights(radius), Eigen::Vector3d(0.0, 0.0, -mass * gravity));
  return solver.solve(F);
}

Eigen::Vector3d jibTipDisplacement(const TowerCraneStructure& s, const Eigen::VectorXd& u) {
  Eigen::Vector3d d = Eigen::Vector3d::Zero();
  for (int n : s.jib_tip_nodes) d += s.nodeDisplacement(u, n);
  return d / static_cast<double>(s.jib_tip_nodes.size());
}

double jibBendingTipDz(const TowerCraneStructure& s, const Eigen::VectorXd& u) {
  const auto& root = s.rail.front();
  double dzRoot = 0.0, thy = 0.0;
  for (int n : {root.left, root.right}) {
    dzRoot += 0.5 * s.nodeDisplacement(u, n).z();
    const int e = s.dof_equation[6 * n + 4];
    if (e >= 0) thy += 0.5 * u(e);
  }
  const double span = s.rail.back().x - root.x;
  return jibTipDisplacement(s, u).z() - (dzRoot - thy * span);
}

}  // namespace crane_twin
