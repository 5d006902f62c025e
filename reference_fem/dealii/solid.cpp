// The reference solver: materials' factories, the distributed mesh and DoFs, assembly of the
// residual and the consistent tangent, Newton with line search and load-increment cut-backs, and
// the post-processed quantities. See solid.hpp for the weak form and docs/reference-fem.md.
#include "reference_fem/dealii/solid.hpp"

#include "core/base/error.hpp"
#include "core/base/stopwatch.hpp"

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/tria_base.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_fe.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria_description.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <optional>
#include <sstream>

namespace tmlab::ref {

using namespace dealii;
using Clock = std::chrono::steady_clock;

// =====================================================================================================
// Mean dilatation (F-bar with one volume change per cell)
// =====================================================================================================
//
// The fast model's p2_mean_dilatation element (tensormass/kernels/hyperelastic_p2.hpp), written for
// any cell of this solver. With the cell's quadrature points q, weights w_q = JxW_q (reference
// volume) and V = sum_q w_q:
//
//   F_q = I + Grad u(X_q),   J_q = det F_q,
//   Jbar = sum_q w_q J_q / V                        (the cell's current volume over its rest volume),
//   alpha_q = (Jbar / J_q)^{1/3},   Fbar_q = alpha_q F_q   (so det Fbar_q = Jbar at every point),
//   Ebar_q = (Fbar_q^T Fbar_q - I) / 2,   W_cell = sum_q w_q W(Ebar_q),
//
// the law (materials.hpp) evaluated at Ebar exactly as the standard element evaluates it at E. The
// force is dW_cell/dU and the tangent d^2 W_cell/dU^2; every Fbar_q depends on all the cell's DoFs
// through Jbar, so the cell matrix is dense (the pattern is the element's own). On an affine field
// every J_q is Jbar, alpha_q = 1 and Fbar = F: the standard element's energy and force (so a
// homogeneous solution is one of both); its tangent differs, since l_qi below is not zero there.
//
// Derivatives. Cell DoF i is the shape function e_{c_i} N_i, with g_qi = Grad N_i(X_q), so
// dF_q/dU_i = e_{c_i} (x) g_qi. With v_qi = F_q^{-T} g_qi:
//   b_qi = d(ln J_q)/dU_i = F_q^{-T} : (e_{c_i} (x) g_qi) = (v_qi)_{c_i},
//   jb_i = d(ln Jbar)/dU_i = sum_q w_q J_q b_qi / (V Jbar),
//   l_qi = d(ln alpha_q)/dU_i = (jb_i - b_qi) / 3,
//   G_qi = dFbar_q/dU_i = alpha_q (e_{c_i} (x) g_qi + l_qi F_q).
// The second derivatives of the logarithms: d^2(ln J)/dF^2 [A, B] = -tr(F^{-1} A F^{-1} B), so
//   HJ_qij = d^2(ln J_q)/dU_i dU_j = -(v_qi)_{c_j} (v_qj)_{c_i},
//   Hbar_ij = d^2(ln Jbar)/dU_i dU_j = sum_q w_q J_q (b_qi b_qj + HJ_qij) / (V Jbar) - jb_i jb_j,
//   d^2(ln alpha_q)/dU_i dU_j = (Hbar_ij - HJ_qij) / 3.
// With Pbar_q = Fbar_q S(Ebar_q) (first Piola-Kirchhoff stress of Fbar) and its derivative
// A_q[dFbar] = dFbar S + Fbar (D : sym(Fbar^T dFbar)):
//   f_i  = sum_q w_q Pbar_q : G_qi,
//   K_ij = sum_q w_q [ G_qi : A_q[G_qj] + alpha_q (m_qi l_qj + l_qi m_qj)
//                      + alpha_q (Pbar_q : F_q) (l_qi l_qj + (Hbar_ij - HJ_qij) / 3) ],
// m_qi = Pbar_q : (e_{c_i} (x) g_qi) = (Pbar_q g_qi)_{c_i}. (The last two terms are the derivative of
// G_qi itself: G_q is linear in alpha_q, in F_q and in l_q.) tests/test_reference_solid.cpp checks the
// tangent against central differences of the force and the force against those of the energy.

namespace {

/// The F-bar kinematics of one cell (see above) at the displacement gradients grad_u of its points.
struct MeanDilatationKinematics {
  std::vector<Tensor<2, 3>> F, Fbar;
  std::vector<double> J;
  double Jbar = 1.0, volume = 0.0;
  bool in_domain = true;  ///< every J_q > 0 ((Jbar / J_q)^{1/3} and the laws need it)
};

MeanDilatationKinematics mean_dilatation_kinematics(const FEValues<3>& fev,
                                                    const std::vector<Tensor<2, 3>>& grad_u) {
  const std::size_t nq = grad_u.size();
  MeanDilatationKinematics k;
  k.F.resize(nq);
  k.Fbar.resize(nq);
  k.J.resize(nq);
  double wJ = 0.0;
  for (unsigned q = 0; q < nq; ++q) {
    k.F[q] = Tensor<2, 3>(unit_symmetric_tensor<3>()) + grad_u[q];
    k.J[q] = determinant(k.F[q]);
    if (!(k.J[q] > 0.0)) k.in_domain = false;
    wJ += fev.JxW(q) * k.J[q];
    k.volume += fev.JxW(q);
  }
  // Jbar = sum_q w_q J_q / V;  Fbar_q = (Jbar / J_q)^{1/3} F_q.
  k.Jbar = wJ / k.volume;
  if (k.in_domain)  // else Fbar stays zero: the callers stop at in_domain
    for (unsigned q = 0; q < nq; ++q) k.Fbar[q] = std::cbrt(k.Jbar / k.J[q]) * k.F[q];
  return k;
}

SymTensor2 green_strain(const Tensor<2, 3>& F) {
  return 0.5 * (symmetrize(transpose(F) * F) - unit_symmetric_tensor<3>());
}

/// W_cell = sum_q w_q W(Ebar_q); +inf outside the domain.
double mean_dilatation_energy(const Material& m, const FEValues<3>& fev,
                              const std::vector<Tensor<2, 3>>& grad_u) {
  const MeanDilatationKinematics k = mean_dilatation_kinematics(fev, grad_u);
  if (!k.in_domain) return std::numeric_limits<double>::infinity();
  double w = 0.0;
  for (unsigned q = 0; q < grad_u.size(); ++q) w += m.energy(green_strain(k.Fbar[q])) * fev.JxW(q);
  return w;
}

/// Adds the cell force f_i to cell_r and, with cell_K, the lower triangle (j <= i) of the cell
/// tangent K_ij (the formulas above). comp[i] = c_i. Returns false outside the domain (nothing added).
bool add_mean_dilatation_cell(const Material& m, const FEValues<3>& fev,
                              const std::vector<Tensor<2, 3>>& grad_u, const std::vector<unsigned>& comp,
                              Vector<double>& cell_r, FullMatrix<double>* cell_K) {
  const MeanDilatationKinematics k = mean_dilatation_kinematics(fev, grad_u);
  if (!k.in_domain) return false;
  const unsigned n = static_cast<unsigned>(comp.size()), nq = static_cast<unsigned>(grad_u.size());
  const double VJbar = k.volume * k.Jbar;
  // Per point q and DoF i (index q n + i): g_qi = Grad N_i, v_qi = F_q^{-T} g_qi, b_qi = (v_qi)_{c_i};
  // and jb_i = sum_q w_q J_q b_qi / (V Jbar).
  std::vector<Tensor<1, 3>> g(nq * n), v(nq * n);
  std::vector<double> b(nq * n), jb(n, 0.0);
  for (unsigned q = 0; q < nq; ++q) {
    const Tensor<2, 3> FinvT = transpose(invert(k.F[q]));
    for (unsigned i = 0; i < n; ++i) {
      const unsigned qi = q * n + i;
      g[qi] = fev.shape_grad_component(i, q, comp[i]);
      v[qi] = FinvT * g[qi];
      b[qi] = v[qi][comp[i]];
      jb[i] += fev.JxW(q) * k.J[q] * b[qi] / VJbar;
    }
  }
  // HJ_qij = -(v_qi)_{c_j} (v_qj)_{c_i};  Hbar_ij = sum_q w_q J_q (b_qi b_qj + HJ_qij) / (V Jbar) - jb_i jb_j
  // (lower triangles; both are symmetric).
  auto HJ = [&](unsigned q, unsigned i, unsigned j) {
    return -v[q * n + i][comp[j]] * v[q * n + j][comp[i]];
  };
  FullMatrix<double> Hbar;
  if (cell_K) {
    Hbar.reinit(n, n);
    for (unsigned q = 0; q < nq; ++q) {
      const double c = fev.JxW(q) * k.J[q] / VJbar;
      for (unsigned i = 0; i < n; ++i)
        for (unsigned j = 0; j <= i; ++j) Hbar(i, j) += c * (b[q * n + i] * b[q * n + j] + HJ(q, i, j));
    }
    for (unsigned i = 0; i < n; ++i)
      for (unsigned j = 0; j <= i; ++j) Hbar(i, j) -= jb[i] * jb[j];
  }
  std::vector<double> l(n), mq(n);
  std::vector<Tensor<2, 3>> G(n), AG(n);
  for (unsigned q = 0; q < nq; ++q) {
    const double w = fev.JxW(q);
    const double alpha = std::cbrt(k.Jbar / k.J[q]);
    const Tensor<2, 3>& Fbar = k.Fbar[q];
    // The law at Ebar: S = dW/dE, D = dS/dE; Pbar = Fbar S.
    const SymTensor2 Ebar = green_strain(Fbar);
    const Tensor<2, 3> S(m.stress(Ebar));
    SymTensor4 D;
    if (cell_K) D = m.tangent(Ebar);
    const Tensor<2, 3> Pbar = Fbar * S;
    const double PF = scalar_product(Pbar, k.F[q]);
    for (unsigned i = 0; i < n; ++i) {
      const unsigned qi = q * n + i;
      // l_qi = (jb_i - b_qi)/3;  G_qi = alpha_q (e_{c_i} (x) g_qi + l_qi F_q).
      l[i] = (jb[i] - b[qi]) / 3.0;
      G[i] = l[i] * k.F[q];
      for (unsigned c = 0; c < 3; ++c) G[i][comp[i]][c] += g[qi][c];
      G[i] *= alpha;
      // Internal force: f_i += w_q Pbar_q : G_qi.
      cell_r(i) += scalar_product(Pbar, G[i]) * w;
      if (cell_K) {
        // m_qi = (Pbar_q g_qi)_{c_i};  A_q[G_qi] = G_qi S + Fbar (D : sym(Fbar^T G_qi)).
        mq[i] = (Pbar * g[qi])[comp[i]];
        AG[i] = G[i] * S + Fbar * Tensor<2, 3>(D * symmetrize(transpose(Fbar) * G[i]));
      }
    }
    if (cell_K)
      // K_ij += w_q [G_qi : A_q[G_qj] + alpha_q (m_qi l_qj + l_qi m_qj)
      //              + alpha_q (Pbar_q : F_q)(l_qi l_qj + (Hbar_ij - HJ_qij)/3)].
      for (unsigned i = 0; i < n; ++i)
        for (unsigned j = 0; j <= i; ++j)
          (*cell_K)(i, j) += w * (scalar_product(G[i], AG[j]) + alpha * (mq[i] * l[j] + l[i] * mq[j]) +
                                  alpha * PF * (l[i] * l[j] + (Hbar(i, j) - HJ(q, i, j)) / 3.0));
  }
  return true;
}

}  // namespace

// =====================================================================================================
// Materials
// =====================================================================================================

Material Material::make(MaterialLaw law, double young, double poisson, double yeoh_c20_ratio,
                        double yeoh_c30_ratio) {
  if (!(young > 0.0) || !std::isfinite(young))
    throw Error("material: E must be > 0 (got " + std::to_string(young) + ")");
  if (!(poisson > -1.0 && poisson < 0.5)) throw Error("material: nu must satisfy -1 < nu < 0.5");
  if (law != Kind::StVK && law != Kind::NeoHookean && law != Kind::Yeoh)
    throw Error("material: law '" + to_string(law) +
                "' is not given by E and nu: give it with its own keys in the case's material section");
  Material m;
  m.lambda = young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
  m.mu = young / (2.0 * (1.0 + poisson));
  m.stvk = {m.lambda, m.mu};
  m.neo = {m.lambda, m.mu};
  m.yeoh = {0.5 * m.mu, 0.5 * m.mu * yeoh_c20_ratio, 0.5 * m.mu * yeoh_c30_ratio,
            m.lambda + 2.0 * m.mu / 3.0};
  m.kind = law;
  if (law == Kind::Yeoh && (yeoh_c20_ratio < 0.0 || yeoh_c30_ratio < 0.0))
    throw Error("material: Yeoh C20, C30 must be >= 0");
  return m;
}

Material Material::make(const std::string& law, double young, double poisson, double yeoh_c20_ratio,
                        double yeoh_c30_ratio) {
  const std::optional<MaterialLaw> named = material_law_from_string(law);
  if (!named || (*named != Kind::StVK && *named != Kind::NeoHookean && *named != Kind::Yeoh))
    throw Error("reference: the law override takes stvk, neo_hookean or yeoh (got '" + law +
                "'); other laws are given in the case's material section");
  return make(*named, young, poisson, yeoh_c20_ratio, yeoh_c30_ratio);
}

PronySeries PronySeries::make(PronyConvention convention, const std::vector<double>& weights,
                              const std::vector<double>& taus, PronyIntegration integration,
                              PronyRelaxation relaxation) {
  if (weights.size() != taus.size() || weights.empty())
    throw Error("prony: need one tau per weight (and at least one term)");
  double gsum = 0.0;
  for (double w : weights) {
    if (!(w >= 0.0)) throw Error("prony: weights must be >= 0");
    gsum += w;
  }
  for (double t : taus)
    if (!(t > 0.0)) throw Error("prony: tau must be > 0");
  if (convention == PronyConvention::Instantaneous && !(gsum < 1.0))
    throw Error("prony: instantaneous weights must sum to < 1");
  PronySeries p;
  p.alpha = long_term_weights(convention, weights);
  p.tau = taus;
  p.integration = integration;
  p.deviatoric = relaxation == PronyRelaxation::Deviatoric;
  return p;
}

// =====================================================================================================
// Mesh helpers
// =====================================================================================================

void build_tet_triangulation(const std::vector<Point<3>>& points,
                             const std::vector<std::array<unsigned, 4>>& tets, Triangulation<3>& tria) {
  std::vector<CellData<3>> cells(tets.size());
  for (std::size_t c = 0; c < tets.size(); ++c) {
    cells[c].vertices.assign(tets[c].begin(), tets[c].end());
    cells[c].material_id = 0;
  }
  // No reordering: deal.II's reference tetrahedron (0,0,0),(1,0,0),(0,1,0),(0,0,1) has the same
  // positive orientation as tmlab's tets, so vertex i of the triangulation is node i of the mesh.
  tria.create_triangulation(points, cells, SubCellData());
}

std::vector<std::vector<unsigned>> coarse_vertex_map(const Solid& solid, const Triangulation<3>& coarse) {
  std::vector<Triangulation<3>::active_cell_iterator> coarse_cells;
  coarse_cells.reserve(coarse.n_active_cells());
  for (const auto& c : coarse.active_cell_iterators()) coarse_cells.push_back(c);
  const auto& cv = coarse.get_vertices();
  std::vector<std::vector<unsigned>> map(solid.triangulation().n_active_cells());
  for (const auto& cell : solid.triangulation().active_cell_iterators()) {
    if (cell->is_artificial()) continue;
    const auto id = cell->id().get_coarse_cell_id();
    if (id >= coarse_cells.size()) throw Error("reference: coarse cell id out of range");
    const auto& cc = coarse_cells[id];
    auto& row = map[cell->active_cell_index()];
    row.resize(cell->n_vertices());
    const double h = cc->diameter();
    for (unsigned v = 0; v < cell->n_vertices(); ++v) {
      unsigned found = numbers::invalid_unsigned_int;
      if (cell->vertex(v).distance(cv[cc->vertex_index(v)]) <= 1e-12 * h) found = cc->vertex_index(v);
      for (unsigned w = 0; w < cc->n_vertices() && found == numbers::invalid_unsigned_int; ++w)
        if (cell->vertex(v).distance(cv[cc->vertex_index(w)]) <= 1e-12 * h) found = cc->vertex_index(w);
      if (found == numbers::invalid_unsigned_int)
        throw Error("reference: cell vertex not found in its coarse cell");
      row[v] = found;
    }
  }
  return map;
}

// =====================================================================================================
// Setup: distributed mesh, finite element, DoFs, history
// =====================================================================================================

Solid::Solid(MPI_Comm comm, Triangulation<3>& coarse, const Discretisation& disc, const Material& material,
             std::optional<PronySeries> prony, const NewtonParameters& newton, std::ostream* log)
    : comm_(comm),
      log_(log),
      tria_(comm),
      disc_(disc),
      material_(material),
      prony_(std::move(prony)),
      newton_(newton) {
  if (disc.degree < 1 || disc.degree > 2) throw Error("reference: degree must be 1 or 2");
  if (disc.mean_dilatation && prony_)
    throw Error("reference: the mean-dilatation (F-bar) form has no viscoelastic (Prony) form");
  // The coarse mesh is the same on every rank; METIS partitions it (deterministically) and the
  // fully distributed triangulation keeps each rank's cells plus one layer of ghosts.
  const unsigned n_ranks = Utilities::MPI::n_mpi_processes(comm);
  if (n_ranks > 1)
    GridTools::partition_triangulation(n_ranks, coarse);
  else
    for (const auto& c : coarse.active_cell_iterators()) c->set_subdomain_id(0);
  const auto description =
      TriangulationDescription::Utilities::create_description_from_triangulation(coarse, comm);
  tria_.create_triangulation(description);

  // Element, mapping and quadrature: P_k on simplices (exact integration of P1 St VK with a
  // degree-2 rule), Q_k on hexahedra with (k+1)^3 Gauss points.
  if (disc.simplex) {
    fe_ = std::make_unique<FESystem<3>>(FE_SimplexP<3>(disc.degree), 3);
    mapping_ = std::make_unique<MappingFE<3>>(FE_SimplexP<3>(1));
    qcell_ = QGaussSimplex<3>(disc.degree + 1);
    qface_ = QGaussSimplex<2>(disc.degree + 1);
  } else {
    fe_ = std::make_unique<FESystem<3>>(FE_Q<3>(disc.degree), 3);
    mapping_ = std::make_unique<MappingQ<3>>(1);
    qcell_ = QGauss<3>(disc.degree + 1);
    qface_ = QGauss<2>(disc.degree + 1);
  }
  dof_handler_.reinit(tria_);
  dof_handler_.distribute_dofs(*fe_);
  owned_ = dof_handler_.locally_owned_dofs();
  DoFTools::extract_locally_relevant_dofs(dof_handler_, relevant_);
  u_.reinit(owned_, comm_);
  u_ghost_.reinit(owned_, relevant_, comm_);

  // Quadrature-point history (Prony): committed and trial states per point of each owned cell.
  if (prony_)
    for (const auto& cell : tria_.active_cell_iterators())
      if (cell->is_locally_owned()) {
        qp_data_.initialize(cell, qcell_.size());
        for (auto& d : qp_data_.get_data(cell)) d->prony.resize(prony_->size());
      }
}

Solid::~Solid() { dof_handler_.clear(); }

int Solid::add_condition(const std::string& name, const TimeFunction& f) {
  conditions_.push_back({name, f});
  return static_cast<int>(conditions_.size()) - 1;
}

void Solid::prescribe(global_dof_index dof, unsigned component, int condition, double value) {
  prescribed_.push_back({dof, component, condition, value});
  setup_done_ = false;
}

int Solid::add_load_function(const TimeFunction& f) {
  load_functions_.push_back(f);
  return static_cast<int>(load_functions_.size()) - 1;
}

void Solid::add_point_force(global_dof_index dof, int load, double value) {
  point_forces_.push_back({dof, load, value});
}

void Solid::add_traction(const CellId& cell, unsigned face, int load, const Tensor<1, 3>& traction) {
  pressures_.push_back({cell, face, load, 0.0, traction});
}

void Solid::add_pressure(const CellId& cell, unsigned face, int load, double pressure) {
  pressures_.push_back({cell, face, load, pressure, Tensor<1, 3>()});
}

void Solid::add_body_force(std::function<Tensor<1, 3>(const Point<3>&)> b0, int load) {
  body_forces_.push_back({std::move(b0), load});
}

void Solid::finalize_setup() {
  // One entry per constrained DoF: the first condition that prescribes it owns it (as in
  // tmlab::tm::DirichletSet; conflicting values are rejected by the driver before this point).
  std::stable_sort(prescribed_.begin(), prescribed_.end(),
                   [](const Prescribed& a, const Prescribed& b) { return a.dof < b.dof; });
  prescribed_.erase(std::unique(prescribed_.begin(), prescribed_.end(),
                                [](const Prescribed& a, const Prescribed& b) { return a.dof == b.dof; }),
                    prescribed_.end());
  hom_constraints_.clear();
  hom_constraints_.reinit(relevant_);
  for (const auto& p : prescribed_) hom_constraints_.add_line(p.dof);
  hom_constraints_.close();

  // Sparsity with the constrained couplings kept, so that the same matrix serves the constrained
  // Newton systems and the unconstrained tangent (finite-difference tests).
  DynamicSparsityPattern dsp(relevant_);
  DoFTools::make_sparsity_pattern(dof_handler_, dsp, hom_constraints_, true);
  SparsityTools::distribute_sparsity_pattern(dsp, owned_, comm_, relevant_);
  K_.reinit(owned_, owned_, dsp, comm_);
  setup_done_ = true;
}

// =====================================================================================================
// Assembly: residual f_int - f_ext and the consistent tangent
// =====================================================================================================

void Solid::assemble(const TrilinosWrappers::MPI::Vector& u_ghost, double t, double dt, Mode mode,
                     const AffineConstraints<double>* constraints, TrilinosWrappers::MPI::Vector& r,
                     TrilinosWrappers::SparseMatrix* K, TrilinosWrappers::MPI::Vector* rhs) {
  const bool tangent = mode == Mode::ResidualAndTangent;
  FEValues<3> fev(*mapping_, *fe_, qcell_,
                  update_values | update_gradients | update_quadrature_points | update_JxW_values);
  FEFaceValues<3> fefv(*mapping_, *fe_, qface_, update_values | update_normal_vectors | update_JxW_values);
  const FEValuesExtractors::Vector disp(0);
  const unsigned n = fe_->n_dofs_per_cell(), nq = qcell_.size();
  std::vector<global_dof_index> dofs(n);
  std::vector<Tensor<2, 3>> grad_u(nq);
  FullMatrix<double> cell_K(n, n);
  Vector<double> cell_r(n), cell_rhs(n);
  std::vector<unsigned> comp(n);
  for (unsigned i = 0; i < n; ++i) comp[i] = fe_->system_to_component_index(i).first;
  std::vector<Tensor<1, 3>> gradN(n);
  std::vector<SymTensor2> dE(n), DdE(n);
  std::vector<Tensor<1, 3>> SgradN(n);

  // Pressure faces by cell (looked up per owned cell).
  std::map<CellId, std::vector<const Pressure*>> faces;
  for (const auto& p : pressures_) faces[p.cell].push_back(&p);

  r = 0.0;
  if (tangent) {
    *K = 0.0;
    *rhs = 0.0;
  }
  const SymTensor2 I = unit_symmetric_tensor<3>();
  const bool fbar = disc_.mean_dilatation;
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    fev.reinit(cell);
    cell->get_dof_indices(dofs);
    if (mode != Mode::External) fev[disp].get_function_gradients(u_ghost, grad_u);
    cell_r = 0.0;
    if (tangent) cell_K = 0.0;
    std::vector<std::shared_ptr<QPData>> qp;
    if (prony_) qp = qp_data_.get_data(cell);
    // Mean dilatation: the cell's force and tangent at once (its points are coupled through Jbar; see
    // "Mean dilatation" above). Outside the domain (a det F <= 0) the residual is NaN, so that the
    // line search shortens the step, as the fast model's NaN forces do.
    if (fbar && mode != Mode::External &&
        !add_mean_dilatation_cell(material_, fev, grad_u, comp, cell_r, tangent ? &cell_K : nullptr))
      for (unsigned i = 0; i < n; ++i) cell_r(i) = std::numeric_limits<double>::quiet_NaN();

    for (unsigned q = 0; q < nq; ++q) {
      const double JxW = fev.JxW(q);
      if (mode != Mode::External && !fbar) {
        // Kinematics: F = I + Grad u, E = (F^T F - I)/2.
        const Tensor<2, 3> F = unit_symmetric_tensor<3>() + grad_u[q];
        const SymTensor2 E = 0.5 * (symmetrize(transpose(F) * F) - I);
        // Constitutive update: S = dW/dE (+ Prony history), D = dS/dE.
        SymTensor2 S;
        SymTensor4 D;
        if (prony_)
          prony_update(material_, *prony_, E, dt, qp[q]->prony, S, tangent ? &D : nullptr);
        else {
          S = material_.stress(E);
          if (tangent) D = material_.tangent(E);
        }
        // Shape function i is e_{c_i} N_i: Grad phi_i = e_c (x) grad N_i, and the strain variation
        // dE_i = sym(F^T Grad phi_i) = sym((F^T e_c) (x) grad N_i).
        for (unsigned i = 0; i < n; ++i) {
          gradN[i] = fev.shape_grad_component(i, q, comp[i]);
          Tensor<1, 3> Fc;  // row c of F = F^T e_c
          for (unsigned k = 0; k < 3; ++k) Fc[k] = F[comp[i]][k];
          dE[i] = symmetrize(outer_product(Fc, gradN[i]));
          // Internal force: f_i = int S : dE_i dV.
          cell_r(i) += (S * dE[i]) * JxW;
          if (tangent) {
            DdE[i] = D * dE[i];
            SgradN[i] = S * gradN[i];
          }
        }
        if (tangent)
          // K_ij = int dE_i : D : dE_j + delta_{c_i c_j} grad N_i . S grad N_j dV (symmetric).
          for (unsigned i = 0; i < n; ++i)
            for (unsigned j = 0; j <= i; ++j) {
              double k = DdE[i] * dE[j];
              if (comp[i] == comp[j]) k += SgradN[i] * gradN[j];
              cell_K(i, j) += k * JxW;
            }
      }
      // Body forces (per unit reference volume): f_ext,i = int b0 . phi_i dV.
      for (const auto& bf : body_forces_) {
        const Tensor<1, 3> b = bf.b0(fev.quadrature_point(q)) * load_factor(bf.load, t);
        for (unsigned i = 0; i < n; ++i) cell_r(i) -= b[comp[i]] * fev.shape_value(i, q) * JxW;
      }
    }
    if (tangent)
      for (unsigned i = 0; i < n; ++i)
        for (unsigned j = i + 1; j < n; ++j) cell_K(i, j) = cell_K(j, i);

    // Dead pressure and traction on the reference surface:
    // f_ext,i = int (t - p N) . phi_i dA (N outward), entering the residual r = f_int - f_ext.
    const auto it = faces.find(cell->id());
    if (it != faces.end())
      for (const Pressure* p : it->second) {
        fefv.reinit(cell, p->face);
        const double lf = load_factor(p->load, t);
        const double pt = p->p * lf;
        const Tensor<1, 3> tt = p->traction * lf;
        for (unsigned q = 0; q < fefv.n_quadrature_points; ++q) {
          const Tensor<1, 3> N = fefv.normal_vector(q);
          for (unsigned i = 0; i < n; ++i)
            cell_r(i) += (pt * N[comp[i]] - tt[comp[i]]) * fefv.shape_value(i, q) * fefv.JxW(q);
        }
      }

    r.add(dofs, cell_r);
    if (tangent) {
      for (unsigned i = 0; i < n; ++i) cell_rhs(i) = -cell_r(i);
      constraints->distribute_local_to_global(cell_K, cell_rhs, dofs, *K, *rhs, true);
    }
  }
  // Point forces on vertex DoFs.
  if (!point_forces_.empty()) {
    std::vector<global_dof_index> idx;
    std::vector<double> val, val_rhs;
    std::vector<global_dof_index> idx_rhs;
    for (const auto& pf : point_forces_) {
      const double f = pf.value * load_factor(pf.load, t);
      idx.push_back(pf.dof);
      val.push_back(-f);
      if (tangent && !constraints->is_constrained(pf.dof)) {
        idx_rhs.push_back(pf.dof);
        val_rhs.push_back(f);
      }
    }
    r.add(idx, val);
    if (tangent && !idx_rhs.empty()) rhs->add(idx_rhs, val_rhs);
  }
  // Nodal constraints (contact) inside advance(): their forces and 3x3 blocks at the vertices.
  if (nodal_ && nodal_active_ && mode != Mode::External)
    nodal_->add_terms(u_ghost, t, r, constraints, tangent ? K : nullptr, tangent ? rhs : nullptr);
  r.compress(VectorOperation::add);
  if (tangent) {
    K->compress(VectorOperation::add);
    rhs->compress(VectorOperation::add);
  }
}

