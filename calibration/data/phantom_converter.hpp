// The silicone tissue-phantom compression CSVs of Dawood et al. (2026) -> tmlab-measured/1.
//
// Layout (calibration/data/phantom/README.md): a header of "Key: value;" lines giving the sample,
// the test and the cylinder geometry in mm, then the table
//   Time (s),Compression (mm),Load (N),Engineering Strain [-],Engineering Stress (kPa),True Strain [-],True
//   Stress (kPa)
// Compression is positive into the sample and Load positive when the sample pushes back (both as
// tmlab-measured/1 wants them; a file whose load is negative at the deepest compression is flipped,
// with a note). The derived strain and stress columns are not copied: they follow from force,
// displacement and geometry. The engineering stress is used once, to check the geometry: it must
// equal Load / (pi (D/2)^2) in kPa at the peak load, within 1 %.
#pragma once

#include "calibration/data/measured_data.hpp"

#include <filesystem>
#include <string>

namespace tmlab::measured {

struct PhantomOptions {
  /// The upstream data do not say whether the platens were lubricated. Frictionless is the
  /// idealisation behind the authors' engineering stress (load over the initial area: a homogeneous
  /// compression); bonded is the other bound (barrelling). Used for both the support (bottom) and
  /// the platens.
  Interface platens = Interface::frictionless;
};

/// True when `text` looks like a phantom CSV (its table header within the first 30 lines).
bool is_phantom_csv(const std::string& text);

/// Converts one phantom CSV; the data set is named after the file's stem. tmlab::Error naming the
/// file, line and column for a malformed file, a compression that reaches the header's height, or a
/// single sample; naming the path for a directory, FIFO or other file that is not a regular file.
DataSet convert_phantom(const std::filesystem::path& file, const PhantomOptions& options = {});
/// The same from text (`file` names it in messages and gives the data set's name).
DataSet convert_phantom_text(const std::string& text, const std::string& file,
                             const PhantomOptions& options = {});

}  // namespace tmlab::measured
