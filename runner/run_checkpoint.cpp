// The run's checkpoint: see run_checkpoint.hpp.
#include "runner/run_checkpoint.hpp"

#include "core/base/interrupt.hpp"
#include "core/results/run_output.hpp"

#include <vector>

namespace tmlab::tm::runner {

namespace {

std::vector<double> as_std(const VecX& x) { return {x.data(), x.data() + x.size()}; }
VecX as_vec(const std::vector<double>& x) {
  return Eigen::Map<const VecX>(x.data(), static_cast<Eigen::Index>(x.size()));
}

}  // namespace

RunCheckpoint::RunCheckpoint(const Problem& p, const std::filesystem::path& dir, const RunOptions& opt)
    : p_(p),
      path_(dir / RunOutput::kStaging / "checkpoint.h5"),
      fingerprint_(effective_case_json(p.cfg)),
      clock_(opt.checkpoints),
      log_(opt.log) {
  if (opt.resume) resume_ = read_checkpoint(path_, "run", fingerprint_);
}

int RunCheckpoint::restore(StepRecorder& rec, const LoopState& loop, const ContactLoop* contact) {
  if (!resume_) return 0;
  const CheckpointData& d = *resume_;
  const int step = static_cast<int>(d.integer("step"));
  loop.t = d.scalar("t");
  loop.s.u = as_vec(d.doubles("u"));
  loop.s.v = as_vec(d.doubles("v"));
  p_.model->restore_committed_state(d.doubles("model.committed"));
  if (loop.central)
    loop.central->restore(loop.t, d.integer("explicit.steps"), loop.s.u, as_vec(d.doubles("explicit.v_half")),
                          loop.s.v);
  if (loop.implicit) loop.implicit->restore(loop.t, loop.s.u, loop.s.v, as_vec(d.doubles("implicit.a")));
  if (loop.newton) loop.newton->restore(d);
  if (loop.total_newton) *loop.total_newton = d.integer("total_newton");
  if (loop.total_cutbacks) *loop.total_cutbacks = d.integer("total_cutbacks");
  if (contact) restore_contact(d, loop, *contact);
  rec.restore(d);
  last_step_ = step;
  if (log_)
    *log_ << "tmlab: resuming '" << p_.cfg.name << "' after step " << step << " (t = " << loop.t << ") from "
          << path_.string() << "\n";
  resume_.reset();  // the memory of the frames is not needed twice
  return step;
}

void RunCheckpoint::after_step(int step, const StepRecorder& rec, const LoopState& loop,
                               const ContactLoop* contact) {
  if (!(pending_interrupt() != 0 || clock_.due(step))) return;
  CheckpointData d;
  d.put_int("step", step);
  d.put_scalar("t", loop.t);
  d.put("u", as_std(loop.s.u));
  d.put("v", as_std(loop.s.v));
  d.put("model.committed", p_.model->committed_state());
  if (loop.central) {
    d.put_int("explicit.steps", loop.central->steps());
    d.put("explicit.v_half", as_std(loop.central->half_step_velocity()));
  }
  if (loop.implicit) d.put("implicit.a", as_std(loop.implicit->acceleration()));
  if (loop.newton) loop.newton->save(d);
  if (loop.total_newton) d.put_int("total_newton", *loop.total_newton);
  if (loop.total_cutbacks) d.put_int("total_cutbacks", *loop.total_cutbacks);
  if (contact) save_contact(d, *contact);
  rec.save(d);
  write_checkpoint(path_, "run", fingerprint_, d);
  clock_.mark();
  last_step_ = step;
}

std::string RunCheckpoint::where() const {
  if (last_step_ < 0) return "; no checkpoint was written: run again without --resume";
  return "; checkpoint after step " + std::to_string(last_step_) + " in " + path_.string() +
         ": continue with the same command and --resume";
}

void RunCheckpoint::remove() const { remove_checkpoint(path_); }

}  // namespace tmlab::tm::runner
