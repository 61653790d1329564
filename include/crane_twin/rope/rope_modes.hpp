// Lowest modes of the rope linearised at a state e_m with its top node's position held
// (docs/model.md): K_ii(e_m) phi = w^2 M_ii phi over the rope coordinates without the top node's
// three position DOFs (the top slope stays free), mass-normalised. With the three rigid
// translations of the whole rope they span the reduced rope's motion (SubdomainReducedSolver): the
// top moves by the translations, which cost no elastic force (the energy is translation-invariant).
//
// Cold solve: ARPACK shift-invert (a few modes) or Eigen's dense generalised solver (a large
// fraction of the spectrum, where Lanczos needs nearly the whole space anyway).
// Warm update: `sweeps` block inverse (subspace) iterations (default two) from the previous
// basis with a sparse LDL^T of K_ii - sigma M_ii, then one Rayleigh-Ritz step on the block
// (Bathe's subspace iteration). The
// block carries `guard` extra vectors beyond the kept modes so the highest kept modes converge.
#pragma once

#include <Eigen/Dense>

#include "crane_twin/elements/sparse_assembly.hpp"

namespace crane_twin {

struct RopeModes {
  Eigen::VectorXd omega2;  ///< [rad^2/s^2], ascending, the kept modes first, then the guard
  Eigen::MatrixXd phi;     ///< full rope coordinates (n rows; the top position rows are zero)
  int kept = 0;            ///< number of kept modes (the first columns)
};

struct RopeModeSettings {
  int kept = 10;        ///< modes kept, 1 .. n - 3
  int guard = 0;        ///< extra block vectors for warm updates (0: max(4, kept / 4))
  double shift = -1.0;  ///< sigma [rad^2/s^2]
  int sweeps = 2;       ///< subspace iterations per warm update
};

/// Interior (top position removed) K and M of the rope: rows/cols 3.. of the full matrices.
SparseMatrix withoutTopPosition(const SparseMatrix& A);

/// Modes from scratch. K, M: full rope matrices (n x n). Throws std::runtime_error on failure.
RopeModes coldRopeModes(const SparseMatrix& K, const SparseMatrix& M, const RopeModeSettings& s);

/// Modes of (K, M) from the previous block `previous` (same n). Throws std::runtime_error if the
/// factorisation fails (the caller then falls back to a cold solve).
RopeModes warmRopeModes(const SparseMatrix& K, const SparseMatrix& M, const RopeModes& previous,
                        const RopeModeSettings& s);

/// max over kept modes of |K phi - w^2 M phi| / |K phi - sigma M phi| (relative residual with the
/// shift, well defined for near-zero w^2), and max |phi^T M phi - I| over kept modes.
double ropeModeResidual(const SparseMatrix& K, const SparseMatrix& M, const RopeModes& m,
                        double shift = -1.0);
double ropeModeOrthonormalityError(const SparseMatrix& M, const RopeModes& m);

}  // namespace crane_twin
