#include "crane_twin/rope/ancf_rope.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace crane_twin {

AncfRope::AncfRope(int elements, double length, double mass_per_length, double axial_stiffness,
                   double bending_stiffness, double end_mass, const Eigen::Vector3d& gravity,
                   double top_mass)
    : elements_(elements),
      end_mass_(end_mass),
      top_mass_(top_mass),
      rope_axial_stiffness_(axial_stiffness),
      gravity_(gravity) {
  if (elements < 1) throw std::invalid_argument("rope needs at least one element");
  if (!(length > 0.0)) throw std::invalid_argument("rope length must be positive");
  element_.length = length / elements;
  element_.mass_per_length = mass_per_length;
  element_.axial_stiffness = axial_stiffness;
  element_.bending_stiffness = bending_stiffness;
  assembleMass();
}

std::uint64_t AncfRope::nextRevision() {
  static std::atomic<std::uint64_t> next{1};
  return next.fetch_add(1, std::memory_order_relaxed);
}

void AncfRope::setLength(double length) {
  if (!(length > 0.0)) throw std::invalid_argument("rope length must be positive");
  revision_ = nextRevision();
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
  revision_ = nextRevision();
}

double AncfRope::minNodalStrain(const Eigen::VectorXd& q) {
  double least = std::numeric_limits<double>::infinity();
  for (int j = 0; 6 * j + 6 <= q.size(); ++j)
    least = std::min(least, q.segment<3>(6 * j + 3).norm() - 1.0);
  return least;
}

double AncfRope::kineticEnergyRelativeToTop(const Eigen::VectorXd& v) const {
  Eigen::VectorXd w = v;
  for (int j = 0; j < nodes(); ++j) w.segment<3>(positionIndex(j)) -= v.head<3>();
  return 0.5 * w.dot(M_ * w);
}

AncfRope AncfRope::lumpedAtHook() const {
  double end = end_mass_;
  if (hasRigging()) end += hook_mass_ + rigging_->massPerLength() * rigging_->length();
  AncfRope r(elements_, length(), element_.mass_per_length, rope_axial_stiffness_,
             element_.bending_stiffness, end, gravity_, top_mass_);
  r.setReevingLength(reeving_length_);
  r.setTensionOnly(element_.tension_only);
  return r;
}

void AncfRope::rescaleSlopes(Eigen::VectorXd& x, double from, double to) {
  const double f = from / to;
  for (int j = 0; 6 * j < x.size(); ++j) x.segment<3>(6 * j + 3) *= f;
}

void AncfRope::rescaleHoistSlopes(Eigen::VectorXd& x, double from, double to) const {
  const double f = from / to;
  for (int j = 0; j <= elements_; ++j) x.segment<3>(6 * j + 3) *= f;
}

void AncfRope::assembleMass() {
  // Two parts on one pattern: the hoist rope's elements, whose entries scale with the element
  // length under hoisting (setLength), and what does not (point masses, the rigging bar).
  SparseAssembler hoist(dofs()), fixed(dofs());
  std::vector<int> eq(12);
  const Matrix12 Me = ancfMassMatrix(element_);
  for (int k = 0; k < elements_; ++k) {
    for (int i = 0; i < 12; ++i) eq[i] = 6 * k + i;
    hoist.add(Me, eq);
  }
  for (int d = 0; d < 3; ++d) {
    if (top_mass_ != 0.0) fixed.addEntry(d, d, top_mass_);
    // With a rigging the payload is the bar's end mass; the hook block sits on the hook node.
    if (hasRigging())
      fixed.addEntry(6 * elements_ + d, 6 * elements_ + d, hook_mass_);
    else
      fixed.addEntry(6 * elements_ + d, 6 * elements_ + d, end_mass_);
  }
  if (hasRigging()) {
    const std::array<int, 6> r = riggingDofs();
    fixed.add(rigging_->massMatrix(), std::vector<int>(r.begin(), r.end()));
  }
  const SparseMatrix Mh = hoist.build(), Mf = fixed.build();
  M_ = Mh + Mf;
  M_.makeCompressed();
  // The length scaling of every entry (setLength): value = unit l^(1 + s_i + s_j) + fixed.
  const double l = element_.length;
  unit_mass_.resize(M_.nonZeros());
  point_mass_.assign(M_.nonZeros(), 0.0);
  mass_exponent_.resize(M_.nonZeros());
  for (int c = 0; c < M_.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(M_, c); it; ++it) {
      const Eigen::Index i = &it.valueRef() - M_.valuePtr();
      // Hoist entries only scale; their rows and columns are the 6-per-node ones.
      const int e = ((it.row() % 6) >= 3) + ((it.col() % 6) >= 3);
      point_mass_[i] = Mf.coeff(it.row(), it.col());
      mass_exponent_[i] = e;
      unit_mass_[i] = Mh.coeff(it.row(), it.col()) / std::pow(l, 1 + e);
    }
  updateGravityForce();
}