double Solid::free_norm(const TrilinosWrappers::MPI::Vector& r) const {
  TrilinosWrappers::MPI::Vector tmp(r);
  hom_constraints_.set_zero(tmp);
  return tmp.l2_norm();
}

void Solid::residual_and_tangent(const TrilinosWrappers::MPI::Vector& u_owned, double t, double dt,
                                 TrilinosWrappers::MPI::Vector& r, TrilinosWrappers::SparseMatrix* K) {
  if (!setup_done_) finalize_setup();
  TrilinosWrappers::MPI::Vector g(owned_, relevant_, comm_), rhs(owned_, comm_);
  g = u_owned;
  r.reinit(owned_, comm_);
  AffineConstraints<double> none(relevant_);
  none.close();
  if (K) {
    assemble(g, t, dt, Mode::ResidualAndTangent, &none, r, &K_, &rhs);
    K->copy_from(K_);
  } else {
    assemble(g, t, dt, Mode::Residual, nullptr, r, nullptr, nullptr);
  }
}

void Solid::set_solution(const TrilinosWrappers::MPI::Vector& u_owned) {
  u_ = u_owned;
  u_ghost_ = u_owned;
}

void Solid::external_force(double t, TrilinosWrappers::MPI::Vector& f) {
  if (!setup_done_) finalize_setup();
  f.reinit(owned_, comm_);
  assemble(u_ghost_, t, 0.0, Mode::External, nullptr, f, nullptr, nullptr);
  f *= -1.0;  // External mode assembles r = -f_ext
}

