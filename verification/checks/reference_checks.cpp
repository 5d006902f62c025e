// Checks against the deal.II reference (compiled to a no-op registration without deal.II).
//
//   reference.same_mesh   tensor-mass and deal.II P1 St VK on the same mesh, shipped case files
//                         (or, with "element": "p2", the fast model's 10-node tets and deal.II P2)
//                         (static and quasi-static viscoelastic, with or without rigid contact bodies):
//                         nodal displacements, reactions and energy differences, and with contact each
//                         body's force, area and active nodes (core result_compare), which must be the
//                         solvers' tolerance
//   reference.p1_vs_p2    tensor-mass P1 on nested box meshes against a deal.II P2 solution on a
//                         reference level, at the vertices both meshes have: nodal discretisation
//                         error, its order, and the P2 reference's own error estimated from P2 on a
//                         coarser level (Richardson with order 3)
//   reference.elastica    the Euler elastica cantilever (issue 12): deal.II Q2 hexes on two meshes against
//                         the exact elastica tip, the fast model's P1 tets (bending locking) on the same
//                         box, and the Newton iteration counts of both under the default line search
//   reference.locking     P1 (tensor-mass) against P2 (deal.II) on the same box mesh for Poisson ratios
//                         towards 0.5 (volumetric locking of linear tets), with P2 on a refined mesh to
//                         show that the reference itself has converged; optionally other elements of the
//                         fast model ("elements": p1_anp, p2, p2_mean_dilatation on hyperelastic_tl)
//                         against the P2 reference on a finer "reference_level"
//
// The box problems are case files: a template in the case directory (verify.json's "template")
// whose selectors use the face groups of make_box_mesh (xmin ... zmax); the check function writes
// the generated meshes into the work directory and sets the template's mesh path. Everything is
// written into ctx.work_dir. Measurements only; the tolerances are in the cases' verify.json.
#include "verification/checks/builtin_checks.hpp"

#include "core/base/format.hpp"

#ifdef TMLAB_HAVE_REFERENCE
#include "verification/checks/check_support.hpp"
#include "verification/checks/elastica.hpp"

#include "core/base/error.hpp"
#include "core/base/stopwatch.hpp"
#include "core/config/case_config.hpp"
#include "core/config/element_kind.hpp"
#include "core/config/fast_model.hpp"
#include "core/io/hdf5_file.hpp"
#include "core/mesh/mesh_generator.hpp"
#include "core/results/result_compare.hpp"
#include "reference_fem/dealii/reference_runner.hpp"
#include "runner/case_runner.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>
#endif

