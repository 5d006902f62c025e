// Names of the values of a closed choice (an enum class with values 0 .. N-1 in declaration order),
// kept in one table per choice and read both ways: value -> name for output, name -> value for
// parsing. The case file, both models and the summaries then agree on every spelling.
#pragma once

#include <cassert>
#include <cstddef>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

namespace tmlab {

/// The name of `value` in `names` (indexed by the enum's value).
template <class E, std::size_t N>
std::string enum_name(const char* const (&names)[N], E value) {
  const auto k = static_cast<std::size_t>(value);
  assert(k < N);
  return names[k];
}

/// The value `name` denotes in `names`, or nothing (exact, case-sensitive).
template <class E, std::size_t N>
std::optional<E> enum_from_name(const char* const (&names)[N], const std::string& name) {
  for (std::size_t k = 0; k < N; ++k)
    if (name == names[k]) return static_cast<E>(k);
  return std::nullopt;
}

/// Every name, in declaration order (for messages that list the accepted values).
template <std::size_t N>
std::vector<std::string> enum_names(const char* const (&names)[N]) {
  return std::vector<std::string>(std::begin(names), std::end(names));
}

}  // namespace tmlab
