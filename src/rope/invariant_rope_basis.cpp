#include "crane_twin/rope/invariant_rope_basis.hpp"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "crane_twin/structure/modal_analysis.hpp"

namespace crane_twin {

SparseMatrix scalarBlock(const SparseMatrix& A, int direction) {
  std::vector<Eigen::Triplet<double>> t;
  for (int c = 0; c < A.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(A, c); it; ++it)
      if (it.row() % 3 == direction && it.col() % 3 == direction)
        t.emplace_back(static_cast<int>(it.row() / 3), static_cast<int>(it.col() / 3), it.value());
  SparseMatrix S(A.rows() / 3, A.cols() / 3);
  S.setFromTriplets(t.begin(), t.end());
  return S;
}

namespace {

// Lowest `count` modes of (K, M) (interior scalar matrices): ARPACK shift-invert for a small
// part of the spectrum, Eigen's dense generalised solver where the part is large or ARPACK
// cannot run (a short rope of few elements).
ModalBasis lowestScalarModes(const SparseMatrix& K, const SparseMatrix& M, int count) {
  const int n = static_cast<int>(K.rows());
  count = std::min(count, n);
  if (count <= 0) return {};
  if (count < n / 4) {
    try {
      ModalOptions opt;
      opt.count = count;
      return lowestModes(K, M, opt);
    } catch (const std::exception&) {
      // dense below
    }
  }
  const Eigen::MatrixXd Kd(K), Md(M);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Kd, Md);
  if (es.info() != Eigen::Success)
    throw std::runtime_error("reduced rope basis: eigen-solve failed");
  ModalBasis b;
  b.omega2 = es.eigenvalues().head(count);
  b.phi = es.eigenvectors().leftCols(count);
  return b;
}

// Append v to `kept`, an M_s-orthonormal set, M_s-orthogonalised against it (twice) and
// normalised, unless what is left of it is under 1e-6 of `reference` (an M_s-norm): then the set
// already spans it.
void appendMsOrthonormal(Eigen::VectorXd v, const SparseMatrix& Ms, double reference,
                         std::vector<Eigen::VectorXd>& kept) {
  for (int pass = 0; pass < 2; ++pass)
    for (const Eigen::VectorXd& u : kept) v -= u.dot(Ms * v) * u;
  const double norm = std::sqrt(v.dot(Ms * v));
  if (norm > 1e-6 * reference) kept.push_back(v / norm);
}

// Shape k of `position` and `slope` (nodes x m) from the scalar vector v (positions, slopes in
// d/dx) divided by `peak`: slopes stored in d/dxi.
void storeShape(const Eigen::VectorXd& v, double peak, double L, int k, Eigen::MatrixXd& position,
                Eigen::MatrixXd& slope) {
  for (int j = 0; j < position.rows(); ++j) {
    position(j, k) = v(2 * j) / peak;
    slope(j, k) = v(2 * j + 1) * L / peak;
  }
}

}  // namespace