namespace tmlab::verify {

#ifdef TMLAB_HAVE_REFERENCE
namespace {

namespace fs = std::filesystem;

std::string fmt(double v, int digits = 3) { return scientific(v, digits); }

/// A number with up to 6 significant digits and no trailing zeros ("0.499", "0.3"), for names.
std::string short_number(double v) {
  std::ostringstream s;
  s << std::setprecision(6) << v;
  return s.str();
}

/// "12.3 s".
std::string seconds_text(double seconds) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(1) << seconds << " s";
  return s.str();
}
std::string seconds_text(std::chrono::steady_clock::time_point t0) { return seconds_text(seconds_since(t0)); }

tmlab::RunOptions run_options(const CheckContext& ctx) {
  tmlab::RunOptions o;
  o.results_root = (ctx.work_dir / "runs").string();
  o.tmlab_root = ctx.source_root.string();
  o.plots = false;
  return o;
}

/// A case as run here: no field output or plots (only timeseries.h5, displacement.h5, summary).
void quiet_output(CaseConfig& c) {
  c.output.vtu = false;
  c.output.xdmf = false;
  c.output.plots = false;
}

/// The fast model's run of a case: tensor_mass for St VK (the paper's model), hyperelastic_tl (the
/// F-based kernel) for the other laws, which tensor_mass does not have.
tmlab::RunResult run_tensor_mass(const CheckContext& ctx, CaseConfig c) {
  c.model = fast_model_for(c.material.law);
  return tm::run_case(c, run_options(ctx));
}

/// The deal.II run of a case: serial (the harness may run under mpirun; the comparisons are serial
/// runs), Newton tolerance of the case, result directory <case><suffix>.
tmlab::RunResult run_reference(const CheckContext& ctx, const CaseConfig& c, int degree,
                               ref::LinearSolver solver, const std::string& suffix) {
  ref::ReferenceOptions o;
  o.degree = degree;
  o.linear_solver = solver;
  o.newton_rtol = c.solver.rtol;
  o.serial = true;
  o.name_suffix = suffix;
  return ref::run_reference_case(c, run_options(ctx), o);
}

/// The last frame of <dir>/displacement.h5 (vertex values in tmlab node order).
Eigen::VectorXd final_displacement(const std::string& dir) {
  H5File::Dims dims;
  const auto u = H5File::open_read(dir + "/displacement.h5").read_double("/u", &dims);
  if (dims.size() != 2 || dims[0] == 0) throw Error(dir + "/displacement.h5: '/u' has no frames");
  const std::size_t cols = dims[1], last = (dims[0] - 1) * cols;
  Eigen::VectorXd out(static_cast<Eigen::Index>(cols));
  for (std::size_t c = 0; c < cols; ++c) out[static_cast<Eigen::Index>(c)] = u[last + c];
  return out;
}

ref::LinearSolver require_linear_solver(ConfigReader& p) {
  const std::string s = p.get<std::string>("linear_solver", "direct");
  try {
    return ref::parse_linear_solver(s);
  } catch (const Error& e) {
    throw p.error("linear_solver", e.what());
  }
}

// ------------------------------------------------------------------ reference.same_mesh
Measurements same_mesh(const CheckContext& ctx) {
  ConfigReader p = parameters(ctx);
  const auto files = p.require<std::vector<std::string>>("cases");
  if (files.empty()) throw p.error("cases", "must name at least one case file");
  // The fast model's element (default p1: the tensor-mass model against deal.II P1). A quadratic
  // element runs on hyperelastic_tl against deal.II P2 on the same mesh; p1_anp has no counterpart.
  const std::string element_name = p.get<std::string>("element", "p1");
  const auto element = element_kind_from_string(element_name);
  if (!element || *element == ElementKind::P1Anp || *element == ElementKind::P2MeanDilatation)
    throw p.error("element", "must be 'p1' or 'p2' (the elements the deal.II reference has; got '" +
                                 element_name + "')");
  const int degree = is_quadratic(*element) ? 2 : 1;
  p.finish();

  Measurements m;
  double worst_u = 0.0, worst_r = 0.0, worst_w = 0.0;
  // Contact cases (a `contact` section): the contact force, area and active-node count per body.
  bool any_contact = false;
  double worst_f = 0.0, worst_a = 0.0, worst_n = 0.0;
  nlohmann::json rows = nlohmann::json::array();
  for (const std::string& rel : files) {
    const fs::path file = ctx.source_root / rel;
    if (!fs::exists(file)) throw p.error("cases", "no case file '" + rel + "' in the tmlab tree");
    CaseConfig c = tmlab::load_case(file.string(), ctx.source_root.string());
    quiet_output(c);
    const auto t0 = std::chrono::steady_clock::now();
    tmlab::RunResult a;
    if (*element == ElementKind::P1) {
      a = run_tensor_mass(ctx, c);
    } else {
      CaseConfig cf = c;
      cf.model = CaseModel::HyperelasticTL;
      cf.mesh.element = *element;
      a = tm::run_case(cf, run_options(ctx));
    }
    const double t_tm = seconds_since(t0);
    const auto t1 = std::chrono::steady_clock::now();
    const tmlab::RunResult b = run_reference(ctx, c, degree, ref::LinearSolver::Direct, "-reference");
    const double t_ref = seconds_since(t1);
    const nlohmann::json cmp = compare_results(a.dir, b.dir);
    const double du = cmp.at("rel_diff_displacement").get<double>();
    const double dr = cmp.at("rel_diff_reaction").get<double>();
    const double dw = cmp.at("rel_diff_energy").get<double>();
    m.set(c.name + "_rel_diff_displacement", du);
    m.set(c.name + "_rel_diff_reaction", dr);
    m.set(c.name + "_rel_diff_energy", dw);
    worst_u = std::max(worst_u, du);
    worst_r = std::max(worst_r, dr);
    worst_w = std::max(worst_w, dw);
    std::string contact_text;
    if (cmp.contains("rel_diff_contact_force")) {
      any_contact = true;
      const double df = cmp.at("rel_diff_contact_force").get<double>();
      const double da = cmp.at("rel_diff_contact_area").get<double>();
      const double dn = cmp.at("max_diff_active_nodes").get<double>();
      m.set(c.name + "_rel_diff_contact_force", df);
      m.set(c.name + "_rel_diff_contact_area", da);
      m.set(c.name + "_max_diff_active_nodes", dn);
      worst_f = std::max(worst_f, df);
      worst_a = std::max(worst_a, da);
      worst_n = std::max(worst_n, dn);
      contact_text =
          ", contact force " + fmt(df) + ", area " + fmt(da) + ", active nodes differ by " + short_number(dn);
    }
    rows.push_back(
        {{"case", rel}, {"comparison", cmp}, {"tensor_mass_seconds", t_tm}, {"reference_seconds", t_ref}});
    ctx.log << "  " << c.name << ": displacement " << fmt(du) << ", reaction " << fmt(dr) << ", energy "
            << fmt(dw) << contact_text << " (fast " << element_name << " " << seconds_text(t_tm)
            << ", deal.II P" << degree << " " << seconds_text(t_ref) << ")\n";
    m.notes.push_back(c.name + ": " + std::to_string(c.solver.steps) + " steps, Newton rtol " +
                      fmt(c.solver.rtol, 1) + "; max rel. differences displacement " + fmt(du) +
                      ", reaction " + fmt(dr) + ", energy " + fmt(dw) + contact_text);
  }
  if (any_contact) {
    m.set("max_rel_diff_contact_force", worst_f);
    m.set("max_rel_diff_contact_area", worst_a);
    m.set("max_diff_active_nodes", worst_n);
  }
  m.set("max_rel_diff_displacement", worst_u);
  m.set("max_rel_diff_reaction", worst_r);
  m.set("max_rel_diff_energy", worst_w);
  m.data["cases"] = rows;
  return m;
}

// ------------------------------------------------------------------ box problems from a template

/// A box problem: make_box_mesh(0, size, level * cells) and a case template whose selectors use
/// the box's face groups.
struct BoxProblem {
  nlohmann::json templ;  ///< the template case document
  std::string templ_file;
  Vec3 size = Vec3::Zero();
  std::array<int, 3> cells{1, 1, 1};
  Vec3 probe = Vec3::Zero();

