// LoadIncrements: the whole step first; halving after failures down to max_cutbacks; growing back
// after a success; the last attempt ends exactly at t_next.
#include "tensormass/solvers/load_increments.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace tmlab::tm {
namespace {

TEST(LoadIncrements, WholeStepWhenItSucceeds) {
  LoadIncrements inc(1.0, 1.5, 3);
  ASSERT_TRUE(inc.more());
  EXPECT_EQ(inc.done(), 1.0);
  EXPECT_EQ(inc.next(), 1.5);
  inc.accept(inc.next());
  EXPECT_FALSE(inc.more());
  EXPECT_EQ(inc.done(), 1.5);
}

TEST(LoadIncrements, HalvesOnFailureAndGrowsBack) {
  LoadIncrements inc(0.0, 1.0, 2);
  inc.cut_back();  // 0.5
  EXPECT_EQ(inc.next(), 0.5);
  inc.cut_back();  // 0.25
  EXPECT_EQ(inc.depth(), 2);
  EXPECT_TRUE(inc.exhausted());
  EXPECT_EQ(inc.next(), 0.25);
  inc.accept(0.25);  // grows back to 0.5
  EXPECT_EQ(inc.depth(), 1);
  EXPECT_FALSE(inc.exhausted());
  EXPECT_EQ(inc.next(), 0.75);
  inc.accept(0.75);  // grows back to 1.0: the rest (0.25) fits, the attempt ends at t_next
  EXPECT_EQ(inc.depth(), 0);
  EXPECT_EQ(inc.next(), 1.0);
  inc.accept(1.0);
  EXPECT_FALSE(inc.more());
}

TEST(LoadIncrements, EndsExactlyAtTheEndDespiteRoundOff) {
  // 0.1 + (0.7 - 0.1) / 2 + ... need not sum to 0.7 in binary: the last attempt ends at t_next
  // itself, with no sliver left.
  LoadIncrements inc(0.1, 0.7, 5);
  std::vector<double> ends;
  inc.cut_back();
  while (inc.more()) {
    ends.push_back(inc.next());
    inc.accept(ends.back());
  }
  ASSERT_FALSE(ends.empty());
  EXPECT_EQ(ends.back(), 0.7);
  EXPECT_EQ(ends.size(), 2u);
}

}  // namespace
}  // namespace tmlab::tm