void AncfRope::updateGravityForce() {
  // F_g = M * (rigid translation field g): exact consistent gravity, incl. the end mass.
  Eigen::VectorXd g = Eigen::VectorXd::Zero(dofs());
  for (int j = 0; j < nodes(); ++j) g.segment<3>(positionIndex(j)) = gravity_;
  Fg_ = M_ * g;
  if (ext_per_length_.isZero() && ext_end_.isZero()) return;
  const double l = element_.length;
  for (int k = 0; k < elements_; ++k) {
    Fg_.segment<3>(6 * k) += 0.5 * l * ext_per_length_;
    Fg_.segment<3>(6 * k + 3) += l * l / 12.0 * ext_per_length_;
    Fg_.segment<3>(6 * k + 6) += 0.5 * l * ext_per_length_;
    Fg_.segment<3>(6 * k + 9) -= l * l / 12.0 * ext_per_length_;
  }
  Fg_.segment<3>(positionIndex(nodes() - 1)) += ext_end_;
}

void AncfRope::setExternalLoad(const Eigen::Vector3d& per_length,
                               const Eigen::Vector3d& end_force) {
  if (!per_length.allFinite() || !end_force.allFinite()) {
    throw std::invalid_argument("rope external load must be finite");
  }
  ext_per_length_ = per_length;
  ext_end_ = end_force;
  updateGravityForce();
  revision_ = nextRevision();
}

