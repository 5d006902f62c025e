// The recording of a run's steps: see step_recorder.hpp.
#include "runner/step_recorder.hpp"

#include "core/base/error.hpp"
#include "core/results/series_names.hpp"
#include "core/results/series_table.hpp"
#include "runner/cell_fields.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <sstream>
#include <string>

namespace tmlab::tm::runner {

namespace {

std::vector<Vec3> as_vec3(const VecX& u) {
  std::vector<Vec3> out(static_cast<std::size_t>(u.size() / 3));
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = u.segment<3>(3 * static_cast<Eigen::Index>(i));
  return out;
}

/// The recorder of the problem's conditions and probes.
Recorder make_recorder(const Problem& p) {
  std::vector<std::string> conditions, probes;
  for (const auto& c : p.conditions) conditions.push_back(c.name);
  for (const auto& pr : p.cfg.output.probes) probes.push_back(pr.name);
  return Recorder(conditions, probes, p.probe_nodes);
}

series_names::ContactValues contact_values(const ContactBodyState& b) {
  double max_pressure = 0.0;
  for (double pr : b.pressure) max_pressure = std::max(max_pressure, pr);
  return series_names::contact_values(b, max_pressure);
}

/// The contact forces on the sample's nodes, added to f.
void add_contact_forces(const std::vector<ContactBodyState>& states, VecX& f) {
  for (const ContactBodyState& b : states)
    for (std::size_t i = 0; i < b.nodes.size(); ++i)
      f.segment<3>(3 * static_cast<Eigen::Index>(b.nodes[i])) += b.nodal_force[i];
}

}  // namespace

StepRecorder::StepRecorder(const Problem& p, const RunOutput& out)
    : p_(p),
      out_(out),
      rec_(make_recorder(p)),
      f_applied_prev_(VecX::Zero(p.system.num_dofs())),
      u_prev_(VecX::Zero(p.system.num_dofs())) {
  if (p.cfg.output.xdmf) xdmf_ = std::make_unique<XdmfTimeSeries>(out.file("fields.xdmf"), p.node_mesh());
  if (p.cfg.output.vtu) pvd_ = std::make_unique<PvdWriter>(out.file("result.pvd"));
  // Nodal displacements at every field frame, in mesh node order: what `tmlab compare` diffs
  // against the deal.II reference (which writes the same file).
  rec_.open_displacements(out.file("displacement.h5"));
}

void StepRecorder::record(int step, double t, const VecX& u, const VecX& v, int newton_its,
                          bool write_fields) {
  rec_.record(values(step, t, u, v, newton_its));
  if (write_fields) fields(t, u, v);
}

void StepRecorder::close() {
  rec_.write_timeseries(out_.file("timeseries.h5"), {{"case", p_.cfg.name}});
  rec_.close_displacements("");
  if (xdmf_) xdmf_->close();
  if (pvd_) pvd_->write();
}

Recorder::StepValues StepRecorder::values(int step, double t, const VecX& u, const VecX& v, int newton_its) {
  const auto [jmin, jtet] = min_volume_ratio(p_.mesh, u);
  if (!(jmin > 0.0)) {
    std::ostringstream m;
    m << p_.mesh.tet_name(jtet) << " inverted at t = " << t << " (step " << step << ", volume ratio " << jmin
      << "): the load is beyond what the " << p_.law.name()
      << " tet mesh survives; reduce the load or refine the mesh";
    throw Error(m.str());
  }
  p_.model->internal_force(u, fint_);
  p_.system.loads().assemble(u, t, fext_);
  const VecX r = fint_ - fext_;
  // Work of the loads and supports on the body, by the trapezoidal rule over the recorded steps:
  // W += 1/2 (F_n + F_{n+1}) . (u_{n+1} - u_n), F = f_ext + reactions (exact for quasi-static
  // runs; in dynamics the reactions leave out the inertia of the prescribed nodes).
  VecX f_applied = fext_;
  for (Index d : p_.system.bc().dofs()) f_applied[d] += r[d];
  if (contact_) add_contact_forces(*contact_, f_applied);
  external_work_ += 0.5 * (f_applied_prev_ + f_applied).dot(u - u_prev_);
  f_applied_prev_ = f_applied;
  u_prev_ = u;
  Recorder::StepValues s;
  s.time = t;
  for (Index i = 0; i < p_.num_nodes(); ++i)
    s.max_displacement = std::max(s.max_displacement, u.segment<3>(3 * i).norm());
  // Stored energy: the elastic energy, or for a viscoelastic material the long-term spring plus
  // the Maxwell-branch energies of the committed state (the same definition as the deal.II
  // reference); dissipation is the model's own count.
  if (const ViscoelasticBase* m = p_.visco) {
    s.elastic_energy = m->committed_elastic_energy() + m->committed_branch_energy();
    s.extras = {{series_names::kSpringEnergy, "J", m->committed_elastic_energy()},
                {series_names::kBranchEnergy, "J", m->committed_branch_energy()},
                {series_names::kDissipatedEnergy, "J", m->total_dissipation()},
                {series_names::kStepDissipation, "J", m->step_dissipation()}};
  } else {
    s.elastic_energy = p_.model->energy(u);
  }
  s.extras.push_back({series_names::kExternalWork, "J", external_work_});
  s.kinetic_energy = 0.5 * v.dot(p_.system.mass().cwiseProduct(v));
  s.min_volume_ratio = jmin;
  s.newton_iterations = newton_its;
  for (std::size_t k = 0; k < p_.conditions.size(); ++k) {
    const Vec3 rk = p_.system.bc().resultant(k, r);
    s.reactions.push_back({rk.x(), rk.y(), rk.z()});
  }
  for (Index n : p_.probe_nodes) {
    const Vec3 up = u.segment<3>(3 * n);
    s.probes.push_back({up.x(), up.y(), up.z()});
  }
  if (contact_)
    for (const ContactBodyState& b : *contact_) s.contact.push_back(contact_values(b));
  return s;
}

std::vector<double> StepRecorder::contact_pressure() const {
  std::vector<double> pr(static_cast<std::size_t>(p_.num_nodes()), 0.0);
  for (const ContactBodyState& b : *contact_)
    for (std::size_t i = 0; i < b.nodes.size(); ++i)
      pr[static_cast<std::size_t>(b.nodes[i])] += b.pressure[i];
  return pr;
}

void StepRecorder::fields(double t, const VecX& u, const VecX& v, const std::vector<double>* pressure) {
  const std::vector<double> pc = !contact_  ? std::vector<double>{}
                                 : pressure ? *pressure
                                            : contact_pressure();
  frames_p_.insert(frames_p_.end(), pc.begin(), pc.end());
  frames_t_.push_back(t);
  frames_u_.insert(frames_u_.end(), u.data(), u.data() + u.size());
  frames_v_.insert(frames_v_.end(), v.data(), v.data() + v.size());
  const int frame = rec_.field_frames();
  // displacement.h5 holds the vertices' displacements (all nodes on linear tets; on quadratic ones the
  // vertices come first): the deal.II reference writes the same at any degree.
  const Eigen::Index nv = 3 * static_cast<Eigen::Index>(p_.mesh.num_points());
  rec_.add_field_frame(t, std::vector<double>(u.data(), u.data() + nv));
  const CellFields c = cell_fields(p_, u);
  const auto disp = as_vec3(u), vel = as_vec3(v);
  std::vector<double> umag(disp.size());
  for (std::size_t i = 0; i < disp.size(); ++i) umag[i] = disp[i].norm();
  if (xdmf_) {
    xdmf_->begin_step(t);
    xdmf_->add_point_vector("displacement", disp);
    xdmf_->add_point_vector("velocity", vel);
    xdmf_->add_cell_scalar("volume_ratio", c.jratio);
    xdmf_->add_cell_scalar("von_mises", c.von_mises);
    xdmf_->add_cell_tensor("green_strain", c.strain);
    xdmf_->add_cell_tensor("cauchy_stress", c.cauchy);
    if (contact_) xdmf_->add_point_scalar("contact_pressure", pc);
    xdmf_->flush();
  }
  if (pvd_) {
    VtuWriter w = p_.quadratic ? VtuWriter(p_.quadratic_nodes, *p_.quadratic) : VtuWriter(p_.mesh);
    w.set_displacement(disp);
    w.add_point_vector("displacement", disp);
    w.add_point_scalar("displacement_magnitude", umag);
    w.add_point_vector("velocity", vel);
    w.add_cell_scalar("volume_ratio", c.jratio);
    w.add_cell_scalar("von_mises", c.von_mises);
    w.add_cell_tensor("green_strain", c.strain);
    w.add_cell_tensor("cauchy_stress", c.cauchy);
    if (contact_) w.add_point_scalar("contact_pressure", pc);
    char name[64];
    std::snprintf(name, sizeof name, "vtu/step_%05d.vtu", frame);
    w.write(out_.file(name));
    pvd_->add(t, out_.file(name));
  }
}

void StepRecorder::save(CheckpointData& d) const {
  nlohmann::json names = nlohmann::json::array();
  const auto& series = rec_.table().series();
  for (std::size_t i = 0; i < series.size(); ++i) {
    names.push_back({series[i].name, series[i].unit});
    d.put("series." + std::to_string(i), series[i].values);
  }
  d.put_text("series.names", names.dump());
  d.put_scalar("work.external", external_work_);
  d.put("work.f_applied_prev",
        std::vector<double>(f_applied_prev_.data(), f_applied_prev_.data() + f_applied_prev_.size()));
  d.put("work.u_prev", std::vector<double>(u_prev_.data(), u_prev_.data() + u_prev_.size()));
  d.put("frames.t", frames_t_);
  d.put("frames.u", frames_u_);
  d.put("frames.v", frames_v_);
  if (contact_) d.put("frames.contact_pressure", frames_p_);
}

void StepRecorder::restore(const CheckpointData& d) {
  const nlohmann::json names = nlohmann::json::parse(d.text("series.names"));
  SeriesTable table;
  for (std::size_t i = 0; i < names.size(); ++i)
    for (const double v : d.doubles("series." + std::to_string(i)))
      table.add(names[i][0].get<std::string>(), names[i][1].get<std::string>(), v);
  rec_.restore_series(std::move(table));
  external_work_ = d.scalar("work.external");
  const auto& fp = d.doubles("work.f_applied_prev");
  const auto& up = d.doubles("work.u_prev");
  f_applied_prev_ = Eigen::Map<const VecX>(fp.data(), static_cast<Eigen::Index>(fp.size()));
  u_prev_ = Eigen::Map<const VecX>(up.data(), static_cast<Eigen::Index>(up.size()));
  // The field files again, frame by frame, exactly as the interrupted run wrote them.
  const auto& ft = d.doubles("frames.t");
  const auto& fu = d.doubles("frames.u");
  const auto& fv = d.doubles("frames.v");
  const std::size_t n = static_cast<std::size_t>(p_.system.num_dofs());
  const std::size_t np = static_cast<std::size_t>(p_.num_nodes());
  const std::vector<double> none;
  const auto& fpc = contact_ ? d.doubles("frames.contact_pressure") : none;
  if (fu.size() != ft.size() * n || fv.size() != ft.size() * n || (contact_ && fpc.size() != ft.size() * np))
    throw Error(d.source() + ": field frames of the wrong size (another mesh?); run without --resume");
  for (std::size_t f = 0; f < ft.size(); ++f) {
    const auto off = static_cast<std::ptrdiff_t>(f * n);
    const VecX u = Eigen::Map<const VecX>(fu.data() + off, static_cast<Eigen::Index>(n));
    const VecX v = Eigen::Map<const VecX>(fv.data() + off, static_cast<Eigen::Index>(n));
    if (!contact_) {
      fields(ft[f], u, v);
      continue;
    }
    const std::vector<double> pc(fpc.begin() + static_cast<std::ptrdiff_t>(f * np),
                                 fpc.begin() + static_cast<std::ptrdiff_t>((f + 1) * np));
    fields(ft[f], u, v, &pc);
  }
}

}  // namespace tmlab::tm::runner
