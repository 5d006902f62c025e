#include "tensormass/solvers/load_increments.hpp"

#include <cassert>

namespace tmlab::tm {

void LoadIncrements::accept(double t_try) {
  t_done_ = t_try;
  if (depth_ > 0) {  // success after a cut-back: let the increment grow back
    h_ *= 2.0;
    --depth_;
  }
}

void LoadIncrements::cut_back() {
  assert(!exhausted());
  h_ *= 0.5;
  ++depth_;
}

}  // namespace tmlab::tm
