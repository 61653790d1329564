// Sparse assembly of element matrices into global matrices over a DOF map.
//
// A DOF map sends a global DOF index to an equation number, or -1 for a constrained DOF
// (clamped base nodes). Element blocks are gathered as triplets and summed by Eigen.
#pragma once

#include <Eigen/Sparse>
#include <vector>

namespace crane_twin {

using SparseMatrix = Eigen::SparseMatrix<double>;

class SparseAssembler {
 public:
  explicit SparseAssembler(int size) : size_(size) {}
  /// Add the dense block Ke at rows/cols given by eq (entries < 0 are skipped).
  void add(const Eigen::MatrixXd& Ke, const std::vector<int>& eq);
  /// Add a value at (i, j) (both >= 0).
  void addEntry(int i, int j, double v);
  SparseMatrix build() const;
  int size() const { return size_; }

 private:
  int size_;
  std::vector<Eigen::Triplet<double>> triplets_;
};

}  // namespace crane_twin