InvariantRopeBasis::InvariantRopeBasis(const AncfRope& rope, const InvariantBasisSettings& s) {
  if (s.transverse_modes < 0 || s.axial_modes < 0) {
    throw std::invalid_argument("reduced rope basis: mode counts must be >= 0");
  }
  const int N = rope.elements(), nodes = N + 1, ns = 2 * nodes;
  const double L = rope.length(), mu = rope.element().mass_per_length;
  // The vertical rope at its static tension profile T(x) = g (m_end + mu (L - x)). Without
  // gravity the shapes are those of the rope under 9.81 m/s^2 (a basis, not a state: any
  // tension profile gives smooth shapes).
  const double g = rope.gravity().norm() > 0.0 ? rope.gravity().norm() : 9.81;
  const Eigen::VectorXd q = rope.stretchedStraight(
      Eigen::Vector3d::Zero(), Eigen::Vector3d(0.0, 0.0, -1.0), g * rope.endMass(), g * mu);
  const SparseMatrix K = rope.tangentStiffness(q);
  const SparseMatrix Ms = scalarBlock(rope.massMatrix(), 0);
  const SparseMatrix KT = scalarBlock(K, 0), KA = scalarBlock(K, 2);
  // Interior: the top node's position (scalar row 0) held.
  const SparseMatrix Mi = Ms.bottomRightCorner(ns - 1, ns - 1);
  const SparseMatrix KTi = KT.bottomRightCorner(ns - 1, ns - 1);
  const SparseMatrix KAi = KA.bottomRightCorner(ns - 1, ns - 1);

  std::vector<Eigen::VectorXd> candidates;  // physical scalar coordinates (slopes d/dx)
  {
    Eigen::VectorXd xi(ns);
    for (int j = 0; j < nodes; ++j) {
      xi(2 * j) = static_cast<double>(j) / N;
      xi(2 * j + 1) = 1.0 / L;
    }
    candidates.push_back(xi);
  }
  // Static shapes under the weight (end mass included in M_s): K_i psi = M_i 1_positions. A
  // tiny mass shift keeps the solve definite where the rope has no tension and no bending.
  Eigen::VectorXd ones = Eigen::VectorXd::Zero(ns - 1);
  for (int i = 1; i < ns - 1; i += 2) ones(i) = 1.0;  // interior index i is scalar i + 1
  const Eigen::VectorXd weight = Mi * ones;
  for (const SparseMatrix* Ki : {&KTi, &KAi}) {
    const double shift = 1e-9 * Ki->diagonal().cwiseAbs().maxCoeff() /
                         std::max(Mi.diagonal().cwiseAbs().maxCoeff(), 1e-300);
    Eigen::SimplicialLDLT<SparseMatrix> ldlt(SparseMatrix(*Ki + shift * Mi));
    if (ldlt.info() != Eigen::Success) continue;
    Eigen::VectorXd v = Eigen::VectorXd::Zero(ns);
    v.tail(ns - 1) = ldlt.solve(weight);
    if (v.allFinite()) candidates.push_back(v);
  }
  const ModalBasis transverse = lowestScalarModes(KTi, Mi, s.transverse_modes);
  const ModalBasis axial = lowestScalarModes(KAi, Mi, s.axial_modes);
  transverse_omega_ = transverse.omega2.cwiseMax(0.0).cwiseSqrt();
  axial_omega_ = axial.omega2.cwiseMax(0.0).cwiseSqrt();
  for (const ModalBasis* b : {&transverse, &axial})
    for (int k = 0; k < b->phi.cols(); ++k) {
      Eigen::VectorXd v = Eigen::VectorXd::Zero(ns);
      v.tail(ns - 1) = b->phi.col(k);
      candidates.push_back(v);
    }

  // M_s-orthogonal Gram-Schmidt (twice) of the candidates; psi_0 = 1 stays apart.
  std::vector<Eigen::VectorXd> kept;
  for (const Eigen::VectorXd& v : candidates) {
    const double norm0 = std::sqrt(v.dot(Ms * v));
    if (norm0 > 0.0) appendMsOrthonormal(v, Ms, norm0, kept);
  }
  const int m = 1 + static_cast<int>(kept.size());
  position_.resize(nodes, m);
  slope_.resize(nodes, m);
  position_.col(0).setOnes();
  slope_.col(0).setZero();
  for (int k = 1; k < m; ++k) {
    const Eigen::VectorXd& v = kept[k - 1];
    double peak = 0.0;
    for (int j = 0; j < nodes; ++j) peak = std::max(peak, std::abs(v(2 * j)));
    if (!(peak > 0.0)) peak = 1.0;
    storeShape(v, peak, L, k, position_, slope_);
  }
}

