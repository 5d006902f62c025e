// The candidate effects of `tmlab discover` (issue 15; docs/discover.md) and the forward model
// they change. Every effect is a change of the forward model, never a curve added to the output:
//
//   material   extra_prony_term              one more term of the relaxation function
//              neo_hookean_hyperelastic, mooney_rivlin_hyperelastic, yeoh_hyperelastic,
//              ogden_hyperelastic, veronda_westmann_hyperelastic
//                                            the elastic law swapped (platen tests only: the
//                                            indentation closed forms see the small-strain modulus)
//              strain_dependent_relaxation   Prony weights alpha_j (1 + a eps): nonlinear viscoelasticity
//              poroelastic_relaxation        a relaxation term with tau = L^2 / D, L the contact radius
//                                            of each test: size-dependent (indentation only)
//              separate_bulk_shear_relaxation the bulk modulus relaxes to a drained Poisson ratio with
//                                            its own time (bulk_shear.hpp); on one rig's forces it is
//                                            confounded with extra_prony_term, so the loop does not try
//                                            it (not_applicable); the benchmark plants it
//   experiment contact_offset                the sample is touched at d0: d_sample = d - d0, no force before
//              force_offset                  the load cell reads F + F0
//              force_drift                   the load cell reads F + r t
//              displacement_drift            the actuator reads d while the sample sees d + v t
//              instrument_compliance         the frame deflects F c: d_sample + c F(d_sample) = d, solved
//                                            sample by sample with the relaxation state
//   geometry   platen_friction               bonded fraction phi of the platens: the Gent-Lindley
//                                            shape-factor stiffening 1 + 2 phi S^2, S the current loaded
//                                            over free area (grows with compression)
//              finite_layer_thickness        a half-space sample that is a bonded layer of thickness h
//                                            (the Dimitriadis factor; sphere indentation only)
//
// The forward model (DiscoverModel): the long-term elastic force X_e(d) of the data's rig (the
// homogeneous platen state of the law, Hertz or Sneddon), run through the hereditary integral of
// docs/theory/viscoelasticity.md section 2 with the exact-linear step
//   h_j <- exp(-dt/tau_j) h_j + tau_j/dt (1 - exp(-dt/tau_j)) dX_e,   F = X_e + sum_j alpha_j h_j,
// alpha_j = e_j / E_inf (E_inf the law's small-strain Young's modulus), then the experiment effects.
#pragma once

#include "calibration/data/measured_data.hpp"
#include "calibration/fit/forward_model.hpp"
#include "calibration/fit/model_spec.hpp"
#include "calibration/fit/parameter.hpp"
#include "core/constitutive/material_law.hpp"

#include <optional>
#include <string>
#include <vector>

