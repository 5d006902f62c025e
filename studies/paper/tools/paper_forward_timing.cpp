// paper_forward_timing: the cost of one forward FE solve of the Section IV-A rig (`tmlab paper
// fig2|fig3|table1|table2`, studies/paper/paper_fit.cpp) at the generating parameters, for
// measuring where a fit's time goes (docs/paper-experiments.md, "Cost"). Not a `tmlab` command: a
// developer tool.
//
//   paper_forward_timing PARAMS.json quick|default elastic|relaxation LAW DEPTH_INDEX [FACTOR [NEWTON]]
//     FACTOR   the contact stiffness factor (0: the contact solver's default eps; absent: the file's)
//     NEWTON   Newton iterations before a load step is cut back (absent: the rig's default)
//
// Prints the rig's size, then for a cold solve at the truth and a warm solve at parameters 1e-6
// away (started from the cold one, as the fit's Jacobian columns are): wall and CPU seconds, Newton
// and contact iterations, cut-backs, and the forces.
#include "calibration/fit/model_spec.hpp"
#include "calibration/fit/rig_forward_model.hpp"
#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/config/config_reader.hpp"
#include "studies/paper/paper_fit.hpp"

#include <chrono>
#include <ctime>
#include <iostream>
#include <string>

namespace {

using namespace tmlab;

struct Clock {
  std::chrono::steady_clock::time_point wall = std::chrono::steady_clock::now();
  std::clock_t cpu = std::clock();
  std::string since() const {
    const double w = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall).count();
    const double c = double(std::clock() - cpu) / CLOCKS_PER_SEC;
    return "wall " + significant(w, 3) + " s, CPU " + significant(c, 3) + " s";
  }
};

void report(const std::string& what, const Clock& c, const fit::RigForwardModelEffort& before,
            const fit::RigForwardModelEffort& after, const std::vector<double>& f) {
  std::cout << what << ": " << c.since() << ", " << after.steps - before.steps << " load steps, "
            << after.newton - before.newton << " Newton iterations, " << after.outer - before.outer
            << " contact outer iterations, " << after.cutbacks - before.cutbacks
            << " cut-backs\n  force [N]:";
  for (const double v : f) std::cout << " " << significant(v, 8);
  std::cout << "\n";
}

int run(int argc, char** argv) {
  if (argc < 6 || argc > 8) {
    std::cerr << "usage: paper_forward_timing PARAMS.json quick|default elastic|relaxation LAW DEPTH_INDEX "
                 "[CONTACT_STIFFNESS_FACTOR [NEWTON_MAX_ITERATIONS]]\n";
    return 2;
  }
  const std::string params = argv[1], mode = argv[2], kind = argv[3], law = argv[4];
  if ((mode != "quick" && mode != "default") || (kind != "elastic" && kind != "relaxation"))
    throw Error("paper_forward_timing: mode must be quick|default and kind elastic|relaxation");
  tm::PaperFitSettings s = tm::paper_fit_settings(ConfigReader::parse_file(params), params, mode == "quick");
  if (argc >= 7) s.contact_stiffness_factor = std::stod(argv[6]);
  const std::size_t k = std::stoul(argv[5]);
  if (k >= s.depths.size()) throw Error("paper_forward_timing: DEPTH_INDEX beyond the file's depths");
  const bool visco = kind == "relaxation";
  const measured::DataSet d = tm::paper_reference_data(s, visco, k);
  const fit::ModelSpec spec =
      fit::parse_model_spec(law + (visco ? "+prony:" + std::to_string(s.prony_moduli.size()) : "") +
                            ",poisson=" + significant(s.poisson, 6));
  std::vector<double> x = {s.young, s.poisson};
  if (visco) {
    x.insert(x.end(), s.prony_moduli.begin(), s.prony_moduli.end());
    x.insert(x.end(), s.prony_taus.begin(), s.prony_taus.end());
  }
  fit::RigForwardModelOptions fe = tm::paper_fe_rig_options(s);
  if (argc == 8) fe.newton_max_iterations = std::stoi(argv[7]);
  const auto model = fit::make_rig_forward_model(d, spec, fe);
  std::cout << model->description() << "\ndepth " << significant(s.depths[k] * 1e3, 4) << " mm, "
            << d.tests[0].size() << " samples, contact stiffness factor "
            << significant(s.contact_stiffness_factor, 3) << " (0: solver default)\n";
  fit::RigForwardModelEffort e0 = fit::rig_forward_model_effort(*model);
  Clock c;
  std::shared_ptr<const fit::WarmStart> state;
  const std::vector<double> f = model->predict_warm(x, nullptr, &state);
  fit::RigForwardModelEffort e1 = fit::rig_forward_model_effort(*model);
  report("cold solve at the truth", c, e0, e1, f);
  std::vector<double> xp = x;
  for (std::size_t i = 0; i < xp.size(); ++i)
    if (i != 1) xp[i] *= 1.0 + 1e-6;  // every parameter but poisson (fixed in the study)
  Clock cw;
  const std::vector<double> fw = model->predict_warm(xp, state.get(), nullptr);
  report("warm solve at 1e-6 away", cw, e1, fit::rig_forward_model_effort(*model), fw);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "paper_forward_timing: " << e.what() << "\n";
    return 1;
  }
}
