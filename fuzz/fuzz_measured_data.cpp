// libFuzzer target: the measured-data reader (tmlab-measured/1: NAME.json + NAME.csv) and the
// silicone phantom converter. The input is the JSON, a form feed (\f), then the CSV; without a form
// feed the whole input is the CSV and a fixed valid JSON goes with it. Any input must give a data
// set or a tmlab::Error, and what the writer makes of a data set must read back to the same text
// (the round trip); the phantom converter's output must read back likewise.
#include "calibration/data/measured_data.hpp"
#include "calibration/data/phantom_converter.hpp"
#include "core/base/error.hpp"
#include "fuzz/fuzz_input.hpp"

#include <cstdlib>
#include <string>

namespace {

const char* kMetadata = R"({"format": "tmlab-measured/1", "name": "fuzz", "test": "indentation",
  "indenter": {"shape": "sphere", "radius_m": 0.005},
  "sample": {"shape": "block", "size_m": [0.04, 0.04, 0.02], "bottom": "bonded"}})";

using tmlab::measured::DataSet;

DataSet read_texts(const std::string& json, const std::string& csv) {
  tmlab::fuzz::MemoryFile j(reinterpret_cast<const std::uint8_t*>(json.data()), json.size());
  tmlab::fuzz::MemoryFile c(reinterpret_cast<const std::uint8_t*>(csv.data()), csv.size());
  return tmlab::measured::read_data_set(c.path(), j.path());
}

/// The writer's text must read back to itself.
void check_round_trip(const DataSet& d) {
  const std::string json = tmlab::measured::format_metadata(d.meta);
  const std::string csv = tmlab::measured::format_samples(d);
  DataSet back;
  try {
    back = read_texts(json, csv);
  } catch (const tmlab::Error&) {
    std::abort();  // the writer wrote something the reader refuses
  }
  if (tmlab::measured::format_metadata(back.meta) != json || tmlab::measured::format_samples(back) != csv)
    std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  const std::size_t split = input.find('\f');
  const std::string json = split == std::string::npos ? kMetadata : input.substr(0, split);
  const std::string csv = split == std::string::npos ? input : input.substr(split + 1);
  try {
    check_round_trip(read_texts(json, csv));
  } catch (const tmlab::Error&) {
  }
  try {
    check_round_trip(tmlab::measured::convert_phantom_text(csv, "fuzz.csv"));
  } catch (const tmlab::Error&) {
  }
  return 0;
}