namespace tmlab::discover {

enum class EffectKind { material, experiment, geometry };
std::string to_string(EffectKind k);

struct EffectInfo {
  std::string name;  ///< snake_case name of the physical effect
  EffectKind kind;
  std::string change;     ///< how it changes the forward model
  std::string signature;  ///< the residual signature it explains
};

/// Every effect of the library, in the order the loop tries them.
std::vector<EffectInfo> effect_library();
/// The library entry `name` (tmlab::Error listing the names when unknown).
EffectInfo effect_info(const std::string& name);
/// The law a *_hyperelastic effect swaps in (nothing for other effects).
std::optional<MaterialLaw> effect_law(const std::string& effect);

enum class Rig { platen_unconfined, platen_confined, tension, sphere, punch };
std::string to_string(Rig r);

/// One test, decimated, time from the test's start.
struct Series {
  std::string id;
  std::vector<double> t, d, f;
};

/// The data a discovery works on: the rig and its geometry, and the (decimated) tests.
struct Prepared {
  std::string name;
  Rig rig = Rig::platen_unconfined;
  double sign = 1.0;          ///< +1: displacement into the sample compresses it; -1 tension
  double height = 0.0;        ///< platen tests: sample height, m
  double area = 0.0;          ///< platen tests: reference cross-section, m^2
  double shape_factor = 0.0;  ///< platen tests: loaded over free lateral area, unloaded
  double radius = 0.0;        ///< indenter radius, m
  double layer = 0.0;         ///< indentation: the metadata's layer thickness (0: half-space), m
  bool layer_bonded = true;
  double strain_scale = 1.0;  ///< 1/height (platens) or 1/radius (indentation)
  std::vector<Series> series;
  std::size_t stride = 1;  ///< every stride-th sample kept
  double peak_force = 0.0, max_depth = 0.0, duration = 0.0, min_dt = 0.0;
  std::size_t size() const;
};

/// Checks `data` and keeps about `max_samples` samples in all (every k-th sample of each test,
/// the last always kept). tmlab::Error naming the data set for what no forward model can take.
Prepared prepare(const measured::DataSet& data, std::size_t max_samples);

/// The model structure: the law, the number of Prony terms and the other effects added.
struct Structure {
  MaterialLaw law = MaterialLaw::StVK;
  int prony_terms = 2;
  std::vector<std::string> effects;  ///< non-law effects other than extra_prony_term, in order added
  bool has(const std::string& e) const;
  /// e.g. "stvk+prony:2" or "yeoh+prony:2 + contact_offset + force_drift".
  std::string label() const;
};

/// The law and Prony terms of `s` as a fit::ModelSpec (one Ogden term), e.g. for the FE rig.
fit::ModelSpec model_spec(const Structure& s);

/// The effects that make `s` differ from `baseline`: its law's effect when the law differs,
/// extra_prony_term once per added term, then the other effects (a law swapped twice is one effect).
std::vector<std::string> effects_in(const Structure& s, const Structure& baseline);

/// `s` with `effect` added (a law effect replaces the law, extra_prony_term adds a term).
Structure with_effect(const Structure& s, const std::string& effect);

/// Empty when `effect` can be added to `s` for data `p`, else why not (one clause).
std::string not_applicable(const std::string& effect, const Structure& s, const Prepared& p);

/// True when `x` sits where `q`'s fit coordinate is flat, at one of its bounds: logit beyond +-12
/// (within 6e-6 of the range from a bound), or for a one-sided bound closer to it than 1e-9 of the
/// start range's reach (e.g. a Prony modulus at 0). A fit started there cannot move the parameter;
/// the term it belongs to has died (tau -> 0, e -> 0, or tau at the longest test).
bool pinned_at_bound(const fit::Parameter& q, double x);

/// The parameters of `s`, with starting values scaled by the data, poisson fixed at `poisson`
/// when `fix_poisson`. Values named as in `previous` (same name) are carried over from
/// `previous_values` unless pinned at a bound (pinned_at_bound: they start afresh); a new law starts
/// from the previous small-strain modulus. Relaxation times are bounded by the longest test.
std::vector<fit::Parameter> structure_parameters(const Structure& s, const Prepared& p, double poisson,
                                                 bool fix_poisson, const Structure* previous = nullptr,
                                                 const std::vector<double>* previous_values = nullptr);

/// The forward model of a structure on prepared data: forces at every sample whose mask entry is
/// nonzero (all samples when the mask is empty), tests in order.
class DiscoverModel final : public fit::ForwardModel {
 public:
  DiscoverModel(const Prepared& p, Structure s, std::vector<char> mask = {});
  std::string name() const override;
  std::string description() const override;
  std::vector<double> predict(const std::vector<double>& x) const override;
  /// Forces at every sample, per test.
  std::vector<std::vector<double>> predict_series(const std::vector<double>& x) const;

 private:
  const Prepared* p_;
  Structure s_;
  std::vector<char> mask_;
};

/// Where the forward model of `p` is exact, one sentence for the report.
std::string exactness(const Prepared& p);

/// The observations of `p` under `mask` (empty: all samples), for a fit::Problem.
fit::Observations observations(const Prepared& p, const std::vector<char>& mask = {});

/// Prony terms sorted by tau (exchangeable terms reported in one order).
std::vector<double> canonical(const Structure& s, const std::vector<fit::Parameter>& params,
                              std::vector<double> x);

}  // namespace tmlab::discover
