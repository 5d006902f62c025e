#include "verification/harness/registry.hpp"

#include "core/base/error.hpp"

#include <cassert>
#include <stdexcept>

namespace tmlab::verify {

void CheckRegistry::add(const std::string& kind, CheckFunction fn) {
  if (!fns_.emplace(kind, std::move(fn)).second)
    throw std::logic_error("verification check kind '" + kind + "' registered twice");
}

void CheckRegistry::add(std::initializer_list<std::pair<std::string, CheckFunction>> checks) {
  for (const auto& [kind, fn] : checks) add(kind, fn);
}

const CheckFunction& CheckRegistry::get(const VerificationCase& c) const {
  const auto it = fns_.find(c.kind);
  if (it == fns_.end()) {
    std::string known;
    for (const auto& [k, f] : fns_) known += (known.empty() ? "" : ", ") + k;
    throw Error(c.spec_file().string() + ": key 'kind': unknown check '" + c.kind +
                "' in this build (known: " + known + ")");
  }
  return it->second;
}

std::vector<std::string> CheckRegistry::kinds() const {
  std::vector<std::string> out;
  for (const auto& [k, f] : fns_) out.push_back(k);
  return out;
}

}  // namespace tmlab::verify