  static BoxProblem read(const CheckContext& ctx, ConfigReader& p) {
    BoxProblem b;
    const std::string name = p.require<std::string>("template");
    b.templ_file = (ctx.vcase.dir / name).string();
    if (!fs::exists(b.templ_file)) throw p.error("template", "no file '" + name + "' in the case directory");
    b.templ = ConfigReader::parse_file(b.templ_file);
    const auto size = p.require<std::vector<double>>("size");
    const auto cells = p.require<std::vector<int>>("cells");
    const auto probe = p.require<std::vector<double>>("probe");
    if (size.size() != 3) throw p.error("size", "needs three values (box edge lengths, m)");
    if (cells.size() != 3) throw p.error("cells", "needs three values (cells per level along x, y, z)");
    if (probe.size() != 3) throw p.error("probe", "needs three values (a point, m)");
    for (int i = 0; i < 3; ++i) {
      if (!(size[i] > 0.0)) throw p.error("size", "entries must be > 0");
      if (cells[i] < 1) throw p.error("cells", "entries must be >= 1");
      b.size[i] = size[i];
      b.cells[i] = cells[i];
      b.probe[i] = probe[i];
    }
    return b;
  }

  std::array<int, 3> counts(int level) const {
    return {cells[0] * level, cells[1] * level, cells[2] * level};
  }
  double h(int level) const { return size.x() / (cells[0] * level); }

  /// Writes the level's mesh into the work directory (once) and returns the case for it, with
  /// `material.nu` replaced when nu > 0.
  CaseConfig config(const CheckContext& ctx, int level, double nu = 0.0) const {
    const auto n = counts(level);
    const fs::path mesh_file = ctx.work_dir / ("box_" + std::to_string(n[0]) + "x" + std::to_string(n[1]) +
                                               "x" + std::to_string(n[2]) + ".msh");
    if (!fs::exists(mesh_file))
      write_gmsh22(make_box_mesh(Vec3::Zero(), size, n[0], n[1], n[2]), mesh_file.string());
    nlohmann::json doc = templ;
    std::string name = doc.value("name", std::string("box")) + "-n" + std::to_string(level);
    if (nu > 0.0) {
      doc["material"]["nu"] = nu;
      name += "-nu" + short_number(nu);
    }
    doc["name"] = name;
    doc["mesh"] = {{"file", mesh_file.string()}};
    CaseConfig c = parse_case(doc, templ_file, {ctx.work_dir.string(), ctx.source_root.string()});
    quiet_output(c);
    return c;
  }

  /// Node index of grid vertex (i, j, k) of a level (make_box_mesh numbers x fastest).
  Index node(int level, int i, int j, int k) const {
    const auto n = counts(level);
    return Index(i) + Index(n[0] + 1) * (Index(j) + Index(n[1] + 1) * Index(k));
  }

  /// For each vertex of `coarse`, its index in the mesh of `fine` (fine must be a multiple).
  std::vector<Index> vertex_map(int coarse, int fine) const {
    const int r = fine / coarse;
    const auto n = counts(coarse);
    std::vector<Index> out;
    out.reserve(std::size_t(n[0] + 1) * (n[1] + 1) * (n[2] + 1));
    for (int k = 0; k <= n[2]; ++k)
      for (int j = 0; j <= n[1]; ++j)
        for (int i = 0; i <= n[0]; ++i) out.push_back(node(fine, r * i, r * j, r * k));
    return out;
  }

