// StepRecorder: the series of each recorded step (time, probes, reactions, work of the loads), the
// field files it writes, an inverted element stopping the run with its name, and the checkpoint
// round trip that rewrites the series and the field frames exactly.
#include "core/base/error.hpp"
#include "core/io/hdf5_file.hpp"
#include "core/results/series_names.hpp"
#include "runner/step_recorder.hpp"
#include "runner/tests/runner_test_case.hpp"

#include <gtest/gtest.h>

#include <filesystem>

namespace tmlab::tm::runner {
namespace {

namespace fs = std::filesystem;

class StepRecorderTest : public RunnerTestCase {
 protected:
  /// u = (lambda - 1) x e_x at every node.
  static VecX stretch_x(const Mesh& mesh, double lambda) {
    VecX u = VecX::Zero(3 * mesh.num_points());
    for (Index i = 0; i < mesh.num_points(); ++i) u[3 * i] = (lambda - 1.0) * mesh.points[i].x();
    return u;
  }
};

TEST_F(StepRecorderTest, RecordsTheSeriesAndWritesTheFieldFiles) {
  const CaseConfig cfg = config(uniaxial(0.001));
  const Problem p(cfg);
  RunOutput out(dir_ / "results" / "uniaxial");
  StepRecorder rec(p, out);
  const VecX zero = VecX::Zero(p.system.num_dofs());
  rec.record(0, 0.0, zero, zero, 0, true);
  const VecX u = stretch_x(p.mesh, 1.1);
  rec.record(1, 1.0, u, zero, 3, true);
  const SeriesTable& t = rec.recorder().table();
  EXPECT_EQ(t.last(series_names::kTime), 1.0);
  EXPECT_NEAR(t.last("probe_corner_x"), 0.1 * kL, 1e-15);
  EXPECT_EQ(t.last(series_names::kNewtonIterations), 3.0);
  // The work of the supports on this homogeneous stretch (lateral contraction held) by the
  // trapezoid from rest: 1/2 P11 (l - 1) V, against the stored energy 1/2 (lambda + 2 mu) E11^2 V:
  // their ratio is l (l - 1) / E11 = 2 l / (l + 1).
  const double l = 1.1;
  EXPECT_NEAR(rec.external_work(), 2.0 * l / (l + 1.0) * t.last(series_names::kElasticEnergy),
              1e-9 * rec.external_work());
  rec.close();
  for (const char* f :
       {"timeseries.h5", "displacement.h5", "fields.xdmf", "result.pvd", "vtu/step_00001.vtu"})
    EXPECT_TRUE(fs::exists(out.staging_dir() / f)) << f;
  H5File h5 = H5File::open_read((out.staging_dir() / "timeseries.h5").string());
  EXPECT_EQ(h5.read_double("/series/time").size(), 2u);
}

TEST_F(StepRecorderTest, AnInvertedElementStopsTheRunNamingIt) {
  const CaseConfig cfg = config(uniaxial(0.001));
  const Problem p(cfg);
  RunOutput out(dir_ / "results" / "uniaxial");
  StepRecorder rec(p, out);
  const VecX zero = VecX::Zero(p.system.num_dofs());
  try {
    rec.record(2, 0.5, stretch_x(p.mesh, -1.0), zero, 0, false);
    FAIL() << "an inverted mesh was recorded";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("inverted at t = 0.5 (step 2, volume ratio -1"), std::string::npos) << m;
    EXPECT_NE(m.find("tetrahedron"), std::string::npos) << m;
  }
}

TEST_F(StepRecorderTest, CheckpointRestoresSeriesWorkAndFieldFrames) {
  const CaseConfig cfg = config(uniaxial(0.001));
  const Problem p(cfg);
  const VecX zero = VecX::Zero(p.system.num_dofs());
  CheckpointData d;
  {
    RunOutput out(dir_ / "results" / "a");
    StepRecorder rec(p, out);
    rec.record(0, 0.0, zero, zero, 0, true);
    rec.record(1, 0.5, stretch_x(p.mesh, 1.05), zero, 2, true);
    rec.save(d);
  }
  RunOutput out(dir_ / "results" / "b");
  StepRecorder back(p, out);
  back.restore(d);
  CheckpointData again;
  back.save(again);
  EXPECT_EQ(again.all_doubles(), d.all_doubles());
  EXPECT_EQ(again.all_texts(), d.all_texts());
  EXPECT_EQ(back.recorder().field_frames(), 2);
  // Both continue identically.
  back.record(2, 1.0, stretch_x(p.mesh, 1.1), zero, 2, false);
  EXPECT_EQ(back.recorder().table().series().front().values.size(), 3u);
  EXPECT_TRUE(fs::exists(out.staging_dir() / "vtu" / "step_00001.vtu"));  // replayed frame
}

}  // namespace
}  // namespace tmlab::tm::runner