std::vector<std::pair<global_dof_index, double>> Solid::prescribed_values(double t) {
  if (!setup_done_) finalize_setup();
  std::vector<std::pair<global_dof_index, double>> out;
  out.reserve(prescribed_.size());
  for (const auto& p : prescribed_) out.emplace_back(p.dof, p.value * conditions_[p.condition].f(t));
  return out;
}

void Solid::set_history(
    const std::function<void(const Triangulation<3>::active_cell_iterator&, unsigned, PronyState&)>& f) {
  if (!prony_) return;
  for (const auto& cell : tria_.active_cell_iterators())
    if (cell->is_locally_owned()) {
      const auto data = qp_data_.get_data(cell);
      for (unsigned q = 0; q < data.size(); ++q) f(cell, q, data[q]->prony);
    }
}

// =====================================================================================================
// Linear solver: MUMPS (direct, through Trilinos Amesos) or CG preconditioned with ML AMG
// =====================================================================================================

int Solid::linear_solve(TrilinosWrappers::MPI::Vector& du, const TrilinosWrappers::MPI::Vector& rhs) {
  du = 0.0;
  if (newton_.linear_solver != LinearSolver::CgAmg) {
    SolverControl control(1, 0.0);
    TrilinosWrappers::SolverDirect::AdditionalData data(
        false, newton_.linear_solver == LinearSolver::Direct ? "Amesos_Mumps" : "Amesos_Klu");
    TrilinosWrappers::SolverDirect solver(control, data);
    solver.solve(K_, du, rhs);
    return 0;
  }
  TrilinosWrappers::PreconditionAMG amg;
  TrilinosWrappers::PreconditionAMG::AdditionalData ad;
  ad.elliptic = true;
  ad.higher_order_elements = disc_.degree > 1;
  ad.smoother_sweeps = 2;
  ad.aggregation_threshold = 0.02;
  DoFTools::extract_constant_modes(dof_handler_, ComponentMask(), ad.constant_modes);
  amg.initialize(K_, ad);
  SolverControl control(10000, std::max(newton_.cg_rtol * rhs.l2_norm(), 1e-300));
  SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
  cg.solve(K_, du, rhs, amg);
  return static_cast<int>(control.last_step());
}

