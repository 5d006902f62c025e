#include "tensormass/system/mechanical_system.hpp"

#include "core/base/error.hpp"

#include <cmath>

namespace tmlab::tm {

MechanicalSystem::MechanicalSystem(ElasticModel& model, VecX dof_mass, DirichletSet bc, ExternalLoads loads,
                                   RayleighDamping damping)
    : model_(model),
      mass_(std::move(dof_mass)),
      bc_(std::move(bc)),
      loads_(std::move(loads)),
      damping_(damping) {
  if (mass_.size() != model_.num_dofs()) throw Error("mass vector size does not match the model's DOF count");
  if (!(damping_.alpha >= 0.0) || !(damping_.beta >= 0.0) || !std::isfinite(damping_.alpha) ||
      !std::isfinite(damping_.beta))
    throw Error("Rayleigh damping coefficients must be finite and >= 0");
}

const SpMat& MechanicalSystem::reference_tangent() const {
  if (!k0_ready_) {
    model_.tangent(VecX::Zero(num_dofs()), k0_);
    k0_ready_ = true;
  }
  return k0_;
}

void MechanicalSystem::add_load_stiffness(const VecX& u, double t, SpMat& J) const {
  if (!loads_.has_follower()) return;
  std::vector<Eigen::Triplet<double>> trip;
  loads_.add_load_stiffness(u, t, trip);
  SpMat kl(J.rows(), J.cols());
  kl.setFromTriplets(trip.begin(), trip.end());
  J += kl;
}

void MechanicalSystem::damping_force(const VecX& v, VecX& out) const {
  out = damping_.alpha * mass_.cwiseProduct(v);
  if (damping_.beta != 0.0) out += damping_.beta * (reference_tangent() * v);
}

}  // namespace tmlab::tm