InvariantRopeBasis InvariantRopeBasis::withShapesOf(const Eigen::VectorXd& q, const SparseMatrix& M,
                                                    double L) const {
  const int nodes = this->nodes(), ns = 2 * nodes;
  const Eigen::VectorXd x = q.head(3 * ns);  // (a rigging's payload point, after, is apart)
  const Projection projection(*this, M, L);
  const Eigen::VectorXd r = x - expand(projection(x), L);
  InvariantRopeBasis b = *this;
  // Round-off of the projection of a state the basis holds: far under 1e-12 of its size.
  if (!(r.cwiseAbs().maxCoeff() > 1e-12 * std::max(1.0, x.cwiseAbs().maxCoeff()))) return b;
  const SparseMatrix Ms = SparseMatrix(scalarBlock(M, 0)).topLeftCorner(ns, ns);
  // psi_1 ... psi_(m-1) (all zero at the top), M_s-normalised, then the new parts after them.
  const Eigen::MatrixXd P = scalarRows(L);
  std::vector<Eigen::VectorXd> kept;
  for (int k = 1; k < P.cols(); ++k)
    kept.push_back(P.col(k) / std::sqrt(P.col(k).dot(Ms * P.col(k))));
  const std::size_t first_new = kept.size();
  // The residual's direction c as a scalar vector (slopes d/dx, scalarRows' convention), less
  // the translation that makes its top position zero (psi_0 = 1 carries that; every other shape
  // is zero at the top, which the constraint rows rely on), then M_s-orthogonalised against the
  // basis and the parts before it.
  std::vector<Eigen::VectorXd> parts(3);
  double largest = 0.0;
  for (int c = 0; c < 3; ++c) {
    Eigen::VectorXd& v = parts[c];
    v.resize(ns);
    for (int i = 0; i < ns; ++i) v(i) = r(3 * i + c);
    for (int j = 0; j < nodes; ++j) v(2 * j) -= r(c);
    largest = std::max(largest, std::sqrt(v.dot(Ms * v)));
  }
  for (const Eigen::VectorXd& v : parts) appendMsOrthonormal(v, Ms, largest, kept);
  const int m0 = shapes(), m = m0 + static_cast<int>(kept.size() - first_new);
  const double le = L / (nodes - 1);
  b.position_.conservativeResize(nodes, m);
  b.slope_.conservativeResize(nodes, m);
  for (int k = m0; k < m; ++k) {
    const Eigen::VectorXd& v = kept[first_new + (k - m0)];
    // (a shape of a bend may move its slopes far more than its positions)
    double peak = 0.0;
    for (int j = 0; j < nodes; ++j)
      peak = std::max({peak, std::abs(v(2 * j)), le * std::abs(v(2 * j + 1))});
    storeShape(v, peak, L, k, b.position_, b.slope_);
    b.position_(0, k) = 0.0;  // (zero to round-off: exactly, for the constraint rows)
  }
  return b;
}

Eigen::MatrixXd InvariantRopeBasis::scalarRows(double L) const {
  const int nodes = this->nodes();
  Eigen::MatrixXd P(2 * nodes, shapes());
  for (int j = 0; j < nodes; ++j) {
    P.row(2 * j) = position_.row(j);
    P.row(2 * j + 1) = slope_.row(j) / L;
  }
  return P;
}

Eigen::VectorXd InvariantRopeBasis::expand(const Eigen::VectorXd& y, double L) const {
  const int m = shapes(), nodes = this->nodes();
  const Eigen::Map<const Eigen::Matrix<double, 3, Eigen::Dynamic>> Y(y.data(), 3, m);
  const Eigen::Matrix<double, 3, Eigen::Dynamic> pos = Y * position_.transpose();
  const Eigen::Matrix<double, 3, Eigen::Dynamic> slo = Y * slope_.transpose() / L;
  Eigen::VectorXd q(6 * nodes);
  for (int j = 0; j < nodes; ++j) {
    q.segment<3>(6 * j) = pos.col(j);
    q.segment<3>(6 * j + 3) = slo.col(j);
  }
  return q;
}