// =====================================================================================================
// Newton with backtracking line search (the same algorithm as tmlab::tm::newton_solve: Armijo on the
// potential where there is one, a falling |R| accepted too, round-off stagnation stop)
// =====================================================================================================

namespace {

using TrilinosVector = TrilinosWrappers::MPI::Vector;

/// Where a line search starts: |R_free| at u_ref and, for the energy merit, Pi(u_ref) and the slope
/// R(u_ref) . du_free (a descent when negative).
struct SearchStart {
  double rref;
  bool energy;
  double pi_ref, slope;
};

using Residual = std::function<double(const TrilinosVector&, TrilinosVector&)>;
using Potential = std::function<double(const TrilinosVector&)>;

/// The start of the line search from u_ref (the constrained DoFs moved in full): |R_free| there
/// (evaluated into r_trial while prescribed increments are pending, else |R(u)| = rnorm with R(u)
/// in r) and, for the energy merit (see tmlab::tm::newton_solve), Pi(u_ref) and the slope
/// R(u_ref) . du_free, which must be a descent.
SearchStart search_start(const NewtonParameters& np, bool has_potential, bool pending, double rnorm,
                         const Residual& residual, const Potential& potential, const TrilinosVector& u_ref,
                         const TrilinosVector& du_free, const TrilinosVector& r, TrilinosVector& r_trial) {
  SearchStart start{rnorm, false, 0.0, 0.0};
  if (pending) start.rref = residual(u_ref, r_trial);
  start.energy = np.line_search == LineSearch::Energy && has_potential && std::isfinite(start.rref);
  if (start.energy) {
    start.slope = (pending ? r_trial : r) * du_free;
    start.pi_ref = potential(u_ref);
    start.energy = start.slope < 0.0 && std::isfinite(start.pi_ref);
  }
  return start;
}

/// Backtracking along the free step du_free from u_ref: Armijo on the potential where there is one,
/// a falling |R| accepted too; with LineSearch::None the full step. The step is shortened by halving,
/// or for the energy merit to the minimiser of the quadratic through Pi(0), Pi'(0), Pi(alpha).
/// Leaves the accepted point in u_trial and its residual in r_trial; returns |R_free| there and the
/// number of backtracks. A non-finite residual after the last backtrack throws (iteration k, time t).
std::pair<double, int> line_search(
    const NewtonParameters& np, const SearchStart& s,
    const std::function<double(const TrilinosVector&, TrilinosVector&)>& residual,
    const std::function<double(const TrilinosVector&)>& potential, const TrilinosVector& u_ref,
    const TrilinosVector& du_free, TrilinosVector& u_trial, TrilinosVector& r_trial, int k, double t) {
  const double eps = std::numeric_limits<double>::epsilon();
  const double rref = s.rref, pi_ref = s.pi_ref, slope = s.slope;
  double alpha = 1.0;
  int backtracks = 0;
  double rt = 0.0;
  while (true) {
    u_trial = u_ref;
    u_trial.add(alpha, du_free);
    rt = residual(u_trial, r_trial);
    double pi = std::numeric_limits<double>::quiet_NaN();
    bool ok;
    if (!std::isfinite(rt)) {
      ok = false;  // an element inverted: always shorten the step
    } else if (np.line_search == LineSearch::None) {
      ok = true;
    } else if (s.energy) {
      pi = potential(u_trial);
      ok = (std::isfinite(pi) &&
            pi <= pi_ref + 1e-4 * alpha * slope + 16.0 * eps * (std::abs(pi_ref) + std::abs(pi))) ||
           rt <= (1.0 - 1e-4 * alpha) * rref;
    } else if (np.line_search == LineSearch::Residual) {
      ok = rt <= (1.0 - 1e-4 * alpha) * rref || !std::isfinite(rref);
    } else {
      ok = true;  // energy merit but no potential (Prony history): the full step, as the fast model
    }
    if (ok) break;
    if (backtracks >= np.max_backtracks) {
      if (!std::isfinite(rt))
        throw Error("reference: non-finite residual in Newton iteration " + std::to_string(k + 1) +
                    " at t = " + std::to_string(t) + " (step too large or element inversion)");
      break;
    }
    double next = 0.5 * alpha;
    if (s.energy && std::isfinite(pi)) {  // minimiser of the quadratic through Pi(0), Pi'(0), Pi(alpha)
      const double curvature = pi - pi_ref - slope * alpha;
      if (curvature > 0.0)
        next = std::clamp(-slope * alpha * alpha / (2.0 * curvature), 0.1 * alpha, 0.5 * alpha);
    }
    alpha = next;
    ++backtracks;
  }
  return {rt, backtracks};
}

/// One line per solve: the iterations and the residual history.
void log_newton(std::ostream& log, double t, int iterations, const std::vector<double>& residuals,
                bool converged) {
  std::ostringstream s;
  s << "    t = " << std::setprecision(6) << t << ": " << iterations << " Newton iterations, |R| =";
  for (double v : residuals) s << " " << std::setprecision(3) << std::scientific << v << std::defaultfloat;
  s << (converged ? "" : "  (not converged)") << "\n";
  log << s.str() << std::flush;
}

}  // namespace