  /// The grid vertex of a level nearest to the probe point.
  Index probe_node(int level) const {
    const auto n = counts(level);
    std::array<int, 3> ijk{};
    for (int d = 0; d < 3; ++d) ijk[d] = std::clamp(int(std::lround(probe[d] / size[d] * n[d])), 0, n[d]);
    return node(level, ijk[0], ijk[1], ijk[2]);
  }
};

Vec3 at(const Eigen::VectorXd& u, Index node) { return u.segment<3>(3 * node); }

/// Nodal differences of `a` (on mesh level la) against `b` (level lb, a multiple of la) at the
/// vertices of level `set` (la must be a multiple of set): max_v |a - b| / max_v |b| and the RMS
/// version sqrt(sum |a - b|^2 / sum |b|^2).
struct NodalDiff {
  double max_rel = 0.0, rms_rel = 0.0;
  std::array<int, 3> worst{0, 0, 0};  ///< grid indices (i, j, k) of the worst vertex on level `set`
};
NodalDiff nodal_diff(const BoxProblem& box, const Eigen::VectorXd& a, int la, const Eigen::VectorXd& b,
                     int lb, int set) {
  const auto ia = box.vertex_map(set, la), ib = box.vertex_map(set, lb);
  double dmax = 0.0, bmax = 0.0, d2 = 0.0, b2 = 0.0;
  std::size_t worst = 0;
  for (std::size_t v = 0; v < ia.size(); ++v) {
    const Vec3 d = at(a, ia[v]) - at(b, ib[v]);
    if (d.norm() > dmax) worst = v;
    dmax = std::max(dmax, d.norm());
    bmax = std::max(bmax, at(b, ib[v]).norm());
    d2 += d.squaredNorm();
    b2 += at(b, ib[v]).squaredNorm();
  }
  if (!(bmax > 0.0)) throw Error("the reference displacement is zero at every compared vertex (no load?)");
  const auto n = box.counts(set);
  const int w = int(worst);
  return {dmax / bmax,
          std::sqrt(d2 / b2),
          {w % (n[0] + 1), (w / (n[0] + 1)) % (n[1] + 1), w / ((n[0] + 1) * (n[1] + 1))}};
}

std::vector<int> read_levels(ConfigReader& p, const std::string& key) {
  const auto v = p.require<std::vector<int>>(key);
  if (v.size() < 2) throw p.error(key, "needs at least two levels");
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (v[i] < 1) throw p.error(key, "entries must be >= 1");
    if (i > 0 && v[i] % v[i - 1] != 0)
      throw p.error(key, "each level must be a multiple of the previous one (nested meshes)");
    if (i > 0 && v[i] == v[i - 1]) throw p.error(key, "levels must increase");
  }
  return v;
}

