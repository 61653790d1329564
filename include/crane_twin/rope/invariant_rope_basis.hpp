// The rotation-invariant Ritz basis of the reduced rope (docs/model.md, "Reduced rope").
//
// The ANCF rope's mass matrix is isotropic, M = M_s (x) I3 (M_s the scalar mass over the 2 (N+1)
// scalar coordinates of one direction: node positions and slopes), and its elastic energy
// depends on q only through the dot products of r_x and r_xx: U(R q) = U(q) for every rotation R
// applied to all positions and slopes. A basis of the form B = Psi (x) I3 (Psi: m scalar shapes
// over those 2 (N+1) coordinates) spans a space that every rotation maps onto itself, so
//   q = B y,  y = [a_0; a_1; ...; a_(m-1)],  r(x) = sum_k psi_k(x) a_k   (a_k in R^3)
// carries any finite rigid rotation and translation of a shape it carries (R q = B (I (x) R) y),
// with a constant mass matrix M_r = (Psi^T M_s Psi) (x) I3 and no frame, no quadratic velocity
// terms and no subdomains. The elastic force is evaluated exactly at the expanded state
// (InvariantReducedSolver::force), so the reduced model is the Galerkin projection of the
// full-order equations onto the space of B (with its own Gauss rule, at least 2 points per
// element).
//
// The shapes, functions of xi = x / L (slopes stored as d/dxi, so r_x = a . psi' / L):
//   psi_0 = 1 (the translation; a_0 is the top node's position, every other shape is zero there),
//   psi_1 = xi (a straight chord of any direction and stretch is a_0 + xi a_1, exactly),
//   the static shapes of the rope hanging along -z under its weight and the end mass: the
//     transverse response to the distributed weight and the axial stretch under it,
//   the lowest transverse modes  K_T psi = w^2 M_s psi  and the lowest axial modes
//     K_A psi = w^2 M_s psi  of that hanging rope with the top position held (ARPACK),
// where K_T and K_A are the x-x and z-z blocks of the full tangent of the vertical rope at its
// static tension profile. Shapes after psi_0 are M_s-orthogonalised in this order (a shape the
// earlier ones already span is dropped) and scaled to a largest node displacement of 1, so a_k
// is in metres.
//
// Hoisting keeps y: with the slopes in d/dxi the full model's uniform rescaling (positions kept,
// slopes scaled by L_old / L_new, AncfRope::setLength) is exactly q = B(L_new) y, and every
// matrix is a function of L in closed form (M_s = mu L M_hat + point masses).
#pragma once

#include <Eigen/Dense>

#include "crane_twin/elements/sparse_assembly.hpp"
#include "crane_twin/rope/ancf_rope.hpp"

namespace crane_twin {

struct InvariantBasisSettings {
  int transverse_modes = 6;  ///< lowest transverse modes of the hanging rope
  int axial_modes = 2;       ///< lowest axial modes
};

class InvariantRopeBasis {
 public:
  /// Shapes of `rope` (its length, masses, EA, EI at the time of the call). Throws
  /// std::invalid_argument for negative counts, std::runtime_error where the eigen-solve fails.
  InvariantRopeBasis(const AncfRope& rope, const InvariantBasisSettings& settings);

  int shapes() const { return static_cast<int>(position_.cols()); }
  int coordinates() const { return 3 * shapes(); }
  int nodes() const { return static_cast<int>(position_.rows()); }
  /// psi_k at the nodes (nodes x m) and d psi_k / d xi there.
  const Eigen::MatrixXd& positionRows() const { return position_; }
  const Eigen::MatrixXd& slopeRows() const { return slope_; }
  /// Lowest angular frequencies of the kept modes [rad/s] (transverse, axial) at the basis length.
  const Eigen::VectorXd& transverseOmega() const { return transverse_omega_; }
  const Eigen::VectorXd& axialOmega() const { return axial_omega_; }

