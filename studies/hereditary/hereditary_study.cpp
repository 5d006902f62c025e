#include "studies/hereditary/hereditary_study.hpp"

#include "core/base/format.hpp"

#include "core/base/error.hpp"
#include "core/config/case_config.hpp"
#include "core/mesh/mesh_ops.hpp"
#include "runner/case_runner.hpp"
#include "studies/common/liver_problem.hpp"
#include "studies/paper/paper_experiments.hpp"
#include "tensormass/solvers/static_solver.hpp"
#include "tensormass/system/external_loads.hpp"
#include "tensormass/system/lumped_mass.hpp"
#include "tensormass/system/mechanical_system.hpp"
#include "tensormass/viscoelastic/hereditary_integral.hpp"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

namespace tmlab::tm {

namespace {

using Integ = ViscoelasticOptions::Integration;
constexpr double kPi = 3.14159265358979323846;

std::string fmt(double v) { return significant(v, 6); }

/// p(eps) = (1 + eps)(eps + eps^2/2): 1-D St VK nominal stress / E_inf, and its derivative.
double stvk_stress(double e) { return (1.0 + e) * (e + 0.5 * e * e); }
double stvk_stiffness(double e) { return 1.0 + 3.0 * e + 1.5 * e * e; }

}  // namespace

// ---------------------------------------------------------------------------------- histories

DriverHistory::DriverHistory(std::string name, Kind kind, DriverLaw law, double strain, double t_end)
    : name_(std::move(name)), kind_(kind), law_(law), strain_(strain), t_end_(t_end) {}

DriverHistory DriverHistory::ramp_hold(std::string name, double strain, double ramp_time, double t_end,
                                       DriverLaw law) {
  if (!(ramp_time > 0.0) || !(t_end > 0.0))
    throw Error("hereditary history '" + name + "': ramp time and end time must be > 0 (got " +
                fmt(ramp_time) + ", " + fmt(t_end) + ")");
  DriverHistory h(std::move(name), Kind::RampHold, law, strain, t_end);
  h.ramp_ = ramp_time;
  if (ramp_time <= t_end) h.kinks_.push_back(ramp_time);
  return h;
}

DriverHistory DriverHistory::sine(std::string name, double strain, double omega, double t_end,
                                  DriverLaw law) {
  if (!(omega > 0.0) || !(t_end > 0.0))
    throw Error("hereditary history '" + name + "': omega and end time must be > 0 (got " + fmt(omega) +
                ", " + fmt(t_end) + ")");
  DriverHistory h(std::move(name), Kind::Sine, law, strain, t_end);
  h.omega_ = {omega};
  h.phase_ = {0.0};
  h.weight_ = {1.0};
  h.omega_max_ = omega;
  return h;
}

DriverHistory DriverHistory::random(std::string name, double strain, std::uint64_t seed, int terms,
                                    double omega_min, double omega_max, double t_end, DriverLaw law) {
  if (terms < 1 || !(omega_min > 0.0) || !(omega_max >= omega_min) || !(t_end > 0.0))
    throw Error("hereditary history '" + name +
                "': need terms >= 1, 0 < omega_min <= omega_max and t_end > 0");
  DriverHistory h(std::move(name), Kind::Random, law, strain, t_end);
  h.seed_ = seed;
  // Drawn from the raw 64-bit stream (std::mt19937_64 is specified exactly; the <random>
  // distributions are not), so a seed gives the same history with every standard library.
  std::mt19937_64 gen(seed);
  auto uniform = [&gen]() { return static_cast<double>(gen() >> 11) * 0x1.0p-53; };
  double wsum = 0.0;
  for (int k = 0; k < terms; ++k) {
    const double w = std::exp(std::log(omega_min) + uniform() * (std::log(omega_max) - std::log(omega_min)));
    h.omega_.push_back(w);
    h.phase_.push_back(2.0 * kPi * uniform());
    h.weight_.push_back(0.5 + 0.5 * uniform());
    wsum += h.weight_.back();
    h.omega_max_ = std::max(h.omega_max_, w);
  }
  for (double& w : h.weight_) w /= wsum;
  return h;
}

double DriverHistory::strain(double t) const {
  if (kind_ == Kind::RampHold) return strain_ * std::min(t / ramp_, 1.0);
  double s = 0.0;
  for (std::size_t k = 0; k < omega_.size(); ++k)
    s += weight_[k] * (std::sin(omega_[k] * t + phase_[k]) - std::sin(phase_[k]));
  return strain_ * s;
}

double DriverHistory::strain_rate(double t) const {
  if (kind_ == Kind::RampHold) return t < ramp_ ? strain_ / ramp_ : 0.0;
  double s = 0.0;
  for (std::size_t k = 0; k < omega_.size(); ++k)
    s += weight_[k] * omega_[k] * std::cos(omega_[k] * t + phase_[k]);
  return strain_ * s;
}

double DriverHistory::value(double t) const {
  const double e = strain(t);
  return law_ == DriverLaw::Linear ? e : stvk_stress(e);
}

double DriverHistory::rate(double t) const {
  const double r = strain_rate(t);
  return law_ == DriverLaw::Linear ? r : stvk_stiffness(strain(t)) * r;
}

nlohmann::json DriverHistory::describe() const {
  nlohmann::json j = {{"name", name_},
                      {"strain_amplitude", strain_},
                      {"t_end", t_end_},
                      {"law", law_ == DriverLaw::Linear ? "linear" : "stvk_1d"}};
  if (kind_ == Kind::RampHold) {
    j["kind"] = "ramp_hold";
    j["ramp_time"] = ramp_;
  } else {
    j["kind"] = kind_ == Kind::Sine ? "sine" : "random";
    j["omega"] = omega_;
    j["phase"] = phase_;
    j["weight"] = weight_;
    if (kind_ == Kind::Random) j["seed"] = seed_;
  }
  return j;
}

int steps_to_cover(const DriverHistory& x, double dt) {
  return std::max(1, static_cast<int>(std::ceil(x.t_end() / dt - 1e-9)));
}

// ---------------------------------------------------------------------------------- exact and recursion

std::vector<double> exact_history(const DriverHistory& x, double tau, double dt, int steps, int refine) {
  assert(tau > 0.0 && dt > 0.0 && refine >= 1);
  // Panels no wider than a quarter of the shortest time scale (tau, 1/omega_max), 8 Gauss points:
  // the relative quadrature error per panel is far below round-off (checked with refine = 2).
  double scale = tau;
  if (x.max_frequency() > 0.0) scale = std::min(scale, 1.0 / x.max_frequency());
  const double width = scale / 4.0;
  auto rate = [&x](double s, VecX& r) {
    r.resize(1);
    r[0] = x.rate(s);
  };
  std::vector<double> h(static_cast<std::size_t>(steps) + 1, 0.0);
  const double decay = std::exp(-dt / tau);
  for (int n = 0; n < steps; ++n) {
    const double t0 = n * dt, t1 = (n + 1) * dt;
    // Split the step at kinks of X_e (the quadrature assumes a smooth integrand on each piece).
    std::vector<double> cuts = {t0};
    for (double k : x.kinks())
      if (k > t0 + 1e-12 * dt && k < t1 - 1e-12 * dt) cuts.push_back(k);
    cuts.push_back(t1);
    double step_integral = 0.0;
    for (std::size_t p = 0; p + 1 < cuts.size(); ++p) {
      const double a = cuts[p], b = cuts[p + 1];
      const int panels = refine * std::max(1, static_cast<int>(std::ceil((b - a) / width)));
      // int_a^b exp(-(b-s)/tau) X_e' ds, carried to t1 by exp(-(t1-b)/tau)
      step_integral += std::exp(-(t1 - b) / tau) * convolve_rate(rate, 1, tau, a, b, panels, 8)[0];
    }
    h[static_cast<std::size_t>(n) + 1] = decay * h[static_cast<std::size_t>(n)] + step_integral;
  }
  return h;
}

std::vector<double> recursion_history(const DriverHistory& x, Integ scheme, double tau, double dt,
                                      int steps) {
  std::vector<double> h(static_cast<std::size_t>(steps) + 1, 0.0);
  const RecursionFactors f = recursion_factors(scheme, dt, tau);  // the model's own factors
  double x_prev = x.value(0.0);
  for (int n = 0; n < steps; ++n) {
    const double x_next = x.value((n + 1) * dt);
    h[static_cast<std::size_t>(n) + 1] = f.a * h[static_cast<std::size_t>(n)] + f.c * (x_next - x_prev);
    x_prev = x_next;
  }
  return h;
}

RecursionError recursion_error(const DriverHistory& x, Integ scheme, double alpha, double tau, double dt,
                               bool quadrature_check) {
  RecursionError r;
  r.dt = dt;
  r.dt_over_tau = dt / tau;
  r.steps = steps_to_cover(x, dt);
  const std::vector<double> he = exact_history(x, tau, dt, r.steps);
  const std::vector<double> hr = recursion_history(x, scheme, tau, dt, r.steps);
  double peak = 0.0, err = 0.0;
  for (int n = 0; n <= r.steps; ++n) {
    const std::size_t i = static_cast<std::size_t>(n);
    peak = std::max(peak, std::abs(x.value(n * dt) + alpha * he[i]));
    err = std::max(err, alpha * std::abs(hr[i] - he[i]));
  }
  r.error = peak > 0.0 ? err / peak : err;
  if (quadrature_check) {
    const std::vector<double> he2 = exact_history(x, tau, dt, r.steps, 2);
    double q = 0.0;
    for (std::size_t i = 0; i < he.size(); ++i) q = std::max(q, alpha * std::abs(he2[i] - he[i]));
    r.quadrature = peak > 0.0 ? q / peak : q;
  }
  return r;
}

double fitted_order(const std::vector<RecursionError>& runs, double max_dt_over_tau, double floor) {
  double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
  int n = 0;
  for (const auto& r : runs) {
    if (r.dt_over_tau > max_dt_over_tau * (1.0 + 1e-9) || !(r.error > floor)) continue;
    const double lx = std::log(r.dt), ly = std::log(r.error);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
    ++n;
  }
  if (n < 3) return std::numeric_limits<double>::quiet_NaN();
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

double breakdown_dt_over_tau(const std::vector<RecursionError>& runs, double level) {
  for (std::size_t i = 0; i < runs.size(); ++i) {
    if (runs[i].error < level) continue;
    if (i == 0) return 0.0;
    const RecursionError& a = runs[i - 1];
    const RecursionError& b = runs[i];
    const double s = (std::log(level) - std::log(a.error)) / (std::log(b.error) - std::log(a.error));
    return std::exp(std::log(a.dt_over_tau) + s * (std::log(b.dt_over_tau) - std::log(a.dt_over_tau)));
  }
  return std::numeric_limits<double>::infinity();
}

std::vector<double> default_sweep(bool quick) {
  std::vector<double> s;
  if (quick) {
    for (int k = -6; k <= 2; ++k) s.push_back(std::pow(10.0, k / 2.0));
  } else {
    for (int k = -12; k <= 4; ++k) s.push_back(std::pow(10.0, k / 4.0));
  }
  return s;
}

std::vector<DriverHistory> study_histories(const std::vector<std::string>& groups, const StudyOptions& o) {
  for (const auto& g : groups)
    if (g != "ramp_hold" && g != "sine" && g != "random")
      throw Error("hereditary: unknown history group '" + g + "' (expected ramp_hold, sine or random)");
  auto has = [&groups](const char* g) { return std::find(groups.begin(), groups.end(), g) != groups.end(); };
  const double tau = o.tau, eps = 0.1;
  std::vector<DriverHistory> out;
  if (has("ramp_hold")) {
    out.push_back(DriverHistory::ramp_hold("ramp_hold", eps, tau, 6.0 * tau));
    out.push_back(DriverHistory::ramp_hold("ramp_hold_fast", eps, 0.01 * tau, 6.0 * tau));
  }
  if (has("sine"))
    for (double wt : {0.1, 1.0, 10.0}) {
      const double omega = wt / tau;
      // two periods (one in quick mode), at least 6 tau
      const double t_end = std::max(6.0 * tau, (o.quick ? 1.0 : 2.0) * 2.0 * kPi / omega);
      out.push_back(DriverHistory::sine("sine_w" + fmt(wt), eps, omega, t_end));
    }
  if (has("random"))
    out.push_back(DriverHistory::random("random", eps, o.seed, 8, 0.1 / tau, 10.0 / tau, 20.0 * tau));
  return out;
}

SweepResult sweep(const DriverHistory& x, Integ scheme, const StudyOptions& o,
                  const std::function<void(const std::string&)>& progress) {
  SweepResult s;
  s.history = x.name();
  s.scheme = ViscoelasticOptions::to_string(scheme);
  const std::vector<double> dts = o.dt_over_tau.empty() ? default_sweep(o.quick) : o.dt_over_tau;
  for (double q : dts) {
    s.runs.push_back(recursion_error(x, scheme, o.alpha, o.tau, q * o.tau, true));
    if (progress)
      progress(s.history + " " + s.scheme + " dt/tau " + fmt(q) + ": error " + fmt(s.runs.back().error));
  }
  // Asymptotic window: dt at most 5 % of the shortest time scale (tau, 1/omega_max).
  s.fit_max_dt_over_tau = 0.05 / std::max(1.0, x.max_frequency() * o.tau);
  s.order = fitted_order(s.runs, s.fit_max_dt_over_tau);
  s.breakdown_1pct = breakdown_dt_over_tau(s.runs, 0.01);
  s.breakdown_10pct = breakdown_dt_over_tau(s.runs, 0.1);
  return s;
}

TimeHistory time_history(const DriverHistory& x, Integ scheme, double alpha, double tau, double dt) {
  TimeHistory th;
  const int n = steps_to_cover(x, dt);
  th.h_exact = exact_history(x, tau, dt, n);
  th.h_rec = recursion_history(x, scheme, tau, dt, n);
  for (int k = 0; k <= n; ++k) {
    const double t = k * dt, xe = x.value(t);
    th.t.push_back(t);
    th.x_rec.push_back(xe + alpha * th.h_rec[static_cast<std::size_t>(k)]);
    th.x_exact.push_back(xe + alpha * th.h_exact[static_cast<std::size_t>(k)]);
  }
  return th;
}

int sign_changes(const TimeHistory& th, double t_from) {
  int changes = 0;
  double prev = 0.0;
  for (std::size_t k = 1; k < th.t.size(); ++k) {
    if (th.t[k - 1] < t_from - 1e-12) continue;
    const double d = th.h_rec[k] - th.h_rec[k - 1];
    if (d == 0.0) continue;
    if (prev != 0.0 && (d > 0.0) != (prev > 0.0)) ++changes;
    prev = d;
  }
  return changes;
}

// ---------------------------------------------------------------------------------- liver

namespace {

/// 4th-order finite-difference derivatives of equally spaced samples (one-sided at the ends).
std::vector<double> derivative(const std::vector<double>& y, double h) {
  const std::size_t m = y.size();
  if (m < 5) throw Error("hereditary liver study: a path piece needs at least 5 samples");
  std::vector<double> d(m);
  for (std::size_t i = 2; i + 2 < m; ++i)
    d[i] = (y[i - 2] - 8.0 * y[i - 1] + 8.0 * y[i + 1] - y[i + 2]) / (12.0 * h);
  d[0] = (-25.0 * y[0] + 48.0 * y[1] - 36.0 * y[2] + 16.0 * y[3] - 3.0 * y[4]) / (12.0 * h);
  d[1] = (-3.0 * y[0] - 10.0 * y[1] + 18.0 * y[2] - 6.0 * y[3] + y[4]) / (12.0 * h);
  d[m - 1] =
      (25.0 * y[m - 1] - 48.0 * y[m - 2] + 36.0 * y[m - 3] - 16.0 * y[m - 4] + 3.0 * y[m - 5]) / (12.0 * h);
  d[m - 2] = (3.0 * y[m - 1] + 10.0 * y[m - 2] - 18.0 * y[m - 3] + 6.0 * y[m - 4] - y[m - 5]) / (12.0 * h);
  return d;
}

/// Exact hereditary variable of a scalar path y(t_k), t_k = k h, smooth on [0, kink] and [kink, end]:
/// StoredHistory (cubic Hermite) per piece, the pieces joined by the semigroup property.
/// Returns h(t_k) for every sample k.
std::vector<double> exact_path_history(const std::vector<double>& y, double h, std::size_t kink, double tau) {
  std::vector<double> out(y.size(), 0.0);
  std::size_t start = 0;
  double carried = 0.0;  // h at the start of the piece
  while (start + 1 < y.size()) {
    const std::size_t end = (kink > start && kink < y.size() - 1) ? kink : y.size() - 1;
    const std::vector<double> piece(y.begin() + static_cast<std::ptrdiff_t>(start),
                                    y.begin() + static_cast<std::ptrdiff_t>(end) + 1);
    const std::vector<double> d = derivative(piece, h);
    StoredHistory sh(1);
    for (std::size_t k = 0; k < piece.size(); ++k)
      sh.add((start + k) * h, VecX::Constant(1, piece[k]), VecX::Constant(1, d[k]));
    for (std::size_t k = 1; k < piece.size(); ++k) {
      const double decay = std::exp(-(k * h) / tau);
      // StoredHistory adds the jump term decay * y(t_start); the path is continuous, so replace it by
      // the history carried in from the previous piece.
      out[start + k] = sh.convolve(k, tau)[0] - decay * piece[0] + decay * carried;
    }
    carried = out[end];
    start = end;
  }
  return out;
}

struct CoupledRun {
  std::vector<double> t, force;
  std::vector<double>
      node_driver;  ///< y(t_k): sum over the node's tets of X_e at the node, z (signed like force)
  double seconds = 0.0;
};

/// The fig6 relaxation of one node, set up once and run per scheme and dt: the liver problem (the
/// same one the work-precision study uses), the pushed node's condition, its tets, and the times.
struct LiverSetup {
  LiverProblem problem;
  SolverSpec solver;
  std::vector<DirichletCondition> conditions;  ///< base, push
  std::size_t push_index = 1;
  Index push_node = 0;
  std::vector<std::pair<Index, int>> node_tets;  ///< (tet, local index of the push node)
  VecX node_mass;
  ViscoelasticOptions::History history = ViscoelasticOptions::History::NodalForce;
  /// The isolated recursion error and the path check read X_e = the nodal elastic forces of the pushed
  /// node's tets, whose sum is the elastic reaction: nodal_force history only.
  bool nodal = true;
  double t_end = 0.0, ramp = 0.0, dt_max = 0.0;

  /// Steps of size dt to t_end; throws unless dt divides t_end, the ramp time and the coarsest dt.
  int steps(double dt) const {
    const double n = t_end / dt;
    if (std::abs(n - std::round(n)) > 1e-9 || std::abs(ramp / dt - std::round(ramp / dt)) > 1e-9 ||
        std::abs(dt_max / dt - std::round(dt_max / dt)) > 1e-9)
      throw Error("hereditary liver study: dt " + fmt(dt) +
                  " must divide t_end, the ramp time and the coarsest dt");
    return static_cast<int>(std::lround(n));
  }
};

constexpr double kSign = -1.0;  // fig6 draws -reaction_z (pushing force positive)

/// The fig6 run of the requested node (its push condition and solver settings) on the liver problem.
LiverSetup liver_setup(const nlohmann::json& params, const std::string& where, const std::string& tmlab_root,
                       const LiverStudyOptions& o) {
  const PaperFigure fig = paper_figure("fig6", params, where);
  // fig6 runs are [scheme][node]; take the first scheme's run of the requested node and set the
  // history/integration ourselves.
  std::vector<const PaperRun*> node_runs;
  for (const auto& r : fig.runs)
    if (r.scheme == fig.runs.front().scheme) node_runs.push_back(&r);
  if (o.node < 1 || o.node > static_cast<int>(node_runs.size()))
    throw Error(where + ": fig6 has " + std::to_string(node_runs.size()) + " nodes; node " +
                std::to_string(o.node) + " requested");
  if (o.dts.empty() || o.reference_dts.size() != 2 ||
      std::abs(o.reference_dts[0] - 2.0 * o.reference_dts[1]) > 1e-12 * o.reference_dts[0])
    throw Error("hereditary liver study: need dts and a reference pair dt_f, dt_f/2");
  LiverSetup s;
  s.history = ViscoelasticOptions::parse_history(o.history);
  s.nodal = s.history == ViscoelasticOptions::History::NodalForce;
  const nlohmann::json& base_doc = node_runs[static_cast<std::size_t>(o.node) - 1]->case_doc;
  s.t_end = base_doc.at("solver").at("t_end").get<double>();
  s.ramp = params.at("fig6").at("ramp").get<double>();
  s.dt_max = *std::max_element(o.dts.begin(), o.dts.end());
  // The push condition and the solver settings from the fig6 case document.
  nlohmann::json doc = base_doc;
  doc["material"]["viscoelastic"] = {{"history", o.history},
                                     {"integration", "exact_linear"},
                                     {"prony", base_doc.at("material").at("viscoelastic").at("prony")}};
  const CaseConfig cfg = parse_case(doc, where + " (fig6)", {tmlab_root});
  s.solver = cfg.solver;
  s.problem = liver_problem(params, where, tmlab_root);
  const Mesh& mesh = s.problem.mesh;
  s.conditions.push_back(s.problem.base);
  for (const auto& b : cfg.boundary)
    if (b.name == "push")
      s.conditions.push_back({b.name, select_nodes(mesh, b.nodes), b.components, b.value, b.function});
  if (s.conditions.size() != 2 || s.conditions[s.push_index].nodes.size() != 1)
    throw Error(where + ": fig6 'push' must select one node");
  s.push_node = s.conditions[s.push_index].nodes[0];
  for (Index t = 0; t < mesh.num_tets(); ++t)
    for (int a = 0; a < 4; ++a)
      if (mesh.tets[static_cast<std::size_t>(t)][static_cast<std::size_t>(a)] == s.push_node)
        s.node_tets.emplace_back(t, a);
  s.node_mass = lumped_node_mass(mesh, s.problem.density);
  return s;
}

/// One coupled quasi-static run: the reaction of the pushed node and its elastic part y per step.
CoupledRun run_coupled(const LiverSetup& s, Integ scheme, double dt,
                       const std::function<void(const std::string&)>& progress) {
  CoupledRun cr;
  const auto w0 = std::chrono::steady_clock::now();
  ViscoelasticOptions vo;
  vo.history = s.history;
  vo.integration = scheme;
  vo.energy_bookkeeping = false;
  const Mesh& mesh = s.problem.mesh;
  ViscoelasticStVK model(mesh, s.problem.material, s.problem.prony, vo);
  const MechanicalSystem system(model, lumped_dof_mass(s.node_mass),
                                DirichletSet(mesh.num_points(), s.conditions),
                                ExternalLoads(mesh, s.node_mass));
  StaticSolver solver(system, newton_options(s.solver), s.solver.max_cutbacks);
  const int n = s.steps(dt);
  VecX u = VecX::Zero(system.num_dofs()), f;
  cr.t.push_back(0.0);
  cr.force.push_back(0.0);
  cr.node_driver.push_back(0.0);
  for (int k = 1; k <= n; ++k) {
    solver.advance((k - 1) * dt, k * dt, u);
    model.internal_force(u, f);  // committed total force; no external loads in fig6
    cr.t.push_back(k * dt);
    cr.force.push_back(kSign * system.bc().resultant(s.push_index, f).z());
    double y = 0.0;
    if (s.nodal) {
      const std::vector<double>& X = model.committed_driver();
      for (const auto& [t, a] : s.node_tets)
        y += X[static_cast<std::size_t>(t) * 12 + 3 * static_cast<std::size_t>(a) + 2];
    }
    cr.node_driver.push_back(kSign * y);
  }
  cr.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
  if (progress)
    progress("liver " + ViscoelasticOptions::to_string(scheme) + " dt " + fmt(dt) + ": " + std::to_string(n) +
             " steps, " + fmt(cr.seconds) + " s");
  return cr;
}

/// Values of a run of step dt at the coarsest times k dt_max.
std::vector<double> at_coarse(double dt_max, double dt, const std::vector<double>& v) {
  std::vector<double> out;
  const std::size_t stride = static_cast<std::size_t>(std::lround(dt_max / dt));
  for (std::size_t k = 0; k < v.size(); k += stride) out.push_back(v[k]);
  return out;
}

/// The reference: Richardson extrapolation (order 2) of exact_linear runs at the reference pair,
/// checked with the midpoint one. Fills t_ref, force_ref, peak_force, reference_check and
/// richardson_correction; returns the finest exact_linear run (its path carries the isolated errors).
CoupledRun liver_reference(const LiverSetup& s, const LiverStudyOptions& o, LiverStudy& study,
                           const std::function<void(const std::string&)>& progress) {
  const double dtf = o.reference_dts[1], dtc = o.reference_dts[0];
  const CoupledRun el_c = run_coupled(s, Integ::ExactLinear, dtc, progress);
  CoupledRun el_f = run_coupled(s, Integ::ExactLinear, dtf, progress);
  const CoupledRun mp_c = run_coupled(s, Integ::Midpoint, dtc, progress);
  const CoupledRun mp_f = run_coupled(s, Integ::Midpoint, dtf, progress);
  const std::vector<double> elc = at_coarse(s.dt_max, dtc, el_c.force),
                            elf = at_coarse(s.dt_max, dtf, el_f.force);
  const std::vector<double> mpc = at_coarse(s.dt_max, dtc, mp_c.force),
                            mpf = at_coarse(s.dt_max, dtf, mp_f.force);
  study.t_ref = at_coarse(s.dt_max, dtf, el_f.t);
  std::vector<double> mp_ref(elf.size());
  study.force_ref.resize(elf.size());
  for (std::size_t k = 0; k < elf.size(); ++k) {
    study.force_ref[k] = elf[k] + (elf[k] - elc[k]) / 3.0;
    mp_ref[k] = mpf[k] + (mpf[k] - mpc[k]) / 3.0;
    study.peak_force = std::max(study.peak_force, std::abs(study.force_ref[k]));
  }
  for (std::size_t k = 0; k < elf.size(); ++k) {
    study.reference_check =
        std::max(study.reference_check, std::abs(mp_ref[k] - study.force_ref[k]) / study.peak_force);
    study.richardson_correction =
        std::max(study.richardson_correction, std::abs(study.force_ref[k] - elf[k]) / study.peak_force);
  }
  return el_f;
}

/// The elastic reaction path y of the finest reference run (step dt) and the exact hereditary
/// variable of each Prony term along it, at every sample (empty for the pk2 history).
struct PathReference {
  std::vector<double> y;
  double dt = 0.0;
  std::vector<std::vector<double>> h_exact;
};

/// The exact history along the finest exact_linear path (the pushed node's tets only: the reaction of
/// the node is sum over its tets of [X_e + sum_j alpha_j h_j] at the node, z), and its two checks:
/// path_check (its reaction against the reference) and path_quadrature (every other sample). NaN for
/// the pk2 history.
PathReference path_reference(const LiverSetup& s, std::vector<double> y, double dtf, LiverStudy& study) {
  PathReference ref{std::move(y), dtf, {}};
  if (!s.nodal) {
    study.path_check = study.path_quadrature = std::numeric_limits<double>::quiet_NaN();
    return ref;
  }
  const PronySeries& prony = s.problem.prony;
  const std::size_t kink = static_cast<std::size_t>(std::lround(s.ramp / dtf));
  for (std::size_t j = 0; j < prony.size(); ++j)
    ref.h_exact.push_back(exact_path_history(ref.y, dtf, kink, prony.tau(j)));
  // the same with every other sample (spacing 2 dt_f): bounds the interpolation/differencing error
  std::vector<double> y2;
  for (std::size_t k = 0; k < ref.y.size(); k += 2) y2.push_back(ref.y[k]);
  for (std::size_t j = 0; j < prony.size(); ++j) {
    const std::vector<double> h2 = exact_path_history(y2, 2.0 * dtf, kink / 2, prony.tau(j));
    for (std::size_t k = 0; k < h2.size(); ++k)
      study.path_quadrature = std::max(
          study.path_quadrature, prony.alpha(j) * std::abs(h2[k] - ref.h_exact[j][2 * k]) / study.peak_force);
  }
  const int fine_stride = static_cast<int>(std::lround(s.dt_max / dtf));
  for (std::size_t k = 0; k < study.t_ref.size(); ++k) {
    const std::size_t kf = k * static_cast<std::size_t>(fine_stride);
    double exact = ref.y[kf];
    for (std::size_t j = 0; j < prony.size(); ++j) exact += prony.alpha(j) * ref.h_exact[j][kf];
    study.path_check = std::max(study.path_check, std::abs(exact - study.force_ref[k]) / study.peak_force);
  }
  return ref;
}

/// The recursion of `scheme` alone, applied to the reference path sampled every dt, against the exact
/// history along it (max at the coarsest times, relative to the peak force).
double isolated_error(const LiverSetup& s, Integ scheme, double dt, const PathReference& ref, double peak) {
  const PronySeries& prony = s.problem.prony;
  const std::size_t stride = static_cast<std::size_t>(std::lround(dt / ref.dt));
  std::vector<double> hsum((ref.y.size() - 1) / stride + 1, 0.0);
  for (std::size_t j = 0; j < prony.size(); ++j) {
    const RecursionFactors fct = recursion_factors(scheme, dt, prony.tau(j));
    double h = 0.0;
    for (std::size_t m = 1; m < hsum.size(); ++m) {
      h = fct.a * h + fct.c * (ref.y[m * stride] - ref.y[(m - 1) * stride]);
      hsum[m] += prony.alpha(j) * h;
    }
  }
  double error = 0.0;
  const std::size_t coarse_stride = static_cast<std::size_t>(std::lround(s.dt_max / dt));
  for (std::size_t m = 0; m < hsum.size(); m += coarse_stride) {
    double exact = 0.0;
    for (std::size_t j = 0; j < prony.size(); ++j) exact += prony.alpha(j) * ref.h_exact[j][m * stride];
    error = std::max(error, std::abs(hsum[m] - exact) / peak);
  }
  return error;
}

/// One run of the study: coupled error against the reference, and (nodal_force) the path deviation
/// and the isolated recursion error.
LiverRun liver_run(const LiverSetup& s, Integ scheme, double dt, const LiverStudy& study,
                   const PathReference& ref, const std::function<void(const std::string&)>& progress) {
  const CoupledRun cr = run_coupled(s, scheme, dt, progress);
  LiverRun lr;
  lr.scheme = ViscoelasticOptions::to_string(scheme);
  lr.dt = dt;
  lr.t = cr.t;
  lr.force = cr.force;
  lr.seconds = cr.seconds;
  const std::vector<double> fc = at_coarse(s.dt_max, dt, cr.force);
  for (std::size_t k = 0; k < fc.size(); ++k)
    lr.error = std::max(lr.error, std::abs(fc[k] - study.force_ref[k]) / study.peak_force);
  if (!s.nodal) {
    lr.isolated_error = lr.path_deviation = std::numeric_limits<double>::quiet_NaN();
    return lr;
  }
  // how far this run's elastic reaction path is from the reference path (the coupling)
  const std::size_t stride = static_cast<std::size_t>(std::lround(dt / ref.dt));
  for (std::size_t m = 0; m < cr.node_driver.size(); ++m)
    lr.path_deviation =
        std::max(lr.path_deviation, std::abs(cr.node_driver[m] - ref.y[m * stride]) / study.peak_force);
  lr.isolated_error = isolated_error(s, scheme, dt, ref, study.peak_force);
  return lr;
}

}  // namespace

LiverStudy liver_study(const nlohmann::json& params, const std::string& where, const std::string& tmlab_root,
                       const LiverStudyOptions& o, const std::function<void(const std::string&)>& progress) {
  const auto wall0 = std::chrono::steady_clock::now();
  const LiverSetup s = liver_setup(params, where, tmlab_root, o);
  LiverStudy study;
  study.num_tets = s.problem.mesh.num_tets();
  study.num_nodes = s.problem.mesh.num_points();
  study.node_tets = static_cast<int>(s.node_tets.size());
  CoupledRun finest = liver_reference(s, o, study, progress);
  const PathReference ref = path_reference(s, std::move(finest.node_driver), o.reference_dts[1], study);
  for (Integ scheme : {Integ::Midpoint, Integ::ExactLinear, Integ::BackwardEuler})
    for (double dt : o.dts) study.runs.push_back(liver_run(s, scheme, dt, study, ref, progress));
  study.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  study.describe = {{"params", where},
                    {"figure", "fig6"},
                    {"node", o.node},
                    {"push_node_index", s.push_node},
                    {"history", o.history},
                    {"t_end", s.t_end},
                    {"ramp", s.ramp},
                    {"prony_long_term", s.problem.prony.to_json()},
                    {"dts", o.dts},
                    {"reference_dts", o.reference_dts},
                    {"mesh", s.problem.mesh_file}};
  return study;
}

}  // namespace tmlab::tm
