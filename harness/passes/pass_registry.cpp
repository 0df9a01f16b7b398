// The list of passes `--pass` accepts. A new pass adds one line here.
#include <functional>

#include "harness/passes/ambient_occlusion.h"
#include "harness/passes/hbao.h"
#include "harness/passes/indirect_lighting.h"
#include "harness/passes/pass.h"
#include "harness/passes/rtao.h"
#include "harness/util/error.h"

namespace ldm {
namespace {

struct Entry {
  const char* name;
  std::function<std::unique_ptr<Pass>(StructureParams&)> make;
};

const std::vector<Entry>& registry() {
  static const std::vector<Entry> entries = {
      {"ao", [](StructureParams& p) { return std::make_unique<AmbientOcclusion>(p); }},
      {"hbao", [](StructureParams& p) { return std::make_unique<Hbao>(p); }},
      {"rtao", [](StructureParams& p) { return std::make_unique<Rtao>(p); }},
      {"indirect", [](StructureParams& p) { return std::make_unique<IndirectLighting>(p); }},
  };
  return entries;
}

}  // namespace

std::vector<std::string> pass_names() {
  std::vector<std::string> names;
  for (const auto& e : registry()) names.emplace_back(e.name);
  return names;
}

std::unique_ptr<Pass> make_pass(const std::string& name, StructureParams params) {
  for (const auto& e : registry()) {
    if (name == e.name) {
      auto pass = e.make(params);
      params.finish("pass " + name);
      return pass;
    }
  }
  std::string known;
  for (const auto& n : pass_names()) known += (known.empty() ? "" : ", ") + n;
  throw UserError("--pass: unknown pass '" + name + "' (known: " + known + ")");
}

}  // namespace ldm
