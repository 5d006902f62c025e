// Silicone phantom CSV -> tmlab-measured/1 (phantom_converter.hpp).
#include "calibration/data/phantom_converter.hpp"

#include "core/base/error.hpp"
#include "core/base/format.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <string_view>
#include <vector>

namespace tmlab::measured {

namespace fs = std::filesystem;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr std::string_view kTableStart = "Time (s),Compression (mm),Load (N)";

Error located(const std::string& file, long line, long column, const std::string& reason) {
  return Error(file + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " + reason);
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

/// The lines of `text` (without '\n' or a trailing '\r').
std::vector<std::string_view> lines_of(const std::string& text) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string_view l(text.data() + start, end - start);
    if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
    out.push_back(l);
    start = end + 1;
  }
  return out;
}

/// Fields of a comma-separated line with their 1-based columns.
std::vector<std::pair<std::string_view, long>> fields_of(std::string_view line) {
  std::vector<std::pair<std::string_view, long>> out;
  std::size_t start = 0;
  for (;;) {
    std::size_t end = line.find(',', start);
    if (end == std::string_view::npos) end = line.size();
    out.emplace_back(trim(line.substr(start, end - start)), long(start) + 1);
    if (end == line.size()) break;
    start = end + 1;
  }
  return out;
}

/// "Cylinder Diameter: 50mm;" -> 50 (mm); false when the line is not "<key>: <number>mm;".
bool millimetres(std::string_view line, std::string_view key, double& mm) {
  line = trim(line);
  if (line.substr(0, key.size()) != key) return false;
  std::string_view v = trim(line.substr(key.size()));
  if (!v.empty() && v.back() == ';') v.remove_suffix(1);
  v = trim(v);
  if (v.size() < 3 || v.substr(v.size() - 2) != "mm") return false;
  std::string why;
  return parse_decimal(trim(v.substr(0, v.size() - 2)), mm, why) && mm > 0.0;
}

std::string header_value(std::string_view line, std::string_view key) {
  line = trim(line);
  if (line.substr(0, key.size()) != key) return "";
  std::string_view v = trim(line.substr(key.size()));
  if (!v.empty() && v.back() == ';') v.remove_suffix(1);
  return std::string(trim(v));
}

/// `mm` (read from `text`) in metres, rounded once: the decimal text with its exponent lowered by 3
/// reads as the double nearest the exact value in metres ("0.02778" mm -> 2.778e-05 m), where
/// mm * 1e-3 would round twice (2.7779999999999998e-05).
double metres_from_millimetres(std::string_view text, double mm) {
  const std::size_t e = text.find_first_of("eE");
  long exponent = 0;
  if (e != std::string_view::npos) {
    const char* first = text.data() + e + 1 + (text[e + 1] == '+' ? 1 : 0);
    const auto r = std::from_chars(first, text.data() + text.size(), exponent);
    if (r.ec != std::errc() || std::labs(exponent) > 100000) return mm * 1e-3;
  }
  const std::string shifted = std::string(text.substr(0, e)) + "e" + std::to_string(exponent - 3);
  double m = 0.0;
  std::string why;
  return parse_decimal(shifted, m, why) ? m : mm * 1e-3;
}

/// Text from the file for the metadata: printable ASCII only (the JSON must be valid UTF-8).
std::string ascii_text(std::string_view s) {
  std::string out;
  for (char c : s.substr(0, 200)) out += (c >= 0x20 && c < 0x7F) ? c : '?';
  return out;
}

std::string safe_name(const std::string& stem) {
  std::string n;
  for (char c : stem)
    n += ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '.')
             ? c
             : '_';
  if (n.empty() || n[0] == '.' || n[0] == '-') n = "phantom" + n;
  return n.substr(0, 200);
}

/// The lines before the column line: the sample's label, the cylinder and the machine.
struct Header {
  std::string label, machine, load_cell, speed;
  double diameter_mm = 0.0, height_mm = 0.0;
  long height_line = 0;  ///< where the height was read (for messages)
};