// ------------------------------------------------------------------ reference.p1_vs_p2
Measurements p1_vs_p2(const CheckContext& ctx) {
  ConfigReader p = parameters(ctx);
  const BoxProblem box = BoxProblem::read(ctx, p);
  const std::vector<int> levels = read_levels(p, "levels");
  const int ref_level = p.require<int>("reference_level");
  const int check_level = p.require<int>("reference_check_level");
  const ref::LinearSolver solver = require_linear_solver(p);
  p.finish();
  // Every level is a multiple of the coarsest, so the coarsest mesh's vertices are vertices of all
  // meshes; P1 levels finer than the reference are compared at the reference's vertices.
  if (ref_level % levels.front() != 0)
    throw p.error("reference_level", "must be a multiple of the coarsest P1 level");
  for (int l : levels)
    if (l % ref_level != 0 && ref_level % l != 0)
      throw p.error("levels", "each level must divide the reference level or be a multiple of it");
  if (check_level < levels.front() || check_level >= ref_level || ref_level % check_level != 0 ||
      check_level % levels.front() != 0)
    throw p.error("reference_check_level",
                  "must be a coarser level than reference_level that divides it and is a multiple of the "
                  "coarsest P1 level");

  Measurements m;
  const int set = levels.front();
  // The reference: P2 on the reference level, and P2 one level coarser for its own error.
  auto t0 = std::chrono::steady_clock::now();
  const CaseConfig ref_cfg = box.config(ctx, ref_level);
  const Eigen::VectorXd u_ref = final_displacement(run_reference(ctx, ref_cfg, 2, solver, "-p2").dir);
  ctx.log << "  deal.II P2, level " << ref_level << " (" << box.counts(ref_level)[0] << "x"
          << box.counts(ref_level)[1] << "x" << box.counts(ref_level)[2] << " cells): " << seconds_text(t0)
          << "\n";
  t0 = std::chrono::steady_clock::now();
  const Eigen::VectorXd u_chk =
      final_displacement(run_reference(ctx, box.config(ctx, check_level), 2, solver, "-p2").dir);
  ctx.log << "  deal.II P2, level " << check_level << ": " << seconds_text(t0) << "\n";
  const NodalDiff p2_diff = nodal_diff(box, u_chk, check_level, u_ref, ref_level, set);

  Series nodal, rms, probe;
  nodal.x_label = rms.x_label = probe.x_label = "h [m]";
  nodal.y_label = "max nodal error / max |u_ref| (coarsest vertices)";
  rms.y_label = "RMS nodal error / RMS u_ref (vertices common to P1 and P2)";
  probe.y_label = "|u_h - u_ref| / |u_ref| at the probe";
  const Index probe_ref = box.probe_node(ref_level);
  const Vec3 u_probe_ref = at(u_ref, probe_ref);
  const Vec3 u_probe_chk = at(u_chk, box.probe_node(check_level));
  // How much the finest P1 errors move when the reference is the coarser P2 solution: for a
  // reference converging at any order >= 1 this bounds what the reference's own error does to them.
  double sensitivity = 0.0;
  nlohmann::json rows = nlohmann::json::array();
  for (int level : levels) {
    t0 = std::chrono::steady_clock::now();
    const Eigen::VectorXd u = final_displacement(run_tensor_mass(ctx, box.config(ctx, level)).dir);
    const NodalDiff fixed = nodal_diff(box, u, level, u_ref, ref_level, set);
    const NodalDiff all = nodal_diff(box, u, level, u_ref, ref_level, std::min(level, ref_level));
    const Index pn = box.probe_node(level);
    const double pe = (at(u, pn) - u_probe_ref).norm() / u_probe_ref.norm();
    const double fixed_chk = nodal_diff(box, u, level, u_chk, check_level, set).max_rel;
    const double pe_chk = (at(u, pn) - u_probe_chk).norm() / u_probe_chk.norm();
    sensitivity = std::max(std::abs(fixed_chk - fixed.max_rel) / fixed.max_rel, std::abs(pe_chk - pe) / pe);
    const double h = box.h(level);
    nodal.x.push_back(h);
    nodal.y.push_back(fixed.max_rel);
    rms.x.push_back(h);
    rms.y.push_back(all.rms_rel);
    probe.x.push_back(h);
    probe.y.push_back(pe);
    rows.push_back({{"level", level},
                    {"h_m", h},
                    {"max_nodal_error", fixed.max_rel},
                    {"rms_nodal_error", all.rms_rel},
                    {"probe_error", pe},
                    {"max_nodal_error_against_coarser_p2", fixed_chk},
                    {"probe_error_against_coarser_p2", pe_chk},
                    {"probe_displacement_m", {at(u, pn).x(), at(u, pn).y(), at(u, pn).z()}}});
    ctx.log << "  P1 level " << level << ": max nodal " << fmt(fixed.max_rel) << ", RMS " << fmt(all.rms_rel)
            << ", probe " << fmt(pe) << " (" << seconds_text(t0) << ")\n";
  }
  m.series["nodal_error"] = nodal;
  m.series["rms_error"] = rms;
  m.series["probe_error"] = probe;
  m.set("finest_nodal_error", nodal.y.back());
  m.set("p2_refinement_diff", p2_diff.max_rel);
  m.set("reference_sensitivity", sensitivity);
  m.set("probe_displacement_reference_m", u_probe_ref.norm());
  m.data["levels"] = rows;
  m.data["probe_reference_m"] = {u_probe_ref.x(), u_probe_ref.y(), u_probe_ref.z()};
  auto where = [&](const NodalDiff& d) {
    const auto n = box.counts(set);
    std::ostringstream o;
    o << "(" << box.size.x() * d.worst[0] / n[0] << ", " << box.size.y() * d.worst[1] / n[1] << ", "
      << box.size.z() * d.worst[2] / n[2] << ") m";
    return o.str();
  };
  m.notes.push_back("P2 reference on level " + std::to_string(ref_level) +
                    " (h = " + fmt(box.h(ref_level), 2) + " m); P2 on level " + std::to_string(check_level) +
                    " differs from it by " + fmt(p2_diff.max_rel) + " (max over the coarsest vertices, at " +
                    where(p2_diff) + "); against it the finest P1 errors change by " + fmt(sensitivity) +
                    " (relative)");
  m.notes.push_back("probe displacement (reference) " + fmt(u_probe_ref.norm()) +
                    " m at the vertex nearest to (" + fmt(box.probe.x(), 2) + ", " + fmt(box.probe.y(), 2) +
                    ", " + fmt(box.probe.z(), 2) + ")");
  return m;
}

