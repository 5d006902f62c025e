// The elastic model a case file asks for: see model_factory.hpp.
#include "runner/model_factory.hpp"

#include "core/base/error.hpp"
#include "core/config/element_kind.hpp"
#include "core/config/fast_model.hpp"

#include <Eigen/Geometry>
#include "tensormass/kernels/averaged_pressure_tet.hpp"
#include "tensormass/kernels/hyperelastic_p2.hpp"
#include "tensormass/kernels/hyperelastic_tl.hpp"
#include "tensormass/kernels/tensor_mass.hpp"
#include "tensormass/kernels/tl_oracle.hpp"
#include "tensormass/system/lumped_mass.hpp"
#include "tensormass/viscoelastic/prony_series.hpp"
#include "tensormass/viscoelastic/viscoelastic_law.hpp"
#include "tensormass/viscoelastic/viscoelastic_law_anp.hpp"
#include "tensormass/viscoelastic/viscoelastic_law_p2.hpp"
#include "tensormass/viscoelastic/viscoelastic_model.hpp"

namespace tmlab::tm::runner {

std::unique_ptr<QuadraticMesh> make_quadratic_mesh(const CaseConfig& cfg, const Mesh& mesh) {
  if (!is_quadratic(cfg.mesh.element)) return nullptr;
  return std::make_unique<QuadraticMesh>(make_quadratic(mesh));
}

VecX make_node_mass(const CaseConfig& cfg, const Mesh& mesh, const QuadraticMesh* quadratic) {
  if (!quadratic) return lumped_node_mass(mesh, cfg.material.density);
  // HRZ lumping (tensormass/system/lumped_mass.hpp): row sums give negative vertex masses for P2.
  if (!(cfg.material.density > 0.0)) throw Error(cfg.file + ": key 'material.density' must be > 0");
  return hrz_lumped_node_mass(*quadratic, cfg.material.density);
}

std::unique_ptr<ElasticModel> make_model(const CaseConfig& cfg, const Mesh& mesh,
                                         const QuadraticMesh* quadratic, const StVenantKirchhoff& material,
                                         const Law& law, const ViscoelasticBase*& visco) {
  check_element_support(cfg, cfg.model);
  if (is_quadratic(cfg.mesh.element) != (quadratic != nullptr))
    throw Error(cfg.file + ": key 'mesh.element': '" + to_string(cfg.mesh.element) +
                "' and the mesh given to the model do not match (internal)");
  if (fast_model_for(cfg.material.law) != CaseModel::TensorMass && cfg.model != CaseModel::HyperelasticTL)
    throw Error(
        cfg.file + ": key 'model': '" + to_string(cfg.model) + "' is " +
        (cfg.model == CaseModel::TensorMass ? "the paper's St Venant-Kirchhoff tensor-mass model"
                                            : "the St Venant-Kirchhoff oracle") +
        "; material.law '" + to_string(cfg.material.law) +
        "' runs on the F-based kernel: set \"model\": \"hyperelastic_tl\" (or --model hyperelastic_tl)");
  const ViscoelasticSpec& vs = cfg.material.viscoelastic;
  if (vs.enabled) {
    // Prony-series viscoelasticity; the law's parameters (material.E for St VK) are the long-term ones.
    if (cfg.model == CaseModel::TlOracle)
      throw Error(
          cfg.file +
          ": key 'model': the tl_oracle kernel is elastic only; use tensor_mass or hyperelastic_tl for "
          "a viscoelastic material");
    const PronySeries prony = vs.convention == PronyConvention::Instantaneous
                                  ? PronySeries::from_instantaneous(vs.weights, vs.taus)
                                  : PronySeries::from_long_term(vs.weights, vs.taus);
    ViscoelasticOptions vo;
    vo.history = vs.history;
    vo.integration = vs.integration;
    vo.relaxation = vs.relaxation;
    if (cfg.model == CaseModel::HyperelasticTL) {
      // The objective scheme on any law (history pk2, relaxation full; the class refuses the rest).
      if (quadratic) {
        std::unique_ptr<ViscoelasticHyperelasticP2> vm;
        try {
          vm = std::make_unique<ViscoelasticHyperelasticP2>(*quadratic, law, prony, vo);
        } catch (const Error& e) {
          throw Error(cfg.file +
                      ": key 'material.viscoelastic' (model hyperelastic_tl, element p2): " + e.what());
        }
        visco = vm.get();
        return vm;
      }
      if (cfg.mesh.element == ElementKind::P1Anp) {
        std::unique_ptr<ViscoelasticAveragedPressureTet> vm;
        try {
          vm = std::make_unique<ViscoelasticAveragedPressureTet>(mesh, law, prony, vo);
        } catch (const Error& e) {
          throw Error(cfg.file +
                      ": key 'material.viscoelastic' (model hyperelastic_tl, element p1_anp): " + e.what());
        }
        visco = vm.get();
        return vm;
      }
      std::unique_ptr<ViscoelasticHyperelastic> vm;
      try {
        vm = std::make_unique<ViscoelasticHyperelastic>(mesh, law, prony, vo);
      } catch (const Error& e) {
        throw Error(cfg.file + ": key 'material.viscoelastic' (model hyperelastic_tl): " + e.what());
      }
      visco = vm.get();
      return vm;
    }
    auto vm = std::make_unique<ViscoelasticStVK>(mesh, material, prony, vo);
    visco = vm.get();
    return vm;
  }
  if (quadratic) {
    P2Options po;
    po.volumetric = cfg.mesh.element == ElementKind::P2MeanDilatation ? P2Options::Volumetric::MeanDilatation
                                                                      : P2Options::Volumetric::Standard;
    return std::make_unique<HyperelasticP2>(*quadratic, law, po);
  }
  if (cfg.mesh.element == ElementKind::P1Anp) {
    return std::make_unique<AveragedPressureTet>(mesh, law);
  }
  if (cfg.model == CaseModel::HyperelasticTL) return std::make_unique<HyperelasticTL>(mesh, law);
  if (cfg.model == CaseModel::TlOracle) return std::make_unique<TotalLagrangianStVK>(mesh, material);
  return std::make_unique<TensorMassStVK>(mesh, material);
}

}  // namespace tmlab::tm::runner