Header read_header(const std::vector<std::string_view>& lines, std::size_t table, const std::string& file) {
  Header h;
  bool compression = false;
  for (std::size_t i = 0; i < table; ++i) {
    const std::string_view l = trim(lines[i]);
    if (i == 0) h.label = ascii_text(l.substr(0, 120));
    if (l == "Compression test;" || l == "Compression test") compression = true;
    if (l.substr(0, 18) == "Cylinder Diameter:" && !millimetres(l, "Cylinder Diameter:", h.diameter_mm))
      throw located(file, long(i) + 1, 1, "cannot read the diameter (expected 'Cylinder Diameter: 50mm;')");
    if (l.substr(0, 16) == "Cylinder Height:" && !millimetres(l, "Cylinder Height:", h.height_mm))
      throw located(file, long(i) + 1, 1, "cannot read the height (expected 'Cylinder Height: 30mm;')");
    if (l.substr(0, 16) == "Cylinder Height:") h.height_line = long(i) + 1;
    if (h.machine.empty()) h.machine = ascii_text(header_value(l, "Machine:"));
    if (h.load_cell.empty()) h.load_cell = ascii_text(header_value(l, "Load cell:"));
    if (h.speed.empty()) h.speed = ascii_text(header_value(l, "Speed (mm/min):"));
  }
  if (!compression) throw located(file, 1, 1, "the header does not say 'Compression test;'");
  if (h.diameter_mm <= 0.0)
    throw located(file, long(table) + 1, 1, "the header has no 'Cylinder Diameter: ...mm;' line");
  if (h.height_mm <= 0.0)
    throw located(file, long(table) + 1, 1, "the header has no 'Cylinder Height: ...mm;' line");
  return h;
}

}  // namespace

bool is_phantom_csv(const std::string& text) {
  const std::vector<std::string_view> lines = lines_of(text.substr(0, 8192));
  for (std::size_t i = 0; i < lines.size() && i < 30; ++i)
    if (trim(lines[i]).substr(0, kTableStart.size()) == kTableStart) return true;
  return false;
}

DataSet convert_phantom(const fs::path& file, const PhantomOptions& options) {
  return convert_phantom_text(read_input_file(file), file.string(), options);
}

