// TangentPattern: the compressed-column sparsity pattern of a P1 tet-mesh stiffness matrix with 3
// DOFs per node (node-major), built once from the mesh graph, plus for every tet the position of
// each of its 16 3x3 blocks in the value array, so a tangent is refilled in place with no search.
//
// Layout: the rows of column 3c+b are 3r+a for the sorted nodes r adjacent to c (including c) and
// a = 0..2; entry (3r+a, 3c+b) sits at value index block_base(t,p,q) + b*column_stride(c) + a with
// column_stride(c) = 3*deg(c).
#pragma once

#include "core/mesh/mesh.hpp"

#include <Eigen/SparseCore>

#include <vector>

namespace tmlab::tm {

class TangentPattern {
 public:
  using StorageIndex = Eigen::SparseMatrix<double>::StorageIndex;

  TangentPattern() = default;
  TangentPattern(Index num_nodes, const std::vector<Tet>& tets);

  Index num_dofs() const { return 3 * num_nodes_; }

  /// True when K is compressed, num_dofs square, with this pattern's column pointers and nnz
  /// (the row indices are not compared: O(num_dofs) check).
  bool matches(const Eigen::SparseMatrix<double>& K) const;
  /// Gives K this pattern with all values zero.
  void reset(Eigen::SparseMatrix<double>& K) const;

  /// Adds the 12x12 local matrix Kt (local node-major rows 3p+a, cols 3q+b) of tet t into `values`
  /// (K.valuePtr() of a matrix with this pattern).
  template <class Mat12>
  void scatter(Index t, const std::array<Index, 4>& tet, const Mat12& Kt, double* values) const {
    const StorageIndex* base = &block_base_[16 * static_cast<std::size_t>(t)];
    for (int q = 0; q < 4; ++q) {
      const StorageIndex stride = stride_[static_cast<std::size_t>(tet[q])];
      for (int p = 0; p < 4; ++p) {
        double* dst = values + base[4 * q + p];
        for (int b = 0; b < 3; ++b)
          for (int a = 0; a < 3; ++a) dst[b * stride + a] += Kt(3 * p + a, 3 * q + b);
      }
    }
  }

 private:
  Index num_nodes_ = 0;
  std::vector<StorageIndex> outer_;       ///< num_dofs + 1 column pointers
  std::vector<StorageIndex> inner_;       ///< row indices
  std::vector<StorageIndex> stride_;      ///< per node c: 3 deg(c)
  std::vector<StorageIndex> block_base_;  ///< per tet, 16 entries [4q + p]: index of (3 tet[p], 3 tet[q])
};

}  // namespace tmlab::tm
