// The list of structures `--structure` accepts. A new structure adds one line here.
#include <functional>

#include "harness/util/error.h"
#include "harness/axes/named_registry.h"
#include "ldm_impls/ldm_structure.h"
#include "ldm_impls/dfbuffer/dfbuffer.h"
#include "ldm_impls/fixed_arrays/ppfla.h"
#include "ldm_impls/fixed_arrays/psppfla.h"
#include "ldm_impls/habuffer/habuffer.h"
#include "ldm_impls/ppsll/ppsll.h"
#include "ldm_impls/psppsll/psppsll.h"

namespace ldm {
namespace {

struct Entry {
  const char* name;
  std::function<std::vector<AxisSpec>()> parameters;
  std::function<std::unique_ptr<LdmStructure>(StructureParams&)> make;
  std::function<std::vector<WorkCounter>()> work;
  std::function<std::vector<WorkCounter>()> query_work;
};

const std::vector<Entry>& registry() {
  static const std::vector<Entry> entries = {
      {"psppsll", Psppsll::parameters, [](StructureParams& p) { return std::make_unique<Psppsll>(p); }, Psppsll::work_counters, Psppsll::query_work_counters},
      {"ppsll", Ppsll::parameters, [](StructureParams& p) { return std::make_unique<Ppsll>(p); }, Ppsll::work_counters, Ppsll::query_work_counters},
      {"dfbuffer", DfBuffer::parameters, [](StructureParams& p) { return std::make_unique<DfBuffer>(p); }, DfBuffer::work_counters, DfBuffer::query_work_counters},
      {"habuffer", HaBuffer::parameters, [](StructureParams& p) { return std::make_unique<HaBuffer>(p); }, HaBuffer::work_counters, HaBuffer::query_work_counters},
      {"ppfla", Ppfla::parameters, [](StructureParams& p) { return std::make_unique<Ppfla>(p); }, Ppfla::work_counters, Ppfla::query_work_counters},
      {"psppfla", Psppfla::parameters, [](StructureParams& p) { return std::make_unique<Psppfla>(p); }, Psppfla::work_counters, Psppfla::query_work_counters},
  };
  return entries;
}

const Entry& entry(const std::string& name) {
  return registry_entry(registry(), name, "--structure", "structure");
}

}  // namespace

std::vector<std::string> structure_names() { return registry_names(registry()); }

std::vector<AxisSpec> structure_parameters(const std::string& name) { return registry_parameters(entry(name)); }

std::vector<WorkCounter> structure_work_counters(const std::string& name) { return entry(name).work(); }

std::vector<WorkCounter> structure_query_work_counters(const std::string& name, const std::string& subpass) {
  std::vector<WorkCounter> counters = entry(name).query_work();
  for (WorkCounter& c : counters) c.subpass = subpass;
  return counters;
}

std::unique_ptr<LdmStructure> make_structure(const std::string& name, StructureParams params) {
  return registry_make(entry(name), std::move(params), "structure");
}

}  // namespace ldm