double Solid::prescribed_increments(double t, const TrilinosWrappers::MPI::Vector& g,
                                    AffineConstraints<double>& first,
                                    TrilinosWrappers::MPI::Vector& du_c) const {
  double max_duc = 0.0;
  std::vector<global_dof_index> idx;
  std::vector<double> val;
  for (const auto& p : prescribed_) {
    const double target = p.value * conditions_[p.condition].f(t);
    const double d = target - g[p.dof];
    first.add_line(p.dof);
    first.set_inhomogeneity(p.dof, d);
    if (owned_.is_element(p.dof)) {
      idx.push_back(p.dof);
      val.push_back(d);
      max_duc = std::max(max_duc, std::abs(d));
    }
  }
  first.close();
  du_c.set(idx, val);
  du_c.compress(VectorOperation::insert);
  return Utilities::MPI::max(max_duc, comm_);
}

void Solid::newton_direction(double t, double dt, const TrilinosWrappers::MPI::Vector& u,
                             const AffineConstraints<double>& constraints, TrilinosWrappers::MPI::Vector& du,
                             StepStats& stats) {
  TrilinosWrappers::MPI::Vector g(owned_, relevant_, comm_), r(owned_, comm_), rhs(owned_, comm_);
  {
    const auto t0 = Clock::now();
    g = u;
    assemble(g, t, dt, Mode::ResidualAndTangent, &constraints, r, &K_, &rhs);
    stats.assembly_seconds += seconds_since(t0);
  }
  {
    const auto t0 = Clock::now();
    stats.linear_iterations += linear_solve(du, rhs);
    stats.solve_seconds += seconds_since(t0);
  }
  constraints.distribute(du);
}