Eigen::Vector3d InvariantRopeBasis::nodePosition(const Eigen::VectorXd& y, int j) const {
  const Eigen::Map<const Eigen::Matrix<double, 3, Eigen::Dynamic>> Y(y.data(), 3, shapes());
  return Y * position_.row(j).transpose();
}

Eigen::VectorXd InvariantRopeBasis::projectForce(const Eigen::VectorXd& x, double L) const {
  // x as 3 x 2(N+1) (column = scalar coordinate 2 j + t); B^T x = vec(X Psi).
  const Eigen::Map<const Eigen::Matrix<double, 3, Eigen::Dynamic>> X(x.data(), 3, 2 * nodes());
  const Eigen::Matrix<double, 3, Eigen::Dynamic> Y = X * scalarRows(L);
  return Eigen::Map<const Eigen::VectorXd>(Y.data(), Y.size());
}

InvariantRopeBasis::Projection::Projection(const InvariantRopeBasis& basis, const SparseMatrix& M,
                                           double L) {
  const Eigen::MatrixXd P = basis.scalarRows(L);
  // (the hoist rope's rows: a rigging's payload point, after them, is not in the basis)
  const int ns = static_cast<int>(P.rows());
  MsP_ = SparseMatrix(scalarBlock(M, 0).topLeftCorner(ns, ns)) * P;
  Mr_ = P.transpose() * MsP_;
  ldlt_.compute(Mr_);
  // (psi_0 = 1 at every node, slopes 0; every other shape is zero at the top)
  const int m = static_cast<int>(P.cols());
  end_row_ = P.row(ns - 2).transpose();  // the last node's position row
  if (m > 1) {
    inner_ldlt_.compute(Mr_.bottomRightCorner(m - 1, m - 1));
    g_ = inner_ldlt_.solve(end_row_.tail(m - 1));
    end_gain_ = end_row_.tail(m - 1).dot(g_);
  }
}

Eigen::VectorXd InvariantRopeBasis::Projection::operator()(const Eigen::VectorXd& x) const {
  // x as 3 x 2(N+1); B^T M x = vec(X M_s Psi), then M_rs^-1 from the right.
  const Eigen::Map<const Eigen::Matrix<double, 3, Eigen::Dynamic>> X(x.data(), 3, MsP_.rows());
  const Eigen::MatrixXd rhs = X * MsP_;  // 3 x m
  const Eigen::MatrixXd Y = ldlt_.solve(rhs.transpose()).transpose();
  return Eigen::Map<const Eigen::VectorXd>(Y.data(), Y.size());
}

Eigen::VectorXd InvariantRopeBasis::Projection::withEndsHeld(const Eigen::VectorXd& x) const {
  const int ns = static_cast<int>(MsP_.rows()), m = static_cast<int>(MsP_.cols());
  // (a basis of psi_0 alone, or whose shapes all vanish at the end, has no end to hold)
  if (m < 2 || !(end_gain_ > 0.0)) return (*this)(x);
  const Eigen::Map<const Eigen::Matrix<double, 3, Eigen::Dynamic>> X(x.data(), 3, ns);
  Eigen::Matrix<double, 3, Eigen::Dynamic> Y(3, m);
  for (int c = 0; c < 3; ++c) {
    const double top = X(c, 0);
    // z = x - top psi_0: psi_0's rows are 1 at the positions (even rows) and 0 at the slopes.
    Eigen::RowVectorXd z = X.row(c);
    for (int i = 0; i < ns; i += 2) z(i) -= top;
    const Eigen::VectorXd rhs = (z * MsP_).tail(m - 1).transpose();
    Eigen::VectorXd y = inner_ldlt_.solve(rhs);
    y += g_ * ((z(ns - 2) - end_row_.tail(m - 1).dot(y)) / end_gain_);
    Y(c, 0) = top;
    Y.row(c).tail(m - 1) = y.transpose();
  }
  return Eigen::Map<const Eigen::VectorXd>(Y.data(), Y.size());
}

}  // namespace crane_twin