// ------------------------------------------------------------------ reference.elastica
/// The tip centre's displacement: the mean of the two tip probes (tip_a, tip_b: the corners on the
/// bending axis's two faces, whose mean is the centre for a rigidly rotating section).
Vec3 tip_displacement(const nlohmann::json& summary) {
  const auto& p = summary.at("probes");
  Vec3 u = Vec3::Zero();
  for (const char* name : {"tip_a", "tip_b"}) {
    const auto& d = p.at(name).at("displacement_m");
    u += Vec3(d.at(0).get<double>(), d.at(1).get<double>(), d.at(2).get<double>());
  }
  return 0.5 * u;
}

Measurements elastica(const CheckContext& ctx) {
  ConfigReader p = parameters(ctx);
  const BoxProblem box = BoxProblem::read(ctx, p);
  const double k = p.positive("load_parameter");
  const auto hex_cells = p.require<std::vector<int>>("hex_cells_along");
  p.finish();
  if (hex_cells.size() < 2)
    throw p.error("hex_cells_along", "needs at least two meshes (a convergence check)");

  // Geometry: bending thickness h along x, width b along y, length L along z; load in -x.
  const double h = box.size.x(), b = box.size.y(), L = box.size.z();
  const double E = box.templ.at("material").at("E").get<double>();
  const double EI = E * b * h * h * h / 12.0, P = k * EI / (L * L);
  const ElasticaTip exact = elastica_cantilever_tip(k);
  ctx.log << "  elastica: P L^2/EI = " << k << ", tip rotation " << exact.theta0 * 180.0 / std::acos(-1.0)
          << " deg, deflection " << exact.transverse << " L, shortening " << 1.0 - exact.axial << " L\n";

  auto config = [&](const std::string& suffix) {
    CaseConfig c = box.config(ctx, 1);
    c.name = "elastica" + suffix;
    for (auto& l : c.loads) l.vector = Vec3(-P, 0, 0);
    return c;
  };
  // Relative tip errors against the elastica, per component, over L.
  auto errors = [&](const Vec3& u) {
    return std::array<double, 2>{std::abs(-u.x() / L - exact.transverse),
                                 std::abs(-u.z() / L - (1.0 - exact.axial))};
  };

  Measurements m;
  m.set("elastica_tip_rotation_deg", exact.theta0 * 180.0 / std::acos(-1.0));
  m.set("elastica_deflection_over_L", exact.transverse);
  m.set("elastica_shortening_over_L", 1.0 - exact.axial);

  // The fast model: P1 tets of the box (6 per cell).
  const auto t0 = std::chrono::steady_clock::now();
  const tmlab::RunResult fast = run_tensor_mass(ctx, config("-p1"));
  const Vec3 u1 = tip_displacement(fast.summary);
  const auto& fs = fast.summary.at("solver");
  const int steps = fs.at("load_steps").get<int>();
  m.set("p1_deflection_ratio", -u1.x() / L / exact.transverse);
  m.set("p1_newton_iterations", fs.at("newton_iterations").get<double>());
  m.set("p1_newton_iterations_per_step", fs.at("newton_iterations").get<double>() / steps);
  m.set("p1_max_iterations_in_a_step", fs.at("newton").at("max_iterations_in_a_step").get<double>());
  m.set("p1_cutbacks", fs.at("cutbacks").get<double>());
  ctx.log << "  P1 tets (" << 6 * box.cells[0] * box.cells[1] * box.cells[2] << "): deflection "
          << fmt(-u1.x() / L) << " L (" << fmt(-u1.x() / L / exact.transverse) << " of the elastica), "
          << fs.at("newton_iterations").get<long>() << " Newton iterations, " << fs.at("cutbacks").get<long>()
          << " cut-backs (" << seconds_text(t0) << ")\n";

  // The reference: Q2 hexes, 1 x 1 x n cells, for each n.
  nlohmann::json rows = nlohmann::json::array();
  std::vector<double> err;
  Vec3 u_prev = Vec3::Zero();
  double change = 0.0;
  for (std::size_t i = 0; i < hex_cells.size(); ++i) {
    const int n = hex_cells[i];
    if (n < 1 || (i > 0 && n <= hex_cells[i - 1]))
      throw p.error("hex_cells_along", "must increase from >= 1");
    const auto t1 = std::chrono::steady_clock::now();
    ref::ReferenceOptions o;
    o.degree = 2;
    o.cells = ref::CellType::Hex;
    o.hex_subdivisions = {1u, 1u, unsigned(n)};
    o.newton_rtol = 1e-10;
    o.serial = true;
    o.name_suffix = "-q2-" + std::to_string(n);
    const tmlab::RunResult r = ref::run_reference_case(config(""), run_options(ctx), o);
    const Vec3 u = tip_displacement(r.summary);
    const auto e = errors(u);
    const auto& rs = r.summary.at("solver");
    const double its = rs.at("newton_iterations").get<double>(), cuts = rs.at("cutbacks").get<double>();
    err.push_back(std::max(e[0], e[1]));
    if (i > 0) change = (u - u_prev).norm() / L;
    u_prev = u;
    const std::string tag = "q2_" + std::to_string(n);
    m.set(tag + "_error", err.back());
    m.set(tag + "_newton_iterations_per_step", its / steps);
    m.set(tag + "_cutbacks", cuts);
    rows.push_back({{"cells_along", n},
                    {"deflection_over_L", -u.x() / L},
                    {"shortening_over_L", -u.z() / L},
                    {"error_deflection", e[0]},
                    {"error_shortening", e[1]},
                    {"newton_iterations", its},
                    {"cutbacks", cuts}});
    ctx.log << "  Q2 hexes 1 x 1 x " << n << ": deflection " << fmt(-u.x() / L) << " L, shortening "
            << fmt(-u.z() / L) << " L, error " << fmt(err.back()) << ", " << long(its)
            << " Newton iterations, " << long(cuts) << " cut-backs (" << seconds_text(t1) << ")\n";
    m.notes.push_back("Q2 hexes 1 x 1 x " + std::to_string(n) + ": tip error " + fmt(err.back()) + " L, " +
                      std::to_string(long(its)) + " Newton iterations in " + std::to_string(steps) +
                      " steps");
  }
  m.set("q2_error_finest", err.back());
  m.set("q2_refinement_change", change);
  m.set("q2_newton_iterations_per_step", rows.back().at("newton_iterations").get<double>() / steps);
  double q2_cuts = 0.0;
  for (const auto& r : rows) q2_cuts += r.at("cutbacks").get<double>();
  m.set("q2_cutbacks", q2_cuts);
  m.data["q2_meshes"] = rows;
  m.notes.push_back("P1 tets: the tip deflects " + fmt(-u1.x() / L / exact.transverse) +
                    " of the elastica's (bending locking of linear tets, one element through the thickness)");
  return m;
}