bool Solid::newton(double t, double dt, TrilinosWrappers::MPI::Vector& u, StepStats& stats) {
  TrilinosWrappers::MPI::Vector g(owned_, relevant_, comm_), r(owned_, comm_), r_trial(owned_, comm_),
      du(owned_, comm_), du_c(owned_, comm_), u_trial(owned_, comm_);
  g = u;

  // Prescribed increments du_c = g(t) - u on the Dirichlet DoFs, applied in the first iteration
  // through inhomogeneous constraints (the free DoFs then get K_ff du_f = -r_f - K_fc du_c).
  AffineConstraints<double> first(relevant_);
  bool pending = prescribed_increments(t, g, first, du_c) > 0.0;

  auto residual = [&](const TrilinosWrappers::MPI::Vector& v, TrilinosWrappers::MPI::Vector& out) {
    const auto t0 = Clock::now();
    g = v;
    assemble(g, t, dt, Mode::Residual, nullptr, out, nullptr, nullptr);
    stats.assembly_seconds += seconds_since(t0);
    return free_norm(out);
  };

  // Force scale for the relative tolerance, as the tensor-mass solver: the larger of |f_ext(t)|
  // and |f_int(u0)| over all DOFs. The latter carries the reactions of prescribed displacements,
  // the only forces in a displacement-driven hold phase, where |R(u0)| is already at round-off.
  TrilinosWrappers::MPI::Vector fe(owned_, comm_);
  assemble(g, t, dt, Mode::External, nullptr, fe, nullptr, nullptr);
  const double fext_norm = fe.l2_norm();
  // Mode::External assembles r = -f_ext. Potential Pi(v) = int W dV - f_ext . v (dead loads; none
  // with Prony history, whose trial forces are not a gradient).
  const TrilinosWrappers::MPI::Vector minus_fext(fe);
  const bool has_potential = !prony_;
  auto potential = [&](const TrilinosWrappers::MPI::Vector& v) {
    g = v;
    const double phi = nodal_ && nodal_active_ ? nodal_->energy(g, t) : 0.0;
    return hyperelastic_energy(g) + (minus_fext * v) + phi;
  };

  double rnorm = residual(u, r);
  stats.residuals.assign(1, rnorm);
  if (!std::isfinite(rnorm))
    throw Error("reference: non-finite residual at the start of the Newton iteration (t = " +
                std::to_string(t) + ")");
  fe += r;  // f_int(u0) = R(u0) + f_ext
  double scale = std::max({rnorm, fext_norm, fe.l2_norm()});
  bool converged = false;
  int iterations = 0;
  for (int k = 0; k < newton_.max_iterations; ++k) {
    if (!pending && rnorm <= newton_.rtol * scale + newton_.atol) {
      converged = true;
      break;
    }
    // Tangent and right-hand side -R with the constraints of this iteration.
    newton_direction(t, dt, u, pending ? first : hom_constraints_, du, stats);
    // Free part of the step (the constrained part du_c is always taken in full).
    TrilinosWrappers::MPI::Vector du_free(du);
    hom_constraints_.set_zero(du_free);

    // u_ref: the constrained DoFs moved in full; the search scales the free part of the step.
    TrilinosWrappers::MPI::Vector u_ref(u);
    u_ref += du_c;
    const SearchStart start =
        search_start(newton_, has_potential, pending, rnorm, residual, potential, u_ref, du_free, r, r_trial);
    if (pending) scale = std::max(scale, start.rref);
    const auto [rt, backtracks] =
        line_search(newton_, start, residual, potential, u_ref, du_free, u_trial, r_trial, k, t);
    stats.backtracks += backtracks;
    // Size of the step actually taken, for the round-off stagnation test.
    TrilinosWrappers::MPI::Vector step(u_trial);
    step -= u;
    const double step_inf = step.linfty_norm();
    const double rprev = rnorm;
    const bool was_pending = pending;
    u.swap(u_trial);
    r.swap(r_trial);
    rnorm = rt;
    du_c = 0.0;
    pending = false;
    iterations = k + 1;
    stats.residuals.push_back(rnorm);
    // Round-off: |R| fell by less than 2x with a step at the round-off of u. Within 1e3 of the
    // target that is the floor of this residual (converged); far above, further steps cannot help.
    if (!was_pending && k >= 1 && rnorm > 0.5 * rprev &&
        step_inf <= newton_.stagnation_tol * std::max(u.linfty_norm(), 1e-300)) {
      const double target = newton_.rtol * scale + newton_.atol;
      converged = rnorm <= 1e3 * target;
      if (converged && rnorm > target) stats.at_roundoff = true;
      break;
    }
  }
  if (!converged && !pending && rnorm <= newton_.rtol * scale + newton_.atol) converged = true;
  stats.newton_iterations += iterations;
  if (log_ && Utilities::MPI::this_mpi_process(comm_) == 0)
    log_newton(*log_, t, iterations, stats.residuals, converged);
  return converged;
}

