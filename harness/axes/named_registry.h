#pragma once
// Lookups in a registry of named entries, each with a `name` and its `parameters()`: the
// passes' (harness/passes/pass_registry.cpp) and the structures'
// (ldm_impls/structure_registry.cpp).
#include <string>
#include <vector>

#include "harness/axes/axis.h"
#include "harness/util/error.h"
#include "harness/util/text.h"

namespace ldm {

template <typename Entry>
std::vector<std::string> registry_names(const std::vector<Entry>& entries) {
  std::vector<std::string> names;
  for (const auto& e : entries) names.emplace_back(e.name);
  return names;
}

// The entry named `name`; else a UserError "<option>: unknown <what> '<name>' (known: ...)".
template <typename Entry>
const Entry& registry_entry(const std::vector<Entry>& entries, const std::string& name,
                            const std::string& option, const std::string& what) {
  for (const auto& e : entries)
    if (name == e.name) return e;
  throw UserError(option + ": unknown " + what + " '" + name + "' (known: " +
                  joined(registry_names(entries)) + ")");
}

// The entry's parameters, owned by it (set as --param NAME:KEY).
template <typename Entry>
std::vector<AxisSpec> registry_parameters(const Entry& entry) {
  std::vector<AxisSpec> specs = entry.parameters();
  for (AxisSpec& s : specs) s.owner = entry.name;
  return specs;
}

// What the entry makes from `params` (StructureParams), checked against its declared
// parameters; messages name it "<what> <name>".
template <typename Entry, typename Params>
auto registry_make(const Entry& entry, Params params, const std::string& what) {
  params.declare(registry_parameters(entry));
  auto made = entry.make(params);
  params.check(what + " " + std::string(entry.name));
  return made;
}

}  // namespace ldm
