// The recording of a run's steps: the scalar series (core::Recorder), the work of the loads and
// supports, the inversion check, and at field frames displacement.h5, fields.xdmf and vtu/; its
// part of the run's checkpoint.
#pragma once

#include "core/io/vtu_writer.hpp"
#include "core/io/xdmf_writer.hpp"
#include "core/results/checkpoint.hpp"
#include "core/results/recorder.hpp"
#include "core/results/run_output.hpp"
#include "runner/problem.hpp"
#include "tensormass/contact/contact_solver.hpp"

#include <memory>
#include <vector>

namespace tmlab::tm::runner {

/// Records the steps of a run: the scalar series (core::Recorder), the work of the loads and
/// supports, and at field frames displacement.h5, fields.xdmf and vtu/.
class StepRecorder {
 public:
  /// Opens displacement.h5 and, as the case asks, fields.xdmf and result.pvd in `out`.
  StepRecorder(const Problem& p, const RunOutput& out);

  /// Records the scalar series of one step and, when asked, the fields. An inverted element (volume
  /// ratio <= 0) throws tmlab::Error naming the tet, the time and the step.
  void record(int step, double t, const VecX& u, const VecX& v, int newton_its, bool write_fields);

  /// Writes timeseries.h5 and closes the field files.
  void close();

  const Recorder& recorder() const { return rec_; }
  double external_work() const { return external_work_; }
  /// The contact outputs recorded with every later step (the contact solver's own state, which
  /// must outlive the recording): the per-body series, the nodal contact forces in the work of
  /// the loads, and the contact pressure field.
  void set_contact(const std::vector<ContactBodyState>* states) { contact_ = states; }

  /// Checkpoints: the series so far, the work bookkeeping and every field frame (t, u, v); restore()
  /// rewrites the field files by replaying the frames, so they never depend on the interrupted files.
  void save(CheckpointData& d) const;
  void restore(const CheckpointData& d);

 private:
  Recorder::StepValues values(int step, double t, const VecX& u, const VecX& v, int newton_its);
  /// The nodal contact pressure of all bodies (0 off contact), Pa.
  std::vector<double> contact_pressure() const;
  /// Fields: displacement, velocity; per tet volume ratio, Green strain, Cauchy stress, von Mises.
  /// `pressure`: the contact pressure of a frame replayed from a checkpoint (null: the current one).
  void fields(double t, const VecX& u, const VecX& v, const std::vector<double>* pressure = nullptr);

  const Problem& p_;
  const RunOutput& out_;
  Recorder rec_;
  std::unique_ptr<XdmfTimeSeries> xdmf_;
  std::unique_ptr<PvdWriter> pvd_;
  VecX fint_, fext_;
  double external_work_ = 0.0;
  VecX f_applied_prev_, u_prev_;
  const std::vector<ContactBodyState>* contact_ = nullptr;
  std::vector<double> frames_t_, frames_u_, frames_v_;  ///< every field frame so far (checkpoints)
  std::vector<double> frames_p_;                        ///< and its contact pressure (contact runs)
};

}  // namespace tmlab::tm::runner
