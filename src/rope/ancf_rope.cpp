#include "crane_twin/rope/ancf_rope.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace crane_twin {

AncfRope::AncfRope(int elements, double length, double mass_per_length, double axial_stiffness,
                   double bending_stiffness, double end_mass, const Eigen::Vector3d& gravity,
                   double top_mass)
    : elements_(elements), end_mass_(end_mass), top_mass_(top_mass),
      rope_axial_stiffness_(axial_stiffness), gravity_(gravity) {
  if (elements < 1) throw std::invalid_argument("rope needs at least one element");
  if (!(length > 0.0)) throw std::invalid_argument("rope length must be positive");
  element_.length = length / elements;
  element_.mass_per_length = mass_per_length;
  element_.axial_stiffness = axial_stiffness;
  element_.bending_stiffness = bending_stiffness;
  assembleMass();
}

void AncfRope::setLength(double length) {
  if (!(length > 0.0)) throw std::invalid_argument("rope length must be positive");
  element_.length = length / elements_;
  element_.axial_stiffness = axialStiffnessAt(length);
  // In place (hoisting changes the length every step): the element mass int rho A S^T S dx
  // scales with l^(1 + s_i + s_j), s = 1 on slope coordinates (S2, S4 carry a factor l); the
  // point masses stay.
  const double l = element_.length;
  const double powers[3] = {l, l * l, l * l * l};
  double* v = M_.valuePtr();
  for (Eigen::Index i = 0; i < M_.nonZeros(); ++i)
    v[i] = unit_mass_[i] * powers[mass_exponent_[i]] + point_mass_[i];
  updateGravityForce();
}

void AncfRope::setReevingLength(double equivalent_length) {
  if (!(std::isfinite(equivalent_length) && equivalent_length >= 0.0)) {
    throw std::invalid_argument("reeving length must be finite and >= 0");
  }
  reeving_length_ = equivalent_length;
  element_.axial_stiffness = axialStiffnessAt(length());
}

double AncfRope::minNodalStrain(const Eigen::VectorXd& q) {
  double least = std::numeric_limits<double>::infinity();
  for (int j = 0; 6 * j < q.size(); ++j) least = std::min(least, q.segment<3>(6 * j + 3).norm() - 1.0);
  return least;
}

double AncfRope::kineticEnergyRelativeToTop(const Eigen::VectorXd& v) const {
  Eigen::VectorXd w = v;
  for (int j = 0; j < nodes(); ++j) w.segment<3>(6 * j) -= v.head<3>();
  return 0.5 * w.dot(M_ * w);
}

void AncfRope::rescaleSlopes(Eigen::VectorXd& x, double from, double to) {
  const double f = from / to;
  for (int j = 0; 6 * j < x.size(); ++j) x.segment<3>(6 * j + 3) *= f;
}

void AncfRope::assembleMass() {
  const Matrix12 Me = ancfMassMatrix(element_);
  SparseAssembler A(dofs());
  std::vector<int> eq(12);
  for (int k = 0; k < elements_; ++k) {
    for (int i = 0; i < 12; ++i) eq[i] = 6 * k + i;
    A.add(Me, eq);
  }
  for (int d = 0; d < 3; ++d) {
    A.addEntry(6 * elements_ + d, 6 * elements_ + d, end_mass_);
    if (top_mass_ != 0.0) A.addEntry(d, d, top_mass_);
  }
  M_ = A.build();
  M_.makeCompressed();
  // The length scaling of every entry (setLength): value = unit l^(1 + s_i + s_j) + point.
  const double l = element_.length;
  unit_mass_.resize(M_.nonZeros());
  point_mass_.assign(M_.nonZeros(), 0.0);
  mass_exponent_.resize(M_.nonZeros());
  for (int c = 0; c < M_.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(M_, c); it; ++it) {
      const Eigen::Index i = &it.valueRef() - M_.valuePtr();
      const int e = ((it.row() % 6) >= 3) + ((it.col() % 6) >= 3);
      double point = 0.0;
      if (it.row() == it.col() && it.row() % 6 < 3) {
        if (it.row() >= 6 * elements_) point += end_mass_;
        if (it.row() < 3) point += top_mass_;
      }
      point_mass_[i] = point;
      mass_exponent_[i] = e;
      unit_mass_[i] = (it.value() - point) / std::pow(l, 1 + e);
    }
  updateGravityForce();
}