  /// This basis with the shapes of a state q it does not hold (full coordinates at length L, M
  /// the rope's mass matrix there): the x, y and z parts of q's residual r = q - B y_p (y_p the
  /// M-orthogonal projection) as three scalar shapes, each M_s-orthogonal to Psi already (M = M_s
  /// (x) I3), orthogonalised among themselves (a part under 1e-6 of the largest part's norm is
  /// dropped: a planar state adds two) and scaled to a largest node displacement or slope change
  /// times the element length of 1 (a bend's shape may move slopes more than positions). The
  /// result holds q exactly and stays rotation-invariant (B = Psi (x) I3). Where r is zero to
  /// round-off, the copy is this basis.
  InvariantRopeBasis withShapesOf(const Eigen::VectorXd& q, const SparseMatrix& M, double L) const;

  /// Full ANCF coordinates of y at rope length L (q = B(L) y).
  Eigen::VectorXd expand(const Eigen::VectorXd& y, double L) const;
  /// Position of node j [m]: sum_k psi_k(x_j) a_k.
  Eigen::Vector3d nodePosition(const Eigen::VectorXd& y, int j) const;
  /// B(L)^T x for a full-coordinate force x.
  Eigen::VectorXd projectForce(const Eigen::VectorXd& x, double L) const;
  /// The M-orthogonal projection of full coordinates x onto the basis at length L: solves
  /// M_r y = B^T M x, M the rope's mass matrix at L (AncfRope::massMatrix), M_r = B^T M B.
  /// Set up once (M_s Psi and the factorised scalar M_rs), applied to any number of vectors.
  class Projection {
   public:
    Projection(const InvariantRopeBasis& basis, const SparseMatrix& M, double L);
    Eigen::VectorXd operator()(const Eigen::VectorXd& x) const;
    /// The same projection with the top and last node's positions held: per direction,
    ///   min (x - Psi y)^T M_s (x - Psi y)  subject to  y_0 = x_top,  psi(1)^T y = x_end,
    /// i.e. y' = M'^-1 Psi'^T M_s z + g (z_end - psi'(1)^T M'^-1 Psi'^T M_s z) / (psi'(1)^T g),
    /// z = x - x_top psi_0, g = M'^-1 psi'(1) (primes: without psi_0). Applied to velocities it
    /// keeps the top's and the end mass's velocity exactly (docs/model.md "Hand-over to full
    /// order"); a state the basis holds is returned exactly, as by operator().
    Eigen::VectorXd withEndsHeld(const Eigen::VectorXd& x) const;
    /// Scalar reduced mass M_rs = Psi^T M_s Psi (m x m).
    const Eigen::MatrixXd& scalarMass() const { return Mr_; }

   private:
    Eigen::MatrixXd MsP_, Mr_;
    Eigen::LDLT<Eigen::MatrixXd> ldlt_;
    // withEndsHeld: the factorised M' (psi_0 left out), g = M'^-1 psi'(1), psi'(1)^T g, psi(1).
    Eigen::LDLT<Eigen::MatrixXd> inner_ldlt_;
    Eigen::VectorXd end_row_, g_;
    double end_gain_ = 0.0;
  };

 private:
  Eigen::MatrixXd position_, slope_;  ///< nodes x m
  Eigen::VectorXd transverse_omega_, axial_omega_;
  // Psi(L) over the 2 (N+1) scalar coordinates (positions, slopes in d/dx) and the scalar
  // block of a full matrix (every direction's block equals it for an isotropic matrix).
  Eigen::MatrixXd scalarRows(double L) const;
};

/// Scalar x-x block of an isotropic or x-z-symmetric full rope matrix: rows/cols 6 j + 3 t + c
/// for direction c (0: x, 2: z) as scalar index 2 j + t.
SparseMatrix scalarBlock(const SparseMatrix& A, int direction);

}  // namespace crane_twin
