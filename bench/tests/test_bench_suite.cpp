// The mesh selection of `tmlab bench` (bench_suite.hpp): the names --meshes accepts and what
// check_bench_meshes refuses (an unknown name, listing the known ones; cube_2m without --large; a
// cube --quick does not measure). run_bench itself is tested end to end by test_cli_bench.
#include "bench/bench_suite.hpp"

#include "core/base/error.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace tmlab::tm {
namespace {

BenchOptions with(std::vector<std::string> meshes, bool quick = false, bool large = false) {
  BenchOptions o;
  o.meshes = std::move(meshes);
  o.quick = quick;
  o.large = large;
  return o;
}

TEST(BenchSuite, KnowsItsMeshes) {
  EXPECT_EQ(bench_mesh_names(),
            (std::vector<std::string>{"liver", "cube_2k", "cube_24k", "cube_240k", "cube_2m", "contact"}));
}

TEST(BenchSuite, AcceptsEveryMeshItMeasures) {
  EXPECT_EQ(check_bench_meshes(with({})), "");
  EXPECT_EQ(check_bench_meshes(with({"liver", "cube_2k", "cube_24k", "cube_240k", "contact"})), "");
  EXPECT_EQ(check_bench_meshes(with({"cube_2m"}, false, true)), "");
  EXPECT_EQ(check_bench_meshes(with({"liver", "cube_2k", "contact"}, true)), "");
}

TEST(BenchSuite, RefusesWhatItWouldNotMeasureSayingWhy) {
  EXPECT_EQ(
      check_bench_meshes(with({"liver", "cube_9k"})),
      "--meshes: unknown mesh 'cube_9k' (known: liver, cube_2k, cube_24k, cube_240k, cube_2m, contact)");
  EXPECT_EQ(check_bench_meshes(with({"cube_2m"})), "--meshes: 'cube_2m' needs --large");
  EXPECT_EQ(check_bench_meshes(with({"cube_24k"}, true)),
            "--meshes: 'cube_24k' is not measured with --quick");
  EXPECT_EQ(check_bench_meshes(with({"cube_240k"}, true, true)),
            "--meshes: 'cube_240k' is not measured with --quick");
}

TEST(BenchSuite, RunBenchRefusesBadOptionsBeforeMeasuring) {
  BenchOptions o = with({"cube_2m"});
  try {
    run_bench(o);
    FAIL() << "cube_2m without --large was run";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "bench: --meshes: 'cube_2m' needs --large");
  }
  o = with({});
  o.max_threads = 0;
  EXPECT_THROW(run_bench(o), Error);
}

}  // namespace
}  // namespace tmlab::tm