void Solid::commit(double dt) {
  if (!prony_) return;
  // Recompute the trial history at the converged state, then make it the committed one.
  TrilinosWrappers::MPI::Vector r(owned_, comm_);
  assemble(u_ghost_, t_committed_, dt, Mode::Residual, nullptr, r, nullptr, nullptr);
  for (const auto& cell : tria_.active_cell_iterators())
    if (cell->is_locally_owned())
      for (auto& d : qp_data_.get_data(cell)) d->prony.commit();
}

bool Solid::solve(double t, double dt, TrilinosWrappers::MPI::Vector& u, StepStats& stats) {
  if (!nodal_) return newton(t, dt, u, stats);
  // The outer loop of the nodal constraints: Newton with the multipliers fixed, then their update
  // and stopping test (contact.hpp), from the committed multipliers of the last accepted increment.
  nodal_->begin_increment();
  TrilinosWrappers::MPI::Vector g(owned_, relevant_, comm_);
  for (int outer = 0; outer < nodal_->max_outer_iterations(); ++outer) {
    ++stats.outer_iterations;
    if (!newton(t, dt, u, stats)) return false;
    g = u;
    if (nodal_->update(g, t)) return true;
  }
  return false;
}

StepStats Solid::advance(double t0, double t1) {
  if (!setup_done_) finalize_setup();
  // The nodal terms enter the assembly only inside advance() (reactions() and the tests' residuals
  // stay f_int - f_ext).
  struct Active {
    bool& flag;
    explicit Active(bool& f) : flag(f) { flag = true; }
    ~Active() { flag = false; }
  } active(nodal_active_);
  const auto start = Clock::now();
  StepStats stats;
  stats.t = t1;
  double t_done = t0, h = t1 - t0;
  int depth = 0;
  while (t_done < t1) {
    const double t_try = (t1 - t_done <= h * (1.0 + 1e-12)) ? t1 : t_done + h;
    TrilinosWrappers::MPI::Vector u_try(u_);
    bool ok = false;
    try {
      ok = solve(t_try, t_try - t_done, u_try, stats);
    } catch (const Error&) {
      if (depth >= newton_.max_cutbacks) throw;
    } catch (const SolverControl::NoConvergence&) {
      if (depth >= newton_.max_cutbacks) throw;
    }
    if (ok) {
      u_ = u_try;
      u_ghost_ = u_;
      t_committed_ = t_try;
      commit(t_try - t_done);
      if (nodal_) nodal_->commit(u_ghost_, t_try);
      t_done = t_try;
      ++stats.sub_increments;
      if (depth > 0) {  // success after a cut-back: let the increment grow back
        h *= 2.0;
        --depth;
      }
      continue;
    }
    if (depth >= newton_.max_cutbacks) {
      std::ostringstream msg;
      msg << "reference: static Newton did not converge at t = " << t_try << " after " << newton_.max_cutbacks
          << " cut-backs of the load increment (last residual "
          << (stats.residuals.empty() ? 0.0 : stats.residuals.back()) << ")";
      if (nodal_) msg << "; " << nodal_->describe();
      throw Error(msg.str());
    }
    h *= 0.5;
    ++depth;
    ++stats.cutbacks;
  }
  stats.newton_seconds = seconds_since(start);
  return stats;
}

