// libFuzzer target: the parameter files of `tmlab paper` (--params FILE): the Section IV-A
// identification settings (studies/paper/paper_fit_settings, with and without the "quick"
// merge patch) and the liver figures fig5, fig6 and fig7 (studies/paper/paper_experiments
// paper_figure: the document checked strictly, each figure's runs built as case documents). Any input
// must give settings or figures, or a tmlab::Error; settings read satisfy the documented ranges.
#include "core/base/error.hpp"
#include "core/config/config_reader.hpp"
#include "fuzz/fuzz_input.hpp"
#include "studies/paper/paper_experiments.hpp"
#include "studies/paper/paper_fit_settings.hpp"

#include <cmath>
#include <cstdlib>

namespace {

void check(const tmlab::tm::PaperFitSettings& s) {
  if (!(s.indenter_radius > 0.0) || s.depths.empty()) std::abort();
  for (const double d : s.depths)
    if (!(d > 0.0 && d < s.indenter_radius)) std::abort();
  if (!(s.young > 0.0) || !(s.poisson > -1.0 && s.poisson < 0.5)) std::abort();
  if (s.prony_moduli.size() != s.prony_taus.size()) std::abort();
  for (std::size_t k = 0; k < s.prony_moduli.size(); ++k)
    if (!(s.prony_moduli[k] > 0.0) || !std::isfinite(s.prony_moduli[k]) || !(s.prony_taus[k] > 0.0))
      std::abort();
  if (s.ramp_samples < 2 || s.hold_samples < 1 || s.starts < 1 || s.local_runs < 1 || s.threads < 1)
    std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  tmlab::fuzz::MemoryFile file(data, size);
  nlohmann::json doc;
  try {
    doc = tmlab::ConfigReader::parse_file(file.path());
  } catch (const tmlab::Error&) {
    return 0;
  }
  for (const bool quick : {false, true}) {
    try {
      check(tmlab::tm::paper_fit_settings(doc, file.path(), quick));
    } catch (const tmlab::Error&) {
    }
  }
  for (const char* fig : {"fig5", "fig6", "fig7"}) {
    try {
      (void)tmlab::tm::paper_figure(fig, doc, file.path());
    } catch (const tmlab::Error&) {
    }
  }
  return 0;
}
