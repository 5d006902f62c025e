// RealtimeCase::make_control: the control model of a real-time case. Kept apart from the case
// reader (realtime_case.cpp) so that the reader builds without the model (the fuzz target
// fuzz_realtime_case links the reader alone).
#include "realtime/realtime_case.hpp"

namespace tmlab::rt {

std::unique_ptr<ControlModel> RealtimeCase::make_control(double dt_override) const {
  ControlOptions o = control;
  if (dt_override > 0.0) o.dt = dt_override;
  auto m = std::make_unique<ControlModel>(mesh, material, prony, viscoelastic, density, fixed_nodes, o);
  m->reset(probe_start);
  return m;
}

}  // namespace tmlab::rt
