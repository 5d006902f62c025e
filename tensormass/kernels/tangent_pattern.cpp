#include "tensormass/kernels/tangent_pattern.hpp"

#include "core/base/error.hpp"

#include <algorithm>
#include <cassert>
#include <cstdint>
#include <limits>
#include <tuple>

namespace tmlab::tm {

template <class Element>
void TangentPattern::build(const std::vector<Element>& tets) {
  const auto n = static_cast<std::size_t>(num_nodes_);
  const std::size_t m = std::tuple_size<Element>::value;
  const std::size_t num_elements = tets.size();
  // Node graph: all (column node, row node) pairs of every element, sorted and unique.
  std::vector<std::uint64_t> pairs;
  pairs.reserve(m * m * num_elements);
  for (std::size_t t = 0; t < num_elements; ++t) {
    const Element& tet = tets[t];
    for (std::size_t q = 0; q < m; ++q)
      for (std::size_t p = 0; p < m; ++p)
        pairs.push_back((static_cast<std::uint64_t>(tet[q]) << 32) | static_cast<std::uint32_t>(tet[p]));
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());

  std::vector<std::size_t> start(n + 1, 0);  // node-graph CSC: rows of column node c
  for (std::uint64_t key : pairs) ++start[static_cast<std::size_t>(key >> 32) + 1];
  for (std::size_t c = 0; c < n; ++c) start[c + 1] += start[c];
  std::vector<Index> rows(pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i) rows[i] = static_cast<Index>(pairs[i] & 0xffffffffu);

  const std::size_t nnz = 9 * pairs.size();
  if (nnz > static_cast<std::size_t>(std::numeric_limits<StorageIndex>::max()))
    throw Error("tangent pattern: too many nonzeros for 32-bit sparse indices");
  outer_.resize(3 * n + 1);
  inner_.resize(nnz);
  stride_.resize(n);
  for (std::size_t c = 0; c < n; ++c) {
    const std::size_t deg = start[c + 1] - start[c];
    stride_[c] = static_cast<StorageIndex>(3 * deg);
    for (std::size_t b = 0; b < 3; ++b) {
      const std::size_t col_begin = 9 * start[c] + b * 3 * deg;
      outer_[3 * c + b] = static_cast<StorageIndex>(col_begin);
      for (std::size_t k = 0; k < deg; ++k)
        for (std::size_t a = 0; a < 3; ++a)
          inner_[col_begin + 3 * k + a] = static_cast<StorageIndex>(3 * rows[start[c] + k] + a);
    }
  }
  outer_[3 * n] = static_cast<StorageIndex>(nnz);

  block_base_.resize(m * m * num_elements);
  for (std::size_t t = 0; t < num_elements; ++t) {
    const Element& tet = tets[t];
    for (std::size_t q = 0; q < m; ++q) {
      const auto c = static_cast<std::size_t>(tet[q]);
      const auto first = rows.begin() + static_cast<std::ptrdiff_t>(start[c]);
      const auto last = rows.begin() + static_cast<std::ptrdiff_t>(start[c + 1]);
      for (std::size_t p = 0; p < m; ++p) {
        const auto it = std::lower_bound(first, last, tet[p]);
        assert(it != last && *it == tet[p]);
        const auto k = static_cast<std::size_t>(it - first);
        block_base_[m * m * t + m * q + p] =
            static_cast<StorageIndex>(outer_[3 * c] + static_cast<StorageIndex>(3 * k));
      }
    }
  }
}

TangentPattern::TangentPattern(Index num_nodes, const std::vector<Tet>& tets) : num_nodes_(num_nodes) {
  build(tets);
}

TangentPattern::TangentPattern(Index num_nodes, const std::vector<Tet10>& tets) : num_nodes_(num_nodes) {
  build(tets);
}

bool TangentPattern::matches(const Eigen::SparseMatrix<double>& K) const {
  if (K.rows() != num_dofs() || K.cols() != num_dofs() || !K.isCompressed()) return false;
  if (static_cast<std::size_t>(K.nonZeros()) != inner_.size()) return false;
  return std::equal(outer_.begin(), outer_.end(), K.outerIndexPtr());
}

void TangentPattern::reset(Eigen::SparseMatrix<double>& K) const {
  std::vector<double> zeros(inner_.size(), 0.0);
  const Eigen::Map<const Eigen::SparseMatrix<double>> view(num_dofs(), num_dofs(),
                                                           static_cast<Eigen::Index>(inner_.size()),
                                                           outer_.data(), inner_.data(), zeros.data());
  K = view;
  K.makeCompressed();
}

}  // namespace tmlab::tm
