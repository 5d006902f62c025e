// (4) MPI: `mpirun -np 2` reproduces the serial answer. Every rank runs the case distributed over
// MPI_COMM_WORLD; rank 0 then runs it alone (ReferenceOptions::serial) and compares the nodal
// displacements (displacement.h5, tmlab node order). Registered with mpirun in CMakeLists.txt.
#include "core/base/error.hpp"
#include "core/io/hdf5_file.hpp"
#include "reference_fem/dealii/reference_runner.hpp"

#include <gtest/gtest.h>
#include <mpi.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

namespace tmlab::ref {
namespace {

namespace fs = std::filesystem;

/// One temporary directory for all ranks (rank 0 picks it).
fs::path shared_dir(const std::string& test) {
  char buf[512] = {0};
  if (MpiSession::rank() == 0) {
    const std::string d =
        (fs::temp_directory_path() / ("tmlab_refmpi_" + std::to_string(::getpid()) + "_" + test)).string();
    std::snprintf(buf, sizeof buf, "%s", d.c_str());
    fs::remove_all(d);
    fs::create_directories(d);
  }
  MPI_Bcast(buf, sizeof buf, MPI_CHAR, 0, MPI_COMM_WORLD);
  return buf;
}

double max_rel_diff(const std::string& a, const std::string& b) {
  H5File::Dims da, db;
  const auto ua = H5File::open_read(a + "/displacement.h5").read_double("/u", &da);
  const auto ub = H5File::open_read(b + "/displacement.h5").read_double("/u", &db);
  EXPECT_EQ(da, db);
  double worst = 0.0;
  for (std::size_t f = 0; f < da[0]; ++f) {
    double d2 = 0.0, n2 = 0.0;
    for (std::size_t i = 0; i < da[1]; ++i) {
      const double x = ua[f * da[1] + i], y = ub[f * da[1] + i];
      d2 += (x - y) * (x - y), n2 += y * y;
    }
    worst = std::max(worst, n2 > 0 ? std::sqrt(d2 / n2) : std::sqrt(d2));
  }
  return worst;
}

/// Runs `cfg` on all ranks with `parallel`, then on rank 0 alone with `serial`; returns the
/// difference on rank 0 (0 elsewhere).
double parallel_vs_serial(const CaseConfig& cfg, ReferenceOptions parallel, ReferenceOptions serial,
                          const std::string& test) {
  EXPECT_EQ(MpiSession::size(), 2) << "run under mpirun -np 2";
  const fs::path dir = shared_dir(test);
  tmlab::RunOptions o;
  o.results_root = (dir / "results").string();
  o.plots = false;
  parallel.name_suffix = "-np" + std::to_string(MpiSession::size());
  const auto a = run_reference_case(cfg, o, parallel);
  EXPECT_EQ(a.summary["discretisation"]["mpi_ranks"].get<int>(), MpiSession::size());
  double d = 0.0;
  if (MpiSession::rank() == 0) {
    serial.serial = true;
    serial.name_suffix = "-serial";
    const auto b = run_reference_case(cfg, o, serial);
    EXPECT_EQ(b.summary["discretisation"]["mpi_ranks"].get<int>(), 1);
    d = max_rel_diff(a.dir, b.dir);
    std::printf("[ measured ] %s: np=2 vs serial, max relative nodal difference %.3e\n", test.c_str(), d);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  if (MpiSession::rank() == 0 && !::testing::Test::HasFailure()) fs::remove_all(dir);
  return d;
}

CaseConfig cube_case(bool viscoelastic, const std::string& mesh = "meshes/cube_n8.msh") {
  nlohmann::json j = nlohmann::json::parse(R"({
    "name": "cube-mpi",
    "mesh": {"file": "meshes/cube_n8.msh", "scale": 0.01},
    "material": {"E": 10000, "nu": 0.4, "density": 1000},
    "boundary": [{"name": "base", "nodes": {"group": "zmin"}}],
    "loads": [
      {"type": "gravity", "acceleration": [0, 0, -9.81], "function": {"type": "ramp", "t0": 0, "t1": 1}},
      {"type": "pressure", "faces": {"group": "zmax"}, "pressure": 300, "function": {"type": "ramp", "t0": 0, "t1": 1}},
      {"type": "pressure", "faces": {"group": "xmax"}, "pressure": 150, "function": {"type": "ramp", "t0": 0, "t1": 1}}
    ],
    "solver": {"type": "static", "steps": 3},
    "output": {"probes": [{"name": "corner", "point": [0.01, 0.01, 0.01]}]}
  })");
  j["mesh"]["file"] = mesh;
  if (viscoelastic) {
    j["material"]["viscoelastic"] = {{"scheme", "objective"},
                                     {"relaxation", "deviatoric"},
                                     {"prony", {{"terms", {{{"weight", 1.0}, {"tau", 0.3}}}}}}};
    j["solver"]["t_end"] = 2.0;
    j["solver"]["steps"] = 6;
  }
  return parse_case(j, "<mpi test>", {TMLAB_SOURCE_DIR});
}

TEST(ReferenceMpi, LiverP1DirectReproducesSerial) {
  const CaseConfig c = load_case(std::string(TMLAB_SOURCE_DIR) + "/cases/liver-probe.json", TMLAB_SOURCE_DIR);
  EXPECT_LE(parallel_vs_serial(c, {}, {}, "liver_p1"), 1e-12);
}

TEST(ReferenceMpi, CubeP2CgAmgReproducesSerialDirect) {
  ReferenceOptions par, ser;
  par.degree = ser.degree = 2;
  par.linear_solver = LinearSolver::CgAmg;
  EXPECT_LE(parallel_vs_serial(cube_case(false, "meshes/cube_n4.msh"), par, ser, "cube_p2_amg"), 1e-8);
}

TEST(ReferenceMpi, ViscoelasticCubeReproducesSerial) {
  EXPECT_LE(parallel_vs_serial(cube_case(true), {}, {}, "cube_visco"), 1e-12);
}

TEST(ReferenceMpi, IdaTimeIntegrationRefusesTwoRanksAndRunsWithTheSerialOption) {
  const fs::path dir = shared_dir("ida");
  tmlab::RunOptions o;
  o.results_root = (dir / "results").string();
  o.plots = false;
  ReferenceOptions ida;
  ida.time_integration = TimeIntegration::Ida;
  try {
    run_reference_case(cube_case(true), o, ida);
    ADD_FAILURE() << "IDA accepted two ranks";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("one MPI rank"), std::string::npos) << e.what();
  }
  if (MpiSession::rank() == 0) {
    ida.serial = true;
    const auto r = run_reference_case(cube_case(true), o, ida);
    EXPECT_EQ(r.summary["solver"]["time_integration"], "ida");
    EXPECT_GT(r.summary["solver"]["ida"]["steps"].get<long>(), 0);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  if (MpiSession::rank() == 0 && !::testing::Test::HasFailure()) fs::remove_all(dir);
}

}  // namespace
}  // namespace tmlab::ref
