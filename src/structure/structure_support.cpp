#include "crane_twin/structure/structure_support.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace crane_twin {

namespace {

// 3 x N rows with row_d . u = sum_i w_i u_{node_i, d} (translations of the weighted nodes).
Eigen::Matrix<double, 3, Eigen::Dynamic> pointRows(const TowerCraneStructure& s,
                                                   const std::vector<NodeLoad>& at) {
  Eigen::Matrix<double, 3, Eigen::Dynamic> P = Eigen::MatrixXd::Zero(3, s.free_dofs);
  for (const auto& w : at)
    for (int d = 0; d < 3; ++d) {
      const int e = s.dof_equation[6 * w.node + d];
      if (e >= 0) P(d, e) += w.weight;
    }
  return P;
}

}  // namespace

Eigen::Matrix3d slewRotation(double theta) {
  return Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

// Trolley point X_p(s): the rail interpolation weights at radius s.
Eigen::Vector3d trolleyPoint(const TowerCraneStructure& s, double radius) {
  Eigen::Vector3d X = Eigen::Vector3d::Zero();
  for (const auto& w : s.trolleyWeights(radius)) X += w.weight * s.nodes[w.node];
  return X;
}

StructureSupportBase::StructureSupportBase(const TowerCraneStructure& s, double trolley_radius,
                                           double slew_angle, const Eigen::MatrixXd* modes)
    : structure_(s) {
  if (modes) modes_ = *modes;
  std::vector<NodeLoad> tip;
  for (int n : s.jib_tip_nodes) tip.push_back({n, 1.0 / s.jib_tip_nodes.size()});
  const auto Pc = pointRows(s, {{s.cab_node, 1.0}}), Pj = pointRows(s, tip);
  cab_ = modes ? Eigen::Matrix<double, 3, Eigen::Dynamic>(Pc * *modes) : Pc;
  tip_ = modes ? Eigen::Matrix<double, 3, Eigen::Dynamic>(Pj * *modes) : Pj;
  setPose(slew_angle, trolley_radius);
}

// r_p = R(theta) (X_p(s) + B(s) T z): D = R B T.
void StructureSupportBase::setPose(double theta, double radius) {
  // (a function of theta and the radius alone: the same pose leaves r_0, D and the version)
  if (pose_version_ > 0 && theta == pose_theta_ && radius == pose_radius_) return;
  pose_theta_ = theta;
  pose_radius_ = radius;
  const std::vector<NodeLoad> w = structure_.trolleyWeights(radius);
  const Eigen::Matrix3d R = slewRotation(theta);
  r0_ = R * trolleyPoint(structure_, radius);
  if (modes_.size() > 0) {
    Eigen::Matrix<double, 3, Eigen::Dynamic> BT = Eigen::MatrixXd::Zero(3, modes_.cols());
    for (const auto& x : w)
      for (int d = 0; d < 3; ++d) {
        const int e = structure_.dof_equation[6 * x.node + d];
        if (e >= 0) BT.row(d) += x.weight * modes_.row(e);
      }
    D_ = R * BT;
  } else {
    D_ = R * pointRows(structure_, w);
  }
  ++pose_version_;
}

const Eigen::Matrix3d* StructureSupportBase::keptCompliance(double a, double c, double k) const {
  const KeptCompliance& g = kept_compliance_;
  const bool kept = a == g.a && c == g.c && k == g.k && g.pose_version == pose_version_;
  return kept ? &g.G : nullptr;
}

const Eigen::Matrix3d& StructureSupportBase::keepCompliance(double a, double c, double k,
                                                            const Eigen::Matrix3d& G) {
  kept_compliance_ = {a, c, k, pose_version_, G};
  return kept_compliance_.G;
}

void slewingFields(const TowerCraneStructure& s, Eigen::VectorXd& r_theta, Eigen::VectorXd& c) {
  std::vector<bool> turns(s.nodes.size(), false);
  for (const StructureMember& m : s.members) {
    if (m.group == "mast") continue;
    turns[m.node1] = turns[m.node2] = true;
  }
  r_theta = Eigen::VectorXd::Zero(s.free_dofs);
  c = Eigen::VectorXd::Zero(s.free_dofs);
  for (std::size_t n = 0; n < s.nodes.size(); ++n) {
    if (!turns[n]) continue;
    const Eigen::Vector3d& X = s.nodes[n];
    const double rt[6] = {-X.y(), X.x(), 0.0, 0.0, 0.0, 1.0};
    const double cf[6] = {-X.x(), -X.y(), 0.0, 0.0, 0.0, 0.0};
    for (int d = 0; d < 6; ++d) {
      const int e = s.dof_equation[6 * n + d];
      if (e < 0) continue;
      r_theta(e) = rt[d];
      c(e) = cf[d];
    }
  }
}

void StructureSupportBase::enableSlewingLoads() {
  Eigen::VectorXd r, c;
  slewingFields(structure_, r, c);
  const Eigen::VectorXd Mr = structure_.M * r, Mc = structure_.M * c;
  euler_ = modes_.size() > 0 ? Eigen::VectorXd(modes_.transpose() * Mr) : Mr;
  centrifugal_ = modes_.size() > 0 ? Eigen::VectorXd(modes_.transpose() * Mc) : Mc;
}

void StructureSupportBase::setSlewMotion(double rate, double acceleration) {
  slew_rate_ = rate;
  slew_acceleration_ = acceleration;
}

double slewingInertia(const TowerCraneStructure& s, double point_mass, double radius) {
  Eigen::VectorXd r, c;
  slewingFields(s, r, c);
  return r.dot(s.M * r) + point_mass * radius * radius;
}

void StructureSupportBase::setExternalLoad(const Eigen::VectorXd& f) {
  if (f.size() == 0) {
    external_.resize(0);
    return;
  }
  if (f.size() != structure_.free_dofs || !f.allFinite()) {
    throw std::invalid_argument("external structure load: needs " +
                                std::to_string(structure_.free_dofs) + " finite values");
  }
  external_ = modes_.size() > 0 ? Eigen::VectorXd(modes_.transpose() * f) : f;
}

void StructureSupportBase::setExternalLoadPatterns(const Eigen::SparseMatrix<double>& P) {
  if (P.cols() > 0 && P.rows() != structure_.free_dofs) {
    throw std::invalid_argument("external load patterns: need " +
                                std::to_string(structure_.free_dofs) + " rows");
  }
  if (modes_.size() > 0) {
    modal_patterns_ = P.cols() > 0 ? Eigen::MatrixXd(P.transpose() * modes_).transpose()
                                   : Eigen::MatrixXd(size(), 0);
    patterns_.resize(0, 0);
  } else {
    patterns_ = P;
    modal_patterns_.resize(0, 0);
  }
  if (P.cols() == 0) external_.resize(0);
}

void StructureSupportBase::setExternalLoadWeights(const Eigen::VectorXd& w) {
  const Eigen::Index columns = modes_.size() > 0 ? modal_patterns_.cols() : patterns_.cols();
  if (w.size() != columns || !w.allFinite()) {
    throw std::invalid_argument("external load weights: need " + std::to_string(columns) +
                                " finite values");
  }
  external_ =
      modes_.size() > 0 ? Eigen::VectorXd(modal_patterns_ * w) : Eigen::VectorXd(patterns_ * w);
}

// T^T f = -(theta'' T^T M r_theta + theta'^2 T^T M c).
Eigen::VectorXd StructureSupportBase::slewingLoad() const {
  if (euler_.size() == 0) return Eigen::VectorXd::Zero(size());
  return -(slew_acceleration_ * euler_ + slew_rate_ * slew_rate_ * centrifugal_);
}

RigidTrolleySupport::RigidTrolleySupport(const TowerCraneStructure& s, double trolley_radius,
                                         double slew_angle)
    : FixedAnchor(Eigen::Vector3d::Zero()), structure_(s) {
  setPose(slew_angle, trolley_radius);
}

void RigidTrolleySupport::setPose(double theta, double radius) {
  p_ = slewRotation(theta) * trolleyPoint(structure_, radius);
}

Eigen::VectorXd RigidTrolleySupport::structureDisplacement(const Eigen::VectorXd&) const {
  return Eigen::VectorXd::Zero(structure_.free_dofs);
}

ModalStructureSupport::ModalStructureSupport(const TowerCraneStructure& s, const ModalBasis& b,
                                             double zeta, double trolley_radius, double slew_angle)
    : StructureSupportBase(s, trolley_radius, slew_angle, &b.phi),
      omega2_(b.omega2),
      damping_(2.0 * zeta * b.omega2.cwiseSqrt()),
      diagonal_(Eigen::VectorXd::Ones(b.omega2.size())) {
  if (!(zeta >= 0.0)) throw std::invalid_argument("modal damping ratio must be >= 0");
}

// z'' + 2 zeta Omega z' + Omega^2 z (mass-normalised modes).
Eigen::VectorXd ModalStructureSupport::internalForce(const Eigen::VectorXd& z,
                                                     const Eigen::VectorXd& zd,
                                                     const Eigen::VectorXd& zdd) const {
  Eigen::VectorXd f = zdd + damping_.cwiseProduct(zd) + omega2_.cwiseProduct(z);
  if (slewingLoads()) f -= slewingLoad();
  if (external_.size() > 0) f -= external_scale_ * external_;
  return f;
}

// A_z = a I + c 2 zeta Omega + k Omega^2 (diagonal), G = D A_z^-1 D^T (kept: keptCompliance).
Eigen::Matrix3d ModalStructureSupport::setIterationWeights(double a, double c, double k) {
  if (const Eigen::Matrix3d* G = keptCompliance(a, c, k)) return *G;
  diagonal_ = Eigen::VectorXd::Constant(omega2_.size(), a) + c * damping_ + k * omega2_;
  return keepCompliance(a, c, k, D_ * diagonal_.cwiseInverse().asDiagonal() * D_.transpose());
}

double ModalStructureSupport::energy(const Eigen::VectorXd& z, const Eigen::VectorXd& zd) const {
  return 0.5 * zd.squaredNorm() + 0.5 * z.dot(omega2_.cwiseProduct(z));
}

FullStructureSupport::FullStructureSupport(const TowerCraneStructure& s, double zeta,
                                           double omega_low, double omega_high,
                                           double trolley_radius, double slew_angle)
    : StructureSupportBase(s, trolley_radius, slew_angle, nullptr), M_(s.M), K_(s.K) {
  if (!(zeta >= 0.0) || !(omega_low > 0.0) || !(omega_high > omega_low)) {
    throw std::invalid_argument("Rayleigh damping needs zeta >= 0 and 0 < omega_low < omega_high");
  }
  // zeta(w) = alpha / (2 w) + beta w / 2, equal to zeta at both frequencies.
  alpha_ = 2.0 * zeta * omega_low * omega_high / (omega_low + omega_high);
  beta_ = 2.0 * zeta / (omega_low + omega_high);
  A_ = M_ + K_;  // union pattern; values rewritten per weight set
  llt_.analyzePattern(A_);
}

Eigen::VectorXd FullStructureSupport::internalForce(const Eigen::VectorXd& z,
                                                    const Eigen::VectorXd& zd,
                                                    const Eigen::VectorXd& zdd) const {
  Eigen::VectorXd f = M_ * (zdd + alpha_ * zd) + K_ * (z + beta_ * zd);
  if (slewingLoads()) f -= slewingLoad();
  if (external_.size() > 0) f -= external_scale_ * external_;
  return f;
}

// A_z = a M + c (alpha M + beta K) + k K, G = D A_z^-1 D^T (kept: keptCompliance; A_z's
// factorisation kept while its two weights are).
Eigen::Matrix3d FullStructureSupport::setIterationWeights(double a, double c, double k) {
  if (const Eigen::Matrix3d* G = keptCompliance(a, c, k)) return *G;
  const double wm = a + c * alpha_, wk = k + c * beta_;
  if (!(wm == weight_m_ && wk == weight_k_)) {
    A_ = wm * M_ + wk * K_;
    llt_.factorize(A_);
    if (llt_.info() != Eigen::Success) {
      throw std::runtime_error("structure iteration matrix factorisation failed");
    }
    weight_m_ = wm;
    weight_k_ = wk;
  }
  X_ = llt_.solve(Eigen::MatrixXd(D_.transpose()));
  return keepCompliance(a, c, k, D_ * X_);
}

double FullStructureSupport::energy(const Eigen::VectorXd& z, const Eigen::VectorXd& zd) const {
  return 0.5 * zd.dot(M_ * zd) + 0.5 * z.dot(K_ * z);
}

}  // namespace crane_twin