// =====================================================================================================
// Post-processing
// =====================================================================================================

namespace {
/// Total PK2 stress of the committed state (the history is not advanced).
SymTensor2 committed_stress(const Material& m, const std::optional<PronySeries>& p, const PronyState* s,
                            const SymTensor2& E) {
  SymTensor2 S = m.stress(E);
  if (p && s)
    for (std::size_t j = 0; j < p->size(); ++j) S += p->alpha[j] * s->h[j];
  return S;
}
}  // namespace

double Solid::hyperelastic_energy(const TrilinosWrappers::MPI::Vector& u_ghost) const {
  return stored_energy(u_ghost, false);
}

double Solid::elastic_energy() const { return stored_energy(u_ghost_, true); }

double Solid::stored_energy(const TrilinosWrappers::MPI::Vector& u_ghost, bool with_history) const {
  FEValues<3> fev(*mapping_, *fe_, qcell_, update_gradients | update_JxW_values);
  const FEValuesExtractors::Vector disp(0);
  std::vector<Tensor<2, 3>> grad_u(qcell_.size());
  double w = 0.0;
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    fev.reinit(cell);
    fev[disp].get_function_gradients(u_ghost, grad_u);
    if (disc_.mean_dilatation) {  // int W(Ebar) dV (no Prony history with mean dilatation)
      w += mean_dilatation_energy(material_, fev, grad_u);
      continue;
    }
    for (unsigned q = 0; q < qcell_.size(); ++q) {
      const Tensor<2, 3> F = unit_symmetric_tensor<3>() + grad_u[q];
      const SymTensor2 E = 0.5 * (symmetrize(transpose(F) * F) - unit_symmetric_tensor<3>());
      w += material_.energy(E) * fev.JxW(q);
      // Stored energy of the Maxwell branches, Psi_j = alpha_j/2 h_j : C0^-1 : h_j with C0 the
      // small-strain (Lame) elasticity (deviatoric: h_j : h_j / (2 mu)), as the tensor-mass model.
      if (with_history && prony_) {
        const auto& st = qp_data_.get_data(cell)[q]->prony;
        for (std::size_t j = 0; j < prony_->size(); ++j) {
          const SymTensor2& h = st.h[j];
          double hh = h * h;
          if (!prony_->deviatoric)
            hh -= material_.lambda / (3.0 * material_.lambda + 2.0 * material_.mu) * trace(h) * trace(h);
          w += 0.5 * prony_->alpha[j] * hh / (2.0 * material_.mu) * fev.JxW(q);
        }
      }
    }
  }
  return Utilities::MPI::sum(w, comm_);
}

double Solid::min_volume_ratio() const {
  FEValues<3> fev(*mapping_, *fe_, qcell_, update_gradients);
  const FEValuesExtractors::Vector disp(0);
  std::vector<Tensor<2, 3>> grad_u(qcell_.size());
  double jmin = std::numeric_limits<double>::infinity();
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    fev.reinit(cell);
    fev[disp].get_function_gradients(u_ghost_, grad_u);
    for (unsigned q = 0; q < qcell_.size(); ++q)
      jmin = std::min(jmin, determinant(Tensor<2, 3>(unit_symmetric_tensor<3>()) + grad_u[q]));
  }
  return Utilities::MPI::min(jmin, comm_);
}

std::vector<Tensor<1, 3>> Solid::reactions(double t) const {
  // R = f_int - f_ext at the committed state: dt = 0 evaluates the committed history unchanged.
  auto* self = const_cast<Solid*>(this);
  TrilinosWrappers::MPI::Vector r(owned_, comm_);
  self->assemble(u_ghost_, t, 0.0, Mode::Residual, nullptr, r, nullptr, nullptr);
  std::vector<Tensor<1, 3>> out(conditions_.size());
  for (const auto& p : prescribed_)
    if (owned_.is_element(p.dof)) out[p.condition][p.component] += r[p.dof];
  for (auto& v : out)
    for (unsigned c = 0; c < 3; ++c) v[c] = Utilities::MPI::sum(v[c], comm_);
  return out;
}

void Solid::cell_fields(Vector<float>& volume_ratio, Vector<float>& von_mises) const {
  FEValues<3> fev(*mapping_, *fe_, qcell_, update_gradients | update_JxW_values);
  const FEValuesExtractors::Vector disp(0);
  std::vector<Tensor<2, 3>> grad_u(qcell_.size());
  volume_ratio.reinit(tria_.n_active_cells());
  von_mises.reinit(tria_.n_active_cells());
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    fev.reinit(cell);
    fev[disp].get_function_gradients(u_ghost_, grad_u);
    std::vector<std::shared_ptr<const QPData>> qp;
    if (prony_) qp = qp_data_.get_data(cell);
    double vol = 0.0, jsum = 0.0, vmsum = 0.0;
    // With mean dilatation the stress is the law's at Fbar (det Fbar = Jbar); the mean of det F is Jbar.
    std::optional<MeanDilatationKinematics> md;
    if (disc_.mean_dilatation) md = mean_dilatation_kinematics(fev, grad_u);
    for (unsigned q = 0; q < qcell_.size(); ++q) {
      const Tensor<2, 3> F = unit_symmetric_tensor<3>() + grad_u[q];
      const Tensor<2, 3> Fe = md ? md->Fbar[q] : F;  // the law's F
      const SymTensor2 E = 0.5 * (symmetrize(transpose(Fe) * Fe) - unit_symmetric_tensor<3>());
      const SymTensor2 S = committed_stress(material_, prony_, prony_ ? &qp[q]->prony : nullptr, E);
      const double J = determinant(F);
      const SymTensor2 sigma = symmetrize(Fe * Tensor<2, 3>(S) * transpose(Fe)) / determinant(Fe);
      const SymTensor2 dev = deviator(sigma);
      jsum += J * fev.JxW(q);
      vmsum += std::sqrt(1.5 * (dev * dev)) * fev.JxW(q);
      vol += fev.JxW(q);
    }
    volume_ratio[cell->active_cell_index()] = static_cast<float>(jsum / vol);
    von_mises[cell->active_cell_index()] = static_cast<float>(vmsum / vol);
  }
}

}  // namespace tmlab::ref
