// Measured force-displacement data in the tmlab-measured/1 interchange format (docs/measured-data.md):
// NAME.csv (the samples: time_s, displacement_m, force_N, optional test_id, other columns kept) and
// NAME.json (what the test was: test type, indenter, sample, boundary conditions, source, licence).
//
// The reader is strict because a fit silently run on a misread curve is worse than no fit: a missing
// column or key, a number whose name carries no unit, a time that does not increase within a test,
// NaN or infinity, and an empty test are tmlab::Error naming the file, line and column
// ("a.csv:12:17: column 'force_N': ..."). Columns and keys the format does not know are kept in the
// data set and reported as notes, so nothing the experimenter wrote is lost.
#pragma once

#include <nlohmann/json.hpp>

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace tmlab::measured {

/// The format identifier every NAME.json carries in "format".
inline constexpr const char* kFormat = "tmlab-measured/1";

enum class TestType { indentation, unconfined_compression, confined_compression, uniaxial_tension };
enum class IndenterShape { sphere, flat_punch, cylinder };
enum class SampleShape { block, cylinder, half_space };
/// A contact between the sample and a rigid surface (the support under it, the compression platens).
enum class Interface { bonded, frictionless };

std::string to_string(TestType t);
std::string to_string(IndenterShape s);
std::string to_string(SampleShape s);
std::string to_string(Interface i);
bool is_compression(TestType t);

struct Indenter {
  IndenterShape shape = IndenterShape::sphere;
  double radius_m = 0.0;           ///< sphere, flat punch and cylinder radius
  std::optional<double> length_m;  ///< cylinder (lying on its side) only, optional
};

struct Sample {
  SampleShape shape = SampleShape::block;
  std::array<double, 3> size_m{};  ///< block: x, y, z with z the loaded direction
  double radius_m = 0.0;           ///< cylinder
  double height_m = 0.0;           ///< cylinder (along the load)
  /// Required unless the sample is a half-space; in a compression test the bottom platen, so
  /// optional there (read as `platens` when absent; a note when it differs from `platens`).
  std::optional<Interface> bottom;
  std::optional<Interface> platens;  ///< compression tests only, required there
};

/// A key the format does not know, kept with its value.
struct ExtraKey {
  std::string object;  ///< "" (top level), "indenter" or "sample": where it was
  std::string key;
  nlohmann::json value;
  std::string path() const { return object.empty() ? key : object + "." + key; }
};

/// NAME.json, parsed. Unknown keys are kept in `extra` (in the order of the keys of each object).
struct Metadata {
  std::string name;  ///< the data set's name: name_problem() is ""
  TestType test = TestType::indentation;
  std::optional<Indenter> indenter;  ///< indentation tests only, required there
  Sample sample;
  std::optional<double> temperature_C;
  std::string source;
  std::string license;
  std::string notes;
  std::vector<ExtraKey> extra;
};

/// A column the format does not know (its name carries a unit), kept with its values.
struct Column {
  std::string name;
  std::vector<double> values;
};

/// One test: a contiguous run of samples with one test_id (the whole file without a test_id column).
struct Test {
  std::string id;       ///< the test_id value; "" when the file has no test_id column
  long first_line = 0;  ///< line of its first sample in NAME.csv (0 for data made in memory)
  std::vector<double> time_s;
  std::vector<double> displacement_m;  ///< positive into the sample (the driving history)
  std::vector<double> force_N;         ///< positive when the sample pushes back
  std::vector<Column> extra;           ///< unknown columns, in file order
  std::size_t size() const { return time_s.size(); }
};

/// Something the reader kept but did not use (an unknown key or column), with where it is.
struct Note {
  std::string where;  ///< "file:line:column"
  std::string text;
};

struct DataSet {
  Metadata meta;
  std::vector<Test> tests;
  std::vector<Note> notes;
};

/// True when `name` ends in a unit after a non-empty quantity: quantity_unit with unit an atom
/// (s, m, mm, N, kN, Pa, kPa, C, K, Hz, ..., 1 for dimensionless) or atom_per_atom ("speed_m_per_s").
bool has_unit_suffix(const std::string& name);

/// Reads a decimal number as the CSV reader does ([+-]digits[.digits][e[+-]digits]); false with the
/// reason in `why` for an empty field, text, NaN, infinity or a value out of the range of a double.
bool parse_decimal(std::string_view s, double& out, std::string& why);

/// The metadata file that goes with `csv`: the same path with the extension .json.
std::filesystem::path metadata_path(const std::filesystem::path& csv);

/// The longest data-set name or test_id (a name becomes a file name).
inline constexpr std::size_t kMaxNameLength = 200;
/// Why `s` is not a plain data-set name or test_id ("" when it is one): the length rule first
/// (at most kMaxNameLength characters), then letters, digits, '_', '-', '.', not starting with '.'
/// or '-'. User text in the reason is shown through tmlab::printable().
std::string name_problem(const std::string& s);

/// The whole content of a user's input file. tmlab::Error naming the path when it does not exist,
/// is a directory, or is not a regular file (a FIFO, socket or device: refused without reading, and
/// opened non-blocking, so a FIFO never blocks the command).
std::string read_input_file(const std::filesystem::path& path);

/// The deepest nesting of arrays and objects a NAME.json may have.
inline constexpr int kMaxJsonDepth = 64;
/// Refuses JSON text nested deeper than kMaxJsonDepth levels, naming file:line:column of the bracket
/// that opens the first level too many. One linear pass over the text (strings and comments
/// skipped), run before the JSON parser so that a hostile 100k-deep file fails at once.
void check_json_depth(const std::string& text, const std::string& file);

/// Reads `csv` and its metadata (metadata_path(csv) unless given). tmlab::Error naming the file,
/// line and column for every violation of the format; notes for what was kept but not used.
DataSet read_data_set(const std::filesystem::path& csv);
DataSet read_data_set(const std::filesystem::path& csv, const std::filesystem::path& json);

/// NAME.json text; unknown keys go back where they were read.
std::string format_metadata(const Metadata& meta);
/// NAME.csv text (test_id column when there is more than one test or a test has an id); numbers in
/// the shortest form that reads back to the same double.
std::string format_samples(const DataSet& data);
/// Checks what the reader checks (every test non-empty, strictly increasing finite time, finite
/// numbers, all extra columns the same in every test) on data made in memory; tmlab::Error otherwise.
void validate(const DataSet& data);
/// Writes dir/NAME.csv and dir/NAME.json (NAME = meta.name), each atomically, after validate();
/// creates `dir`. Returns the CSV path. For a directory tmlab owns (a result's staging directory):
/// files already there are replaced.
std::filesystem::path write_data_set(const DataSet& data, const std::filesystem::path& dir);
/// The same into a user's folder (`tmlab data convert --out`): tmlab::check_output_files()
/// (core/io/output_file.hpp) on both NAME.csv and NAME.json before either is written, so a refusal
/// leaves the folder as it was: never over one of `inputs` (also through links), and over an
/// existing file only when `overwrite`.
std::filesystem::path write_data_set(const DataSet& data, const std::filesystem::path& dir,
                                     const std::vector<std::filesystem::path>& inputs, bool overwrite);

}  // namespace tmlab::measured