void AncfRope::updateGravityForce() {
  // F_g = M * (rigid translation field g): exact consistent gravity, incl. the end mass.
  Eigen::VectorXd g = Eigen::VectorXd::Zero(dofs());
  for (int j = 0; j < nodes(); ++j) g.segment<3>(6 * j) = gravity_;
  Fg_ = M_ * g;
  if (ext_per_length_.isZero() && ext_end_.isZero()) return;
  const double l = element_.length;
  for (int k = 0; k < elements_; ++k) {
    Fg_.segment<3>(6 * k) += 0.5 * l * ext_per_length_;
    Fg_.segment<3>(6 * k + 3) += l * l / 12.0 * ext_per_length_;
    Fg_.segment<3>(6 * k + 6) += 0.5 * l * ext_per_length_;
    Fg_.segment<3>(6 * k + 9) -= l * l / 12.0 * ext_per_length_;
  }
  Fg_.segment<3>(6 * elements_) += ext_end_;
}

void AncfRope::setExternalLoad(const Eigen::Vector3d& per_length, const Eigen::Vector3d& end_force) {
  if (!per_length.allFinite() || !end_force.allFinite()) {
    throw std::invalid_argument("rope external load must be finite");
  }
  ext_per_length_ = per_length;
  ext_end_ = end_force;
  updateGravityForce();
}

void AncfRope::elasticForce(const Eigen::VectorXd& q, Eigen::VectorXd& Q,
                            std::vector<Eigen::Triplet<double>>* tangent) const {
  Q.setZero(dofs());
  Vector12 Qe;
  Matrix12 Ke;
  for (int k = 0; k < elements_; ++k) {
    const Vector12 e = q.segment<12>(6 * k);
    ancfElasticForce(element_, e, Qe, tangent ? &Ke : nullptr);
    Q.segment<12>(6 * k) += Qe;
    if (tangent) {
      const int o = 6 * k;
      for (int j = 0; j < 12; ++j)
        for (int i = 0; i < 12; ++i) tangent->emplace_back(o + i, o + j, Ke(i, j));
    }
  }
}

SparseMatrix AncfRope::tangentStiffness(const Eigen::VectorXd& q, Eigen::VectorXd* force) const {
  Eigen::VectorXd Q;
  std::vector<Eigen::Triplet<double>> t;
  elasticForce(q, Q, &t);
  SparseMatrix K(dofs(), dofs());
  K.setFromTriplets(t.begin(), t.end());
  if (force) *force = std::move(Q);
  return K;
}

double AncfRope::elasticEnergy(const Eigen::VectorXd& q) const {
  double U = 0.0;
  for (int k = 0; k < elements_; ++k) U += ancfElasticEnergy(element_, q.segment<12>(6 * k));
  return U;
}

Eigen::VectorXd AncfRope::stretchedStraight(const Eigen::Vector3d& top, const Eigen::Vector3d& d,
                                            double end_force, double force_per_length) const {
  const double l = element_.length, L = length(), EA = element_.axial_stiffness;
  Eigen::VectorXd q(dofs());
  Eigen::Vector3d r = top;
  for (int j = 0; j < nodes(); ++j) {
    const double T = end_force + force_per_length * (L - j * l);
    q.segment<3>(6 * j) = r;
    q.segment<3>(6 * j + 3) = (1.0 + T / EA) * d;
    const double Tmid = end_force + force_per_length * (L - (j + 0.5) * l);
    r += (1.0 + Tmid / EA) * l * d;
  }
  return q;
}

Eigen::VectorXd AncfRope::straight(const Eigen::Vector3d& top, const Eigen::Vector3d& d) const {
  Eigen::VectorXd q(dofs());
  for (int j = 0; j < nodes(); ++j) {
    q.segment<3>(6 * j) = top + element_.length * j * d;
    q.segment<3>(6 * j + 3) = d;
  }
  return q;
}

// r(xi) = S(xi) e per element (docs/model.md), xi = k / per_element.
std::vector<Eigen::Vector3d> sampleRopeCurve(const Eigen::VectorXd& q, double l,
                                             int per_element) {
  if (per_element < 1) throw std::invalid_argument("rope samples per element must be >= 1");
  const int elements = static_cast<int>(q.size()) / 6 - 1;
  std::vector<Eigen::Vector3d> points;
  points.reserve(static_cast<size_t>(elements * per_element + 1));
  for (int k = 0; k < elements; ++k) {
    const Vector12 e = q.segment<12>(6 * k);
    for (int i = 0; i < per_element; ++i)
      points.push_back(ancfPosition(e, static_cast<double>(i) / per_element, l));
  }
  points.push_back(q.segment<3>(6 * elements));
  return points;
}

}  // namespace crane_twin