DataSet convert_phantom_text(const std::string& text, const std::string& file,
                             const PhantomOptions& options) {
  const std::vector<std::string_view> lines = lines_of(text);
  // The header: everything before the table's column line.
  std::size_t table = lines.size();
  for (std::size_t i = 0; i < lines.size() && i < 30; ++i)
    if (trim(lines[i]).substr(0, kTableStart.size()) == kTableStart) {
      table = i;
      break;
    }
  if (table == lines.size())
    throw located(file, 1, 1,
                  "not a silicone phantom CSV: no column line starting '" + std::string(kTableStart) +
                      "' in the first 30 lines");
  const Header h = read_header(lines, table, file);

  // The table: Time, Compression, Load by name; the engineering stress for the geometry check.
  const auto header = fields_of(lines[table]);
  long c_time = -1, c_comp = -1, c_load = -1, c_stress = -1;
  for (std::size_t c = 0; c < header.size(); ++c) {
    if (header[c].first == "Time (s)") c_time = long(c);
    if (header[c].first == "Compression (mm)") c_comp = long(c);
    if (header[c].first == "Load (N)") c_load = long(c);
    if (header[c].first == "Engineering Stress (kPa)") c_stress = long(c);
  }
  Test t;
  t.first_line = long(table) + 2;
  std::vector<double> stress_kPa;
  std::vector<long> line_of;
  for (std::size_t i = table + 1; i < lines.size(); ++i) {
    if (trim(lines[i]).empty()) continue;
    const auto f = fields_of(lines[i]);
    const long line = long(i) + 1;
    if (f.size() != header.size())
      throw located(file, line, f.back().second,
                    std::to_string(f.size()) + " fields, but the column line (line " +
                        std::to_string(table + 1) + ") has " + std::to_string(header.size()));
    double v[4] = {0, 0, 0, 0};
    const long cols[4] = {c_time, c_comp, c_load, c_stress};
    for (int k = 0; k < 4; ++k) {
      if (cols[k] < 0) continue;
      std::string why;
      if (!parse_decimal(f[cols[k]].first, v[k], why))
        throw located(file, line, f[cols[k]].second,
                      "column '" + std::string(header[cols[k]].first) + "': " + why);
    }
    if (!t.time_s.empty() && !(v[0] > t.time_s.back()))
      throw located(file, line, f[c_time].second, "column 'Time (s)': time does not increase");
    t.time_s.push_back(v[0]);
    t.displacement_m.push_back(metres_from_millimetres(f[c_comp].first, v[1]));
    t.force_N.push_back(v[2]);
    if (c_stress >= 0) stress_kPa.push_back(v[3]);
    line_of.push_back(line);
  }
  if (t.time_s.empty())
    throw located(file, long(table) + 2, 1, "no samples after the column line (an empty test)");
  if (t.size() == 1)
    throw located(file, line_of[0], 1,
                  "one sample only (line " + std::to_string(line_of[0]) +
                      "): a force-displacement curve needs at least two");

  std::string conversion =
      "Converted by 'tmlab data convert' from " + ascii_text(fs::path(file).filename().string()) +
      ": Time (s) -> time_s; Compression (mm) / 1000 -> displacement_m; Load (N) -> force_N. The derived "
      "strain and stress columns are not copied (their stress unit is kPa, although the upstream README "
      "says N/mm^2).";
  // Sign: the format wants the force positive when the sample pushes back.
  const std::size_t deepest = std::size_t(std::max_element(t.displacement_m.begin(), t.displacement_m.end()) -
                                          t.displacement_m.begin());
  if (t.force_N[deepest] < 0.0) {
    for (double& F : t.force_N) F = -F;
    conversion += " The load was negative at the deepest compression and was negated.";
  }
  // A sample cannot shorten by its whole height: the header's height or the column is wrong.
  if (t.displacement_m[deepest] >= h.height_mm * 1e-3) {
    const long line = line_of[deepest];
    throw located(file, line, fields_of(lines[std::size_t(line) - 1])[std::size_t(c_comp)].second,
                  "column 'Compression (mm)': the compression reaches " +
                      significant(t.displacement_m[deepest] * 1e3, 6) + " mm, not less than the height " +
                      significant(h.height_mm, 6) + " mm of 'Cylinder Height' (line " +
                      std::to_string(h.height_line) + "): a sample cannot be compressed by its whole height");
  }
  // Geometry check: engineering stress (kPa) = load / initial area, at the peak load.
  if (c_stress >= 0) {
    const std::size_t peak =
        std::size_t(std::max_element(t.force_N.begin(), t.force_N.end(),
                                     [](double a, double b) { return std::fabs(a) < std::fabs(b); }) -
                    t.force_N.begin());
    const double area_m2 = kPi * 0.25 * h.diameter_mm * h.diameter_mm * 1e-6;
    const double expected_kPa = std::fabs(t.force_N[peak]) / area_m2 * 1e-3;
    if (std::fabs(t.force_N[peak]) > 0.0 &&
        std::fabs(std::fabs(stress_kPa[peak]) - expected_kPa) > 0.01 * expected_kPa)
      throw located(file, line_of[peak], 1,
                    "'Engineering Stress (kPa)' is " + significant(stress_kPa[peak], 6) +
                        " but Load / (pi (D/2)^2) is " + significant(expected_kPa, 6) +
                        " kPa with D = " + significant(h.diameter_mm, 6) +
                        " mm from the header: the geometry or the stress unit is not what the header says");
  }

  DataSet d;
  d.meta.name = safe_name(fs::path(file).stem().string());
  d.meta.test = TestType::unconfined_compression;
  d.meta.sample.shape = SampleShape::cylinder;
  d.meta.sample.radius_m = 0.5 * h.diameter_mm * 1e-3;
  d.meta.sample.height_m = h.height_mm * 1e-3;
  d.meta.sample.bottom = options.platens;
  d.meta.sample.platens = options.platens;
  d.meta.source =
      "Dawood A.B., Zhang Z., Osman D., Suulker C., Abdulali A., Angelmahr M., Althoefer K. (2026), "
      "Hyperelastic Characterisation of Silicone Tissue Phantoms: A Parametric Database with Model Selection "
      "and Inverse Design Framework; data: "
      "https://github.com/abubakardawood/tissue-phantom-material-database "
      "(sample " +
      h.label + ")";
  d.meta.license = "CC-BY-4.0";
  d.meta.notes = "Silicone (Ecoflex) phantom, unconfined uniaxial compression on " +
                 (h.machine.empty() ? std::string("an Instron") : h.machine) +
                 (h.load_cell.empty() ? "" : " (load cell " + h.load_cell + ")") +
                 (h.speed.empty() ? "" : ", crosshead " + h.speed + " mm/min") +
                 ", a monotonic ramp (no hold, no unloading). " + conversion +
                 " Platen friction is not documented upstream: " + to_string(options.platens) +
                 " assumed for both platens. Attribution (CC BY 4.0): cite the article in 'source'; changes: "
                 "units converted to SI, derived columns dropped.";
  d.tests.push_back(std::move(t));
  validate(d);
  return d;
}

}  // namespace tmlab::measured
