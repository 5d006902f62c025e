// tmlab_reference: runs one case file with the deal.II reference solver (docs/reference-fem.md).
// --degree defaults to the case's element's (2 for mesh.element p2 and p2_mean_dilatation, whose F-bar
// form the reference then runs; 1 otherwise).
//   tmlab_reference CASE.json [--degree 1|2] [--law stvk|neo_hookean|yeoh] [--results DIR]
//                   [--solver direct|direct_klu|cg_amg] [--cells tet|hex] [--hex NX,NY,NZ] [--rtol R]
//                   [--time-integration fixed_step|ida] [--ida-rtol R] [--ida-atol A] [--quiet]
// Works under `mpirun -np N`: every rank runs the case, rank 0 writes the result directory.
#include "core/config/case_config.hpp"
#include "core/config/element_kind.hpp"
#include "core/io/hdf5_file.hpp"
#include "core/results/run_output.hpp"
#include "reference_fem/dealii/reference_runner.hpp"

#include <cstdio>
#include <exception>
#include <iostream>
#include <string>

namespace {
int usage(const char* msg) {
  if (tmlab::ref::MpiSession::rank() == 0)
    std::cerr
        << "tmlab_reference: " << msg << "\n"
        << "usage: tmlab_reference CASE.json [--degree 1|2] [--law stvk|neo_hookean|yeoh] [--results DIR]\n"
           "                       [--solver direct|direct_klu|cg_amg] [--cells tet|hex] [--hex NX,NY,NZ] "
           "[--rtol R]\n"
           "                       [--time-integration fixed_step|ida] [--ida-rtol R] [--ida-atol A] "
           "[--quiet]\n";
  return 2;
}
}  // namespace

int main(int argc, char** argv) {
  tmlab::H5File::skip_library_cleanup_at_exit();  // a failed write (full disk) must not loop at exit
  tmlab::ref::MpiSession mpi(argc, argv);
  std::string case_file;
  tmlab::ref::ReferenceOptions ro;
  tmlab::RunOptions opt;
  opt.results_root = "results";
  opt.tmlab_root = TMLAB_SOURCE_DIR;
  opt.command_line = tmlab::command_line(argc, argv);
  opt.plots = false;
  bool quiet = false;
  bool degree_given = false;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      auto value = [&]() -> std::string {
        if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
        return argv[++i];
      };
      if (a == "--degree") {
        ro.degree = std::stoi(value());
        degree_given = true;
      } else if (a == "--law")
        ro.law = tmlab::ref::parse_law(value(), "--law");
      else if (a == "--results")
        opt.results_root = value();
      else if (a == "--solver")
        ro.linear_solver = tmlab::ref::parse_linear_solver(value(), "--solver");
      else if (a == "--cells")
        ro.cells = tmlab::ref::parse_cell_type(value(), "--cells");
      else if (a == "--rtol")
        ro.newton_rtol = std::stod(value());
      else if (a == "--time-integration")
        ro.time_integration = tmlab::ref::parse_time_integration(value(), "--time-integration");
      else if (a == "--ida-rtol")
        ro.ida_rtol = std::stod(value());
      else if (a == "--ida-atol")
        ro.ida_atol = std::stod(value());
      else if (a == "--hex") {
        const std::string v = value();
        if (std::sscanf(v.c_str(), "%u,%u,%u", &ro.hex_subdivisions[0], &ro.hex_subdivisions[1],
                        &ro.hex_subdivisions[2]) != 3)
          throw std::invalid_argument("--hex needs NX,NY,NZ");
      } else if (a == "--quiet")
        quiet = true;
      else if (!a.empty() && a[0] == '-')
        throw std::invalid_argument("unknown option " + a);
      else if (case_file.empty())
        case_file = a;
      else
        throw std::invalid_argument("more than one case file");
    }
    if (case_file.empty()) return usage("no case file given");
  } catch (const std::exception& e) {
    return usage(e.what());
  }
  opt.log = quiet ? nullptr : &std::cout;
  try {
    const tmlab::CaseConfig cfg = tmlab::load_case(case_file, TMLAB_SOURCE_DIR);
    if (!degree_given) ro.degree = tmlab::is_quadratic(cfg.mesh.element) ? 2 : 1;
    const auto r = tmlab::ref::run_reference_case(cfg, opt, ro);
    if (tmlab::ref::MpiSession::rank() == 0 && !quiet)
      std::cout << "results     " << r.dir
                << "/ (summary.json, timeseries.h5, displacement.h5, result.pvd)\n";
  } catch (const std::exception& e) {
    std::cerr << "tmlab_reference: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
