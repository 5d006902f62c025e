// A contact run's part of the run's checkpoint (runner/run_checkpoint.hpp): the committed contact
// state (multipliers, active candidates, glued nodes and anchors; the bodies' positions follow from
// t), the contact outputs of the last step, the implicit integrator's acceleration and the
// summary's contact log, saved as "contact.*" entries and restored exactly.
#pragma once

#include "core/results/checkpoint.hpp"
#include "runner/contact_log.hpp"
#include "runner/loop_state.hpp"
#include "tensormass/contact/contact_implicit.hpp"
#include "tensormass/contact/contact_solver.hpp"
#include "tensormass/contact/kinematic_contact.hpp"

#include <cstddef>
#include <vector>

namespace tmlab::tm::runner {

/// The contact objects of a contact run's loop (null: not in this loop), checkpointed besides the
/// LoopState: the committed contact state (multipliers, active candidates, glued nodes and anchors;
/// the bodies' positions follow from t), the outputs of the last step, and the summary's log.
struct ContactLoop {
  ContactStaticSolver* augmented = nullptr;  ///< static, and implicit dynamics' contact()
  KinematicContact* kinematic = nullptr;     ///< explicit
  ContactImplicitDynamics* implicit = nullptr;
  ContactLog* log = nullptr;
};
/// Saves the contact objects of `c` that are set.
void save_contact(CheckpointData& d, const ContactLoop& c);
/// Restores what save_contact saved; inconsistent entries throw tmlab::Error naming the file.
void restore_contact(const CheckpointData& d, const LoopState& loop, const ContactLoop& c);

/// The contact outputs of every body ("contact.out.<b>.*"), exactly.
void save_contact_outputs(CheckpointData& d, const std::vector<ContactBodyState>& states);
/// The outputs of `n_bodies` bodies back; inconsistent entries throw tmlab::Error naming the file.
std::vector<ContactBodyState> restore_contact_outputs(const CheckpointData& d, std::size_t n_bodies);

}  // namespace tmlab::tm::runner
