// TangentPattern: the compressed-column sparsity pattern of a tet-mesh stiffness matrix with 3 DOFs
// per node (node-major), built once from the element node graph, plus for every element the position
// of each of its n^2 3x3 blocks in the value array (n = 4 nodes for P1 tets, 10 for the quadratic
// tets of core/mesh/quadratic_mesh.hpp), so a tangent is refilled in place with no search.
//
// Layout: the rows of column 3c+b are 3r+a for the sorted nodes r adjacent to c (including c) and
// a = 0..2; entry (3r+a, 3c+b) sits at value index block_base(t,p,q) + b*column_stride(c) + a with
// column_stride(c) = 3*deg(c).
#pragma once

#include "core/mesh/mesh.hpp"
#include "core/mesh/quadratic_mesh.hpp"

#include <Eigen/SparseCore>

#include <vector>

namespace tmlab::tm {

class TangentPattern {
 public:
  using StorageIndex = Eigen::SparseMatrix<double>::StorageIndex;

  TangentPattern() = default;
  TangentPattern(Index num_nodes, const std::vector<Tet>& tets);
  /// The pattern of the 10-node tets (the P2 node graph: every pair of nodes sharing a tet).
  TangentPattern(Index num_nodes, const std::vector<Tet10>& tets);

  Index num_dofs() const { return 3 * num_nodes_; }

  /// True when K is compressed, num_dofs square, with this pattern's column pointers and nnz
  /// (the row indices are not compared: O(num_dofs) check).
  bool matches(const Eigen::SparseMatrix<double>& K) const;
  /// Gives K this pattern with all values zero.
  void reset(Eigen::SparseMatrix<double>& K) const;

  /// Adds the 3N x 3N local matrix Kt (local node-major rows 3p+a, cols 3q+b) of element t into
  /// `values` (K.valuePtr() of a matrix with this pattern; N the pattern's nodes per element).
  template <std::size_t N, class MatN>
  void scatter(Index t, const std::array<Index, N>& tet, const MatN& Kt, double* values) const {
    constexpr int n = static_cast<int>(N);
    const StorageIndex* base = &block_base_[N * N * static_cast<std::size_t>(t)];
    for (int q = 0; q < n; ++q) {
      const StorageIndex stride = stride_[static_cast<std::size_t>(tet[q])];
      for (int p = 0; p < n; ++p) {
        double* dst = values + base[n * q + p];
        for (int b = 0; b < 3; ++b)
          for (int a = 0; a < 3; ++a) dst[b * stride + a] += Kt(3 * p + a, 3 * q + b);
      }
    }
  }

 private:
  /// The pattern of the elements `tets` (std::array<Index, n> each).
  template <class Element>
  void build(const std::vector<Element>& tets);

  Index num_nodes_ = 0;
  std::vector<StorageIndex> outer_;       ///< num_dofs + 1 column pointers
  std::vector<StorageIndex> inner_;       ///< row indices
  std::vector<StorageIndex> stride_;      ///< per node c: 3 deg(c)
  std::vector<StorageIndex> block_base_;  ///< per element, n^2 entries [n q + p]: index of (3 el[p], 3 el[q])
};

}  // namespace tmlab::tm