void AncfRope::elasticForce(const Eigen::VectorXd& q, Eigen::VectorXd& Q,
                            std::vector<Eigen::Triplet<double>>* tangent) const {
  Q.setZero(dofs());
  Vector12 Qe;
  Matrix12 Ke;
  for (int k = 0; k < elements_; ++k) {
    ancfElasticForce(element_, q.segment<12>(6 * k), Qe, tangent ? &Ke : nullptr);
    Q.segment<12>(6 * k) += Qe;
    if (tangent) {
      const int o = 6 * k;
      for (int j = 0; j < 12; ++j)
        for (int i = 0; i < 12; ++i) tangent->emplace_back(o + i, o + j, Ke(i, j));
    }
  }
  if (!hasRigging()) return;
  const std::array<int, 6> r = riggingDofs();
  Vector6 qb, Qb;
  Matrix6 Kb;
  for (int i = 0; i < 6; ++i) qb(i) = q(r[i]);
  rigging_->elasticForce(qb, Qb, tangent ? &Kb : nullptr);
  for (int i = 0; i < 6; ++i) Q(r[i]) += Qb(i);
  if (tangent) {
    for (int j = 0; j < 6; ++j)
      for (int i = 0; i < 6; ++i) tangent->emplace_back(r[i], r[j], Kb(i, j));
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
  if (hasRigging()) {
    const int n = 6 * elements_;
    Vector6 qb;
    qb << q.segment<3>(n), q.tail<3>();
    U += rigging_->elasticEnergy(qb);
  }
  return U;
}

Eigen::VectorXd AncfRope::axialDampingForce(double c, const Eigen::VectorXd& q,
                                            const Eigen::VectorXd& v) const {
  Eigen::VectorXd Q = Eigen::VectorXd::Zero(dofs());
  if (c == 0.0) return Q;
  Vector12 Qe;
  for (int k = 0; k < elements_; ++k) {
    ancfAxialDampingForce(element_, c, q.segment<12>(6 * k), v.segment<12>(6 * k), Qe);
    Q.segment<12>(6 * k) += Qe;
  }
  if (hasRigging()) {
    const std::array<int, 6> r = riggingDofs();
    Vector6 qb, vb, Qb;
    for (int i = 0; i < 6; ++i) qb(i) = q(r[i]), vb(i) = v(r[i]);
    rigging_->dampingForce(c, qb, vb, Qb);
    for (int i = 0; i < 6; ++i) Q(r[i]) += Qb(i);
  }
  return Q;
}

double AncfRope::slackSwitchWorkError(const Eigen::VectorXd& q0, const Eigen::VectorXd& q1) const {
  if (!element_.tension_only) return 0.0;
  double err = 0.0;
  for (int k = 0; k < elements_; ++k) {
    err += ancfSlackSwitchWorkError(element_, q0.segment<12>(6 * k), q1.segment<12>(6 * k));
  }
  return err + riggingSwitchWorkError(q0, q1);
}

double AncfRope::slackSwitchWorkError(const Eigen::VectorXd& q0, const Eigen::VectorXd& q1,
                                      const Eigen::VectorXd& eps0,
                                      const Eigen::VectorXd& eps1) const {
  if (!element_.tension_only) return 0.0;
  const int g = element_.gauss_points;
  double err = 0.0;
  for (int k = 0; k < elements_; ++k)
    err += ancfSlackSwitchWorkError(element_, eps0.data() + g * k, eps1.data() + g * k);
  return err + riggingSwitchWorkError(q0, q1);
}

void AncfRope::axialStrains(const Eigen::VectorXd& q, Eigen::VectorXd& eps) const {
  const int g = element_.gauss_points;
  eps.resize(elements_ * g);
  for (int k = 0; k < elements_; ++k)
    ancfAxialStrains(element_, q.segment<12>(6 * k), eps.data() + g * k);
}

double AncfRope::riggingSwitchWorkError(const Eigen::VectorXd& q0,
                                        const Eigen::VectorXd& q1) const {
  double err = 0.0;
  if (hasRigging()) {
    const int n = 6 * elements_;
    Vector6 b0, b1;
    b0 << q0.segment<3>(n), q0.tail<3>();
    b1 << q1.segment<3>(n), q1.tail<3>();
    err += rigging_->slackSwitchWorkError(b0, b1);
  }
  return err;
}

Eigen::VectorXd AncfRope::stretchedStraight(const Eigen::Vector3d& top, const Eigen::Vector3d& d,
                                            double end_force, double force_per_length) const {
  const double l = element_.length, L = length(), EA = element_.axial_stiffness;
  // With a rigging: end_force acts at the payload; the rigging's tension grows by its own weight
  // and the hook block's adds at the junction (the field force_per_length / mu per kilogram).
  double hook_force = end_force;
  const double field =
      element_.mass_per_length > 0.0 ? force_per_length / element_.mass_per_length : 0.0;
  if (hasRigging())
    hook_force += field * (rigging_->massPerLength() * rigging_->length() + hook_mass_);
  Eigen::VectorXd q(dofs());
  Eigen::Vector3d r = top;
  for (int j = 0; j <= elements_; ++j) {
    const double T = hook_force + force_per_length * (L - j * l);
    q.segment<3>(6 * j) = r;
    q.segment<3>(6 * j + 3) = (1.0 + T / EA) * d;
    const double Tmid = hook_force + force_per_length * (L - (j + 0.5) * l);
    r += (1.0 + Tmid / EA) * l * d;
  }
  if (hasRigging()) {
    // The bar's uniform tension: the payload's load and half the bar's weight (its consistent
    // gravity puts half on each end).
    const double Tr = end_force + 0.5 * field * rigging_->massPerLength() * rigging_->length();
    q.tail<3>() = q.segment<3>(6 * elements_) +
                  (1.0 + Tr / rigging_->axialStiffness()) * rigging_->length() * d;
  }
  return q;
}

Eigen::VectorXd AncfRope::straight(const Eigen::Vector3d& top, const Eigen::Vector3d& d) const {
  // Zero axial force: eps = 0, or the tension-only law's slack edge eps = -kSlackBand (at eps = 0
  // its smoothed band still carries EA kSlackBand / 4, ancfAxialLaw).
  const double g = element_.tension_only ? 1.0 - kSlackBand : 1.0;
  Eigen::VectorXd q(dofs());
  for (int j = 0; j <= elements_; ++j) {
    q.segment<3>(6 * j) = top + g * element_.length * j * d;
    q.segment<3>(6 * j + 3) = g * d;
  }
  if (hasRigging()) q.tail<3>() = top + (g * length() + rigging_->length()) * d;
  return q;
}

void AncfRope::setRigging(double length, double hook_mass, double mass_per_length,
                          double axial_stiffness) {
  if (!(std::isfinite(hook_mass) && hook_mass > 0.0)) {
    throw std::invalid_argument("rigging: hook block mass must be finite and > 0");
  }
  // PendulumRope checks length, mass per length and EA; a sling takes no compression.
  rigging_.emplace(length, mass_per_length, axial_stiffness, end_mass_, gravity_, 0.0);
  rigging_->setTensionOnly(true);
  hook_mass_ = hook_mass;
  assembleMass();
  revision_ = nextRevision();
}

std::vector<Eigen::Vector3d> AncfRope::sampleCurve(const Eigen::VectorXd& q, int per_element,
                                                   double element_length) const {
  const double le = element_length > 0.0 ? element_length : element_.length;
  if (!hasRigging()) return sampleRopeCurve(q, le, per_element);
  std::vector<Eigen::Vector3d> points =
      sampleRopeCurve(q.head(6 * (elements_ + 1)), le, per_element);
  const Eigen::Vector3d hook = points.back(), load = q.tail<3>();
  for (int i = 1; i <= per_element; ++i) points.push_back(hook + (load - hook) * i / per_element);
  return points;
}

std::array<int, 6> AncfRope::riggingDofs() const {
  const int n = 6 * elements_, p = dofs() - 3;
  return {n, n + 1, n + 2, p, p + 1, p + 2};
}

// r(xi) = S(xi) e per element (docs/model.md), xi = k / per_element.
std::vector<Eigen::Vector3d> sampleRopeCurve(const Eigen::VectorXd& q, double l, int per_element) {
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
