#include "crane_twin/elements/sparse_assembly.hpp"

#include <stdexcept>

namespace crane_twin {

void SparseAssembler::add(const Eigen::MatrixXd& Ke, const std::vector<int>& eq) {
  if (Ke.rows() != static_cast<long>(eq.size()) || Ke.cols() != Ke.rows()) {
    throw std::invalid_argument("SparseAssembler::add: block size does not match DOF list");
  }
  for (std::size_t i = 0; i < eq.size(); ++i) {
    if (eq[i] < 0) continue;
    for (std::size_t j = 0; j < eq.size(); ++j) {
      if (eq[j] < 0 || Ke(i, j) == 0.0) continue;
      triplets_.emplace_back(eq[i], eq[j], Ke(i, j));
    }
  }
}

void SparseAssembler::addEntry(int i, int j, double v) { triplets_.emplace_back(i, j, v); }

SparseMatrix SparseAssembler::build() const {
  SparseMatrix A(size_, size_);
  A.setFromTriplets(triplets_.begin(), triplets_.end());
  A.makeCompressed();
  return A;
}

}  // namespace crane_twin
