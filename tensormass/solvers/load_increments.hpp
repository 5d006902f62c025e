// LoadIncrements: the sub-increments of one load step [t_prev, t_next] with cut-backs, as the static
// solver (static_solver.hpp) and the contact loop around it (tensormass/contact/contact_solver.hpp)
// take them. The first attempt is the whole step; a failed attempt halves the increment (at most
// max_cutbacks halvings deep); a success after a cut-back lets the increment grow back (doubles it).
// An attempt ends at t_next when what is left fits in the increment to a relative 1e-12, so round-off
// never leaves a sliver of a step.
#pragma once

namespace tmlab::tm {

class LoadIncrements {
 public:
  LoadIncrements(double t_prev, double t_next, int max_cutbacks)
      : t_done_(t_prev), t_next_(t_next), h_(t_next - t_prev), max_cutbacks_(max_cutbacks) {}

  /// True while part of the step is left.
  bool more() const { return t_done_ < t_next_; }
  /// The end of the load reached so far.
  double done() const { return t_done_; }
  /// The end of the next attempt.
  double next() const { return (t_next_ - t_done_ <= h_ * (1.0 + 1e-12)) ? t_next_ : t_done_ + h_; }
  /// The attempt ending at t_try succeeded.
  void accept(double t_try);
  /// True when the increment may not be halved again (a failure now is final).
  bool exhausted() const { return depth_ >= max_cutbacks_; }
  /// A failed attempt: halves the increment (call only when !exhausted()).
  void cut_back();
  /// How many halvings deep the current increment is.
  int depth() const { return depth_; }

 private:
  double t_done_, t_next_, h_;
  int max_cutbacks_;
  int depth_ = 0;
};

}  // namespace tmlab::tm
