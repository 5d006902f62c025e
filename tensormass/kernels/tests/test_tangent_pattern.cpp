// TangentPattern: the compressed-column pattern and the per-tet block positions, checked against
// the obvious oracle, a matrix assembled from triplets (Eigen's setFromTriplets sums duplicates).
#include "tensormass/kernels/tangent_pattern.hpp"

#include "core/mesh/mesh_generator.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <random>
#include <set>
#include <utility>
#include <vector>

namespace tmlab::tm {
namespace {

using Mat12 = Eigen::Matrix<double, 12, 12>;
using SpMat = Eigen::SparseMatrix<double>;

/// Local matrices with small integer entries, so every sum is exact and the comparison can be ==.
std::vector<Mat12> integer_blocks(std::size_t count, std::mt19937& rng) {
  std::uniform_int_distribution<int> value(-9, 9);
  std::vector<Mat12> out(count);
  for (Mat12& m : out)
    for (int i = 0; i < 12; ++i)
      for (int j = 0; j < 12; ++j) m(i, j) = value(rng);
  return out;
}

/// The oracle: K assembled from triplets, local (3p+a, 3q+b) -> global (3 tet[p]+a, 3 tet[q]+b).
SpMat assemble_with_triplets(Index num_nodes, const std::vector<Tet>& tets, const std::vector<Mat12>& kt) {
  std::vector<Eigen::Triplet<double>> trip;
  for (std::size_t t = 0; t < tets.size(); ++t)
    for (int p = 0; p < 4; ++p)
      for (int q = 0; q < 4; ++q)
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b)
            trip.emplace_back(3 * tets[t][p] + a, 3 * tets[t][q] + b, kt[t](3 * p + a, 3 * q + b));
  SpMat K(3 * num_nodes, 3 * num_nodes);
  K.setFromTriplets(trip.begin(), trip.end());
  K.makeCompressed();
  return K;
}

SpMat assemble_with_pattern(const TangentPattern& pattern, const std::vector<Tet>& tets,
                            const std::vector<Mat12>& kt) {
  SpMat K;
  pattern.reset(K);
  for (std::size_t t = 0; t < tets.size(); ++t)
    pattern.scatter(static_cast<Index>(t), tets[t], kt[t], K.valuePtr());
  return K;
}

/// Number of distinct (row node, column node) pairs coupled by some tet.
std::size_t coupled_node_pairs(const std::vector<Tet>& tets) {
  std::set<std::pair<Index, Index>> pairs;
  for (const Tet& tet : tets)
    for (const Index i : tet)
      for (const Index j : tet) pairs.emplace(i, j);
  return pairs.size();
}

TEST(TangentPattern, ScatterEqualsTripletAssemblyOnABoxMesh) {
  const Mesh m = make_box_mesh(Vec3::Zero(), Vec3::Ones(), 3, 2, 2);
  std::mt19937 rng(11);
  const std::vector<Mat12> kt = integer_blocks(m.tets.size(), rng);
  const TangentPattern pattern(m.num_points(), m.tets);
  const SpMat expected = assemble_with_triplets(m.num_points(), m.tets, kt);
  const SpMat K = assemble_with_pattern(pattern, m.tets, kt);
  ASSERT_EQ(K.rows(), 3 * m.num_points());
  ASSERT_EQ(K.cols(), 3 * m.num_points());
  EXPECT_EQ(Eigen::MatrixXd(K), Eigen::MatrixXd(expected));
  // The pattern holds every 3x3 block of every coupled node pair, and nothing else (an entry that
  // happens to sum to zero is still stored).
  EXPECT_EQ(static_cast<std::size_t>(K.nonZeros()), 9 * coupled_node_pairs(m.tets));
}

TEST(TangentPattern, ShuffledNodeOrderAndUnusedNodes) {
  // Tets listing their nodes in arbitrary order, a node shared by all, and nodes 5 and 7 in no tet
  // (their rows and columns stay empty).
  const std::vector<Tet> tets = {{3, 0, 6, 1}, {6, 2, 3, 0}, {4, 3, 2, 6}, {8, 6, 4, 3}};
  const Index num_nodes = 9;
  std::mt19937 rng(12);
  const std::vector<Mat12> kt = integer_blocks(tets.size(), rng);
  const TangentPattern pattern(num_nodes, tets);
  EXPECT_EQ(pattern.num_dofs(), 27);
  const SpMat K = assemble_with_pattern(pattern, tets, kt);
  EXPECT_EQ(Eigen::MatrixXd(K), Eigen::MatrixXd(assemble_with_triplets(num_nodes, tets, kt)));
  EXPECT_EQ(static_cast<std::size_t>(K.nonZeros()), 9 * coupled_node_pairs(tets));
  for (const Index unused : {5, 7})
    for (int a = 0; a < 3; ++a) {
      const Index col = 3 * unused + a;
      EXPECT_EQ(K.outerIndexPtr()[col + 1] - K.outerIndexPtr()[col], 0) << "column " << col;
    }
}

TEST(TangentPattern, RowIndicesAreSortedWithinEachColumn) {
  // Eigen's compressed format (and every solver reading it) needs sorted, unique rows per column.
  const Mesh m = make_box_mesh(Vec3::Zero(), Vec3::Ones(), 2, 2, 2);
  const TangentPattern pattern(m.num_points(), m.tets);
  SpMat K;
  pattern.reset(K);
  for (Index c = 0; c < K.cols(); ++c) {
    for (auto k = K.outerIndexPtr()[c] + 1; k < K.outerIndexPtr()[c + 1]; ++k) {
      ASSERT_LT(K.innerIndexPtr()[k - 1], K.innerIndexPtr()[k]) << "column " << c;
    }
  }
  EXPECT_EQ(Eigen::MatrixXd(K).norm(), 0.0);  // reset gives the pattern with all values zero
}

TEST(TangentPattern, ResetThenMatchesAndRefillsInPlace) {
  const Mesh m = make_box_mesh(Vec3::Zero(), Vec3::Ones(), 2, 1, 1);
  const TangentPattern pattern(m.num_points(), m.tets);
  SpMat K;
  EXPECT_FALSE(pattern.matches(K));  // empty
  pattern.reset(K);
  EXPECT_TRUE(pattern.matches(K));
  // A refill scatters into the same storage: the value array does not move.
  std::mt19937 rng(13);
  const double* values = K.valuePtr();
  for (int round = 0; round < 2; ++round) {
    const std::vector<Mat12> kt = integer_blocks(m.tets.size(), rng);
    std::fill(K.valuePtr(), K.valuePtr() + K.nonZeros(), 0.0);
    for (std::size_t t = 0; t < m.tets.size(); ++t)
      pattern.scatter(static_cast<Index>(t), m.tets[t], kt[t], K.valuePtr());
    EXPECT_EQ(K.valuePtr(), values);
    EXPECT_EQ(Eigen::MatrixXd(K), Eigen::MatrixXd(assemble_with_triplets(m.num_points(), m.tets, kt)));
  }
}

TEST(TangentPattern, MatchesRejectsOtherSizesUncompressedAndOtherPatterns) {
  const Mesh m = make_box_mesh(Vec3::Zero(), Vec3::Ones(), 2, 1, 1);
  const TangentPattern pattern(m.num_points(), m.tets);
  SpMat K;
  pattern.reset(K);

  SpMat smaller(K.rows() - 3, K.cols() - 3);
  smaller.makeCompressed();
  EXPECT_FALSE(pattern.matches(smaller));

  SpMat uncompressed = K;
  uncompressed.uncompress();
  EXPECT_FALSE(pattern.matches(uncompressed));

  // Same size, fewer entries: the triplet matrix of the mesh's first tet alone.
  const std::vector<Tet> fewer = {m.tets.front()};
  std::mt19937 rng(14);
  const SpMat other = assemble_with_triplets(m.num_points(), fewer, integer_blocks(fewer.size(), rng));
  ASSERT_EQ(other.rows(), K.rows());
  ASSERT_LT(other.nonZeros(), K.nonZeros());
  EXPECT_FALSE(pattern.matches(other));

  // Another pattern of the same size: the tangent of a different mesh.
  const TangentPattern other_pattern(m.num_points(), fewer);
  EXPECT_FALSE(other_pattern.matches(K));
}

}  // namespace
}  // namespace tmlab::tm
