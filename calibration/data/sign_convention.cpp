#include "calibration/data/sign_convention.hpp"

#include "core/base/error.hpp"
#include "core/base/format.hpp"

#include <cstddef>

namespace tmlab::measured {

int force_sign(TestType t) { return t == TestType::uniaxial_tension ? -1 : 1; }

namespace {

/// "compression", "indentation" or "tension": the word the convention uses for a test kind.
std::string kind_word(TestType t) {
  if (is_compression(t)) return "compression";
  return t == TestType::indentation ? "indentation" : "tension";
}

/// The sum of `v` times `sign` is negative: the values lie mostly on the wrong side of zero.
bool wrong_side(const std::vector<double>& v, int sign) {
  double sum = 0.0;
  for (const double x : v) sum += x;
  return sign * sum < 0.0;
}

}  // namespace

void check_force_sign(const DataSet& data, const std::string& file) {
  const TestType kind = data.meta.test;
  const int sign = force_sign(kind);
  std::size_t bad_tests = 0, first = 0;
  for (std::size_t k = 0; k < data.tests.size(); ++k)
    if (wrong_side(data.tests[k].force_N, sign) && bad_tests++ == 0) first = k;
  if (bad_tests == 0) return;
  const Test& t = data.tests[first];
  std::size_t wrong = 0;
  for (const double f : t.force_N) wrong += sign * f < 0.0 ? 1 : 0;
  const std::string positive = sign > 0 ? "positive" : "negative",
                    negative = sign > 0 ? "negative" : "positive";
  // Both columns flipped (a tension recorded as a compression's mirror image) need both flipped back.
  // (Not for indentation, where an approach before contact may be long and at negative depth.)
  const bool displacement_too = kind != TestType::indentation && wrong_side(t.displacement_m, sign);
  std::string msg =
      printable(file.empty() ? data.meta.name : file, 200) + ": test " +
      (t.id.empty() ? std::to_string(first + 1) : "'" + printable(t.id, 60) + "'") + " (" + to_string(kind) +
      "): force must be " + positive + " in " + kind_word(kind) +
      " (the sign convention of tmlab-measured/1: force_N positive when the sample pushes back, negative "
      "when it pulls): " +
      std::to_string(wrong) + " of " + std::to_string(t.size()) + " samples are " + negative +
      "; flip the sign of force_N" +
      (displacement_too ? " (and of displacement_m, which is " + negative + " too: it must be " + positive +
                              " in " + kind_word(kind) + ")"
                        : std::string());
  if (bad_tests > 1)
    msg += " (" + std::to_string(bad_tests) + " of the " + std::to_string(data.tests.size()) +
           " tests have the wrong sign)";
  throw Error(msg);
}

}  // namespace tmlab::measured