// ------------------------------------------------------------------ reference.locking
Measurements locking(const CheckContext& ctx) {
  ConfigReader p = parameters(ctx);
  const BoxProblem box = BoxProblem::read(ctx, p);
  const int level = p.require<int>("level");
  const int fine = p.require<int>("p2_check_level");
  const auto nus = p.require<std::vector<double>>("poisson_ratios");
  const ref::LinearSolver solver = require_linear_solver(p);
  // The fast model's elements (default: p1, the tensor-mass model) and the level of the deal.II P2
  // reference (default: the elements' own mesh).
  const auto names = p.get<std::vector<std::string>>("elements", {"p1"});
  const int ref_level = p.get<int>("reference_level", level);
  p.finish();
  if (level < 1) throw p.error("level", "must be >= 1");
  if (ref_level < level || ref_level % level != 0)
    throw p.error("reference_level", "must be 'level' or a multiple of it");
  if (fine <= ref_level || fine % level != 0)
    throw p.error("p2_check_level", "must be a multiple of 'level' above 'reference_level'");
  if (nus.size() < 2) throw p.error("poisson_ratios", "needs at least two values");
  for (std::size_t i = 0; i < nus.size(); ++i) {
    if (!(nus[i] > 0.0 && nus[i] < 0.5)) throw p.error("poisson_ratios", "entries must be in (0, 0.5)");
    if (i > 0 && nus[i] <= nus[i - 1]) throw p.error("poisson_ratios", "must increase");
  }
  if (names.empty()) throw p.error("elements", "must name at least one element");
  std::vector<ElementKind> kinds;
  for (const auto& n : names) {
    const auto e = element_kind_from_string(n);
    if (!e) throw p.error("elements", "unknown element '" + n + "' (p1 | p1_anp | p2 | p2_mean_dilatation)");
    kinds.push_back(*e);
  }

  Measurements m;
  nlohmann::json rows = nlohmann::json::array();
  std::vector<std::vector<double>> err(names.size()), rms(names.size());
  std::vector<double> p2_probe, p2_over(names.size(), 0.0), p2_over_rms(names.size(), 0.0);
  double p2_worst = 0.0;
  for (double nu : nus) {
    const auto t0 = std::chrono::steady_clock::now();
    const CaseConfig c = box.config(ctx, level, nu);
    const Eigen::VectorXd u2 =
        final_displacement(run_reference(ctx, box.config(ctx, ref_level, nu), 2, solver, "-p2").dir);
    const Eigen::VectorXd u2f =
        final_displacement(run_reference(ctx, box.config(ctx, fine, nu), 2, solver, "-p2").dir);
    const NodalDiff e2 = nodal_diff(box, u2, ref_level, u2f, fine, level);
    const Vec3 w2 = at(u2, box.probe_node(ref_level)), w2f = at(u2f, box.probe_node(fine));
    const std::string tag = "nu" + short_number(nu);
    m.set("p2_refinement_diff_" + tag, e2.max_rel);
    m.set("p2_refinement_rms_diff_" + tag, e2.rms_rel);
    p2_probe.push_back(w2f.norm());
    p2_worst = std::max(p2_worst, e2.max_rel);
    const double lambda_over_mu = 2.0 * nu / (1.0 - 2.0 * nu);
    nlohmann::json row = {{"nu", nu},
                          {"lambda_over_mu", lambda_over_mu},
                          {"p2_refinement_diff", e2.max_rel},
                          {"probe_p2_m", w2.norm()},
                          {"probe_p2_refined_m", w2f.norm()}};
    std::string note = "nu = " + short_number(nu) + " (lambda/mu = " + fmt(lambda_over_mu, 2) + "):";
    for (std::size_t k = 0; k < names.size(); ++k) {
      Eigen::VectorXd u1;
      if (kinds[k] == ElementKind::P1) {
        u1 = final_displacement(run_tensor_mass(ctx, c).dir);
      } else {
        CaseConfig ce = c;
        ce.name += "-" + names[k];
        ce.model = CaseModel::HyperelasticTL;
        ce.mesh.element = kinds[k];
        u1 = final_displacement(tm::run_case(ce, run_options(ctx)).dir);
      }
      const NodalDiff e1 = nodal_diff(box, u1, level, u2, ref_level, level);
      const Vec3 w1 = at(u1, box.probe_node(level));
      const double deflection_ratio = w1.norm() / w2.norm();
      const std::string& el = names[k];
      m.set(el + "_error_" + tag, e1.max_rel);
      m.set(el + "_rms_error_" + tag, e1.rms_rel);
      m.set(el + "_probe_ratio_" + tag, deflection_ratio);
      err[k].push_back(e1.max_rel);
      rms[k].push_back(e1.rms_rel);
      p2_over[k] = std::max(p2_over[k], e2.max_rel / e1.max_rel);
      p2_over_rms[k] = std::max(p2_over_rms[k], e2.rms_rel / e1.rms_rel);
      row[el + "_max_nodal_error"] = e1.max_rel;
      row[el + "_rms_nodal_error"] = e1.rms_rel;
      row[el + "_over_p2_probe_displacement"] = deflection_ratio;
      row["probe_" + el + "_m"] = w1.norm();
      note += " " + el + " error " + fmt(e1.max_rel) + " (RMS " + fmt(e1.rms_rel) + ", probe ratio " +
              fmt(deflection_ratio) + ");";
    }
    rows.push_back(row);
    ctx.log << "  " << note << " P2 vs P2 refined " << fmt(e2.max_rel) << " (" << seconds_text(t0) << ")\n";
    m.notes.push_back(note + " P2 reference vs P2 refined " + fmt(e2.max_rel));
  }
  for (std::size_t k = 0; k < names.size(); ++k) {
    const std::string& el = names[k];
    m.set(el + "_locking_ratio", err[k].back() / err[k].front());
    m.set(el + "_rms_locking_ratio", rms[k].back() / rms[k].front());
    for (std::size_t i = 1; i < nus.size(); ++i) {
      const std::string tag = "nu" + short_number(nus[i]);
      m.set(el + "_locking_ratio_" + tag, err[k][i] / err[k].front());
      m.set(el + "_rms_locking_ratio_" + tag, rms[k][i] / rms[k].front());
    }
    m.set("p2_rms_diff_over_" + el + "_rms_error_max", p2_over_rms[k]);
    double growth = 1e300;
    for (std::size_t i = 1; i < err[k].size(); ++i) growth = std::min(growth, err[k][i] / err[k][i - 1]);
    m.set(el + "_error_min_growth", growth);
    m.set(el + "_error_last", err[k].back());
    m.set("p2_diff_over_" + el + "_error_max", p2_over[k]);
  }
  m.set("locking_ratio", err.front().back() / err.front().front());
  const auto [lo, hi] = std::minmax_element(p2_probe.begin(), p2_probe.end());
  m.set("reference_probe_variation", (*hi - *lo) / *lo);
  m.set("p2_refinement_diff_max", p2_worst);
  m.data["poisson_ratios"] = rows;
  m.notes.push_back("elements on level " + std::to_string(level) + ", deal.II P2 reference on level " +
                    std::to_string(ref_level) + ", its check on level " + std::to_string(fine));
  return m;
}

}  // namespace
#endif  // TMLAB_HAVE_REFERENCE

void register_reference_checks([[maybe_unused]] CheckRegistry& registry) {
#ifdef TMLAB_HAVE_REFERENCE
  registry.add("reference.same_mesh", same_mesh);
  registry.add("reference.p1_vs_p2", p1_vs_p2);
  registry.add("reference.locking", locking);
  registry.add("reference.elastica", elastica);
#endif
}

}  // namespace tmlab::verify
