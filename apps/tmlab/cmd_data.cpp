// tmlab data convert|show: measured data sets (docs/measured-data.md). Thin: the reader, the
// converters and the plot script do the work (calibration/data/).
#include "commands.hpp"

#include "cli_args.hpp"
#include "command_specs.hpp"

#include "calibration/data/measured_data.hpp"
#include "calibration/data/phantom_converter.hpp"
#include "core/base/error.hpp"
#include "core/base/format.hpp"
#include "core/base/process.hpp"
#include "core/io/atomic_file.hpp"
#include "core/io/output_file.hpp"

#include <nlohmann/json.hpp>

#include <stdlib.h>  // mkdtemp

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>

namespace tmlab::cli {

namespace fs = std::filesystem;
using namespace tmlab::measured;

namespace {

std::string describe(const Metadata& m) {
  std::string s = to_string(m.test);
  if (m.indenter)
    s += ", " + to_string(m.indenter->shape) + " indenter r " + significant(m.indenter->radius_m * 1e3, 4) +
         " mm";
  const Sample& p = m.sample;
  if (p.shape == SampleShape::block)
    s += ", block " + significant(p.size_m[0] * 1e3, 4) + " x " + significant(p.size_m[1] * 1e3, 4) + " x " +
         significant(p.size_m[2] * 1e3, 4) + " mm";
  if (p.shape == SampleShape::cylinder)
    s += ", cylinder " + significant(2e3 * p.radius_m, 4) + " mm diameter x " +
         significant(p.height_m * 1e3, 4) + " mm high";
  if (p.shape == SampleShape::half_space) s += ", half-space";
  if (p.bottom) s += ", bottom " + to_string(*p.bottom);
  if (p.platens) s += ", platens " + to_string(*p.platens);
  return s;
}

/// A fresh private directory under the system's temporary directory, removed with its contents
/// when it goes out of scope: where `data show` writes the plot's input, never the user's folder.
class TempDir {
 public:
  TempDir() {
    std::string t = (fs::temp_directory_path() / "tmlab-data-show-XXXXXX").string();
    if (::mkdtemp(t.data()) == nullptr) throw Error(t + ": cannot create a temporary directory");
    path_ = t;
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

int convert(const ParsedOptions& p) {
  if (p.positional.size() != 1) throw UsageError("data convert needs exactly one input file");
  if (!p.given("--out")) throw UsageError("data convert needs --out DIR");
  PhantomOptions opt;
  if (p.text("--platens") == "bonded") opt.platens = Interface::bonded;
  const fs::path in = p.positional[0];
  const std::string text = read_input_file(in);  // a directory or a FIFO is named, never read
  if (!is_phantom_csv(text))
    throw Error(
        in.string() +
        ": not a layout 'tmlab data convert' knows (known: the silicone phantom compression CSVs of "
        "Dawood et al. 2026, a header then 'Time (s),Compression (mm),Load (N),...'); a tmlab-measured/1 "
        "data set needs no conversion (docs/measured-data.md)");
  const DataSet d = convert_phantom_text(text, in.string(), opt);
  // Into a user's folder: never over the input, nothing already there without --overwrite.
  const fs::path csv = write_data_set(d, p.text("--out"), {in}, p.flag("--overwrite"));
  std::cout << "converted " << in.string() << " (silicone phantom CSV, Dawood et al. 2026, CC BY 4.0)\n"
            << "  " << d.meta.name << ": " << describe(d.meta) << ", " << d.tests.front().size()
            << " samples\n"
            << "wrote " << csv.string() << " and " << metadata_path(csv).string() << "\n";
  return 0;
}

int show(const ParsedOptions& p) {
  if (p.positional.size() != 1) throw UsageError("data show needs exactly one NAME.csv");
  const fs::path csv = p.positional[0];
  const DataSet d = read_data_set(csv);
  // The plot's target is checked before anything is shown or written: in a folder given with --out
  // a NAME.png already there is the user's (replaced only with --overwrite); in the default
  // results/data/NAME/ it is the previous plot. Never an input, in either.
  const bool plot = !p.flag("--no-plots");
  const fs::path out = p.given("--out") ? fs::path(p.text("--out"))
                                        : fs::path(tmlab_root()) / "results" / "data" / d.meta.name;
  const fs::path png = out / (d.meta.name + ".png");
  const std::vector<fs::path> inputs = {csv, metadata_path(csv)};
  const bool overwrite = !p.given("--out") || p.flag("--overwrite");
  if (plot) check_output_files({png}, inputs, overwrite);
  std::cout << d.meta.name << ": " << describe(d.meta) << "\n";
  if (d.meta.temperature_C) std::cout << "temperature: " << significant(*d.meta.temperature_C, 4) << " C\n";
  // Free text from the user's file: control characters (an ESC sequence) are shown escaped.
  if (!d.meta.source.empty()) std::cout << "source: " << printable(d.meta.source, 4000) << "\n";
  if (!d.meta.license.empty()) std::cout << "licence: " << printable(d.meta.license, 4000) << "\n";
  std::cout << std::left << std::setw(12) << "test" << std::right << std::setw(8) << "samples"
            << std::setw(13) << "duration_s" << std::setw(26) << "displacement_mm" << std::setw(26)
            << "force_N" << std::setw(14) << "peak_force_N" << std::setw(12) << "at_mm"
            << "\n";
  for (const Test& t : d.tests) {
    const auto [dmin, dmax] = std::minmax_element(t.displacement_m.begin(), t.displacement_m.end());
    const auto [fmin, fmax] = std::minmax_element(t.force_N.begin(), t.force_N.end());
    // The peak is the force of largest magnitude (negative in tension), with where it was reached.
    const std::size_t peak =
        std::size_t(std::max_element(t.force_N.begin(), t.force_N.end(),
                                     [](double a, double b) { return std::fabs(a) < std::fabs(b); }) -
                    t.force_N.begin());
    std::cout << std::left << std::setw(12) << (t.id.empty() ? "(all)" : t.id) << std::right << std::setw(8)
              << t.size() << std::setw(13) << significant(t.time_s.back() - t.time_s.front(), 6)
              << std::setw(26) << (significant(*dmin * 1e3, 5) + " .. " + significant(*dmax * 1e3, 5))
              << std::setw(26) << (significant(*fmin, 5) + " .. " + significant(*fmax, 5)) << std::setw(14)
              << significant(t.force_N[peak], 6) << std::setw(12)
              << significant(t.displacement_m[peak] * 1e3, 5) << "\n";
  }
  if (!d.notes.empty()) {
    std::cout << "kept, not used:\n";
    for (const Note& n : d.notes) std::cout << "  " << n.where << ": " << n.text << "\n";
  }
  if (!plot) return 0;

  // The plot's input and the script's PNG go to a private temporary directory; only the finished
  // PNG is placed in `out` (write_file_atomically: a fresh temporary name beside it, then a rename).
  const TempDir work;
  nlohmann::json spec_json = {{"name", d.meta.name},
                              {"title", d.meta.name + ": " + describe(d.meta)},
                              {"tests", nlohmann::json::array()}};
  for (const Test& t : d.tests)
    spec_json["tests"].push_back(
        {{"id", t.id}, {"time_s", t.time_s}, {"displacement_m", t.displacement_m}, {"force_N", t.force_N}});
  const fs::path spec = work.path() / (d.meta.name + "_plot.json");
  const fs::path drawn = work.path() / (d.meta.name + ".png");
  write_file_atomically(spec, spec_json.dump() + "\n");
  const ProcessStatus ps =
      run_python(fs::path(tmlab_root()) / "calibration" / "data" / "python" / "tmlab_data_plot.py",
                 {spec.string(), drawn.string()});
  if (!ps.ok()) throw Error(png.string() + ": the plot failed (" + ps.describe() + "); --no-plots skips it");
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec) throw Error(out.string() + ": cannot create directory (" + ec.message() + ")");
  check_output_files({png}, inputs, overwrite);  // again: a file made there meanwhile is kept
  write_file_atomically(png, read_input_file(drawn));
  std::cout << "plot: " << png.string() << "\n";
  return 0;
}

}  // namespace

int cmd_data(const std::vector<std::string>& args) {
  if (args.empty()) throw UsageError("data needs a sub-command: convert FILE --out DIR | show NAME.csv");
  const std::string sub = args[0];
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  if (sub == "convert") return convert(parse(data_convert_spec(), rest));
  if (sub == "show") return show(parse(data_show_spec(), rest));
  throw UsageError("unknown data sub-command '" + sub + "' (convert or show)");
}

}  // namespace tmlab::cli
