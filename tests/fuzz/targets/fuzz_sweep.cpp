// libFuzzer target: any bytes as a sweep file. The parser must either give combinations
// (each naming only known axes) or throw UserError; anything else (another exception, a
// crash, undefined behaviour, a hang) is a finding. The vocabulary is fixed: the parser
// knows the registries only through it (harness/run/sweep_spec.h).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "harness/run/sweep_spec.h"
#include "harness/util/error.h"

namespace {

// A vocabulary of every kind of axis the parser checks (names, integers, reals, image sizes,
// parameters of two owners), declared here: the target links the parser alone, not the
// registries whose declarations ldmbench uses.
ldm::SweepVocabulary fuzz_vocabulary() {
  using ldm::AxisKind;
  using ldm::AxisSpec;
  auto axis = [](const char* key, AxisKind kind, double lo, double hi, std::vector<std::string> choices = {}) {
    AxisSpec a;
    a.key = key;
    a.kind = kind;
    a.min = lo;
    a.max = hi;
    a.choices = std::move(choices);
    return a;
  };
  ldm::SweepVocabulary v;
  v.axes = {axis("scenes", AxisKind::Text, 0, 0),
            axis("passes", AxisKind::Choice, 0, 0, {"ao", "hbao"}),
            axis("structures", AxisKind::Choice, 0, 0, {"psppsll", "ppsll", "dfbuffer", "habuffer", "ppfla", "psppfla"}),
            axis("views", AxisKind::UInt, 1, 4096),
            axis("r_ldm", AxisKind::UInt, 1, 8192),
            axis("d_max", AxisKind::Real, 1e-30, 1e30),
            axis("visibility", AxisKind::Choice, 0, 0, {"scene", "attenuated", "unattenuated"}),
            axis("trace", AxisKind::Choice, 0, 0, {"listing5", "interval", "plane"}),
            axis("sizing_budget_mib", AxisKind::Real, 0.001, 1048576),
            axis("image_size", AxisKind::ImageSize, 16, 16384),
            axis("frames", AxisKind::UInt, 1, 100000)};
  AxisSpec k = axis("k", AxisKind::UInt, 0, 1u << 20);
  k.owner = "ppfla";
  AxisSpec jitter = axis("jitter", AxisKind::Choice, 0, 0, {"off", "on"});
  jitter.owner = "hbao";
  AxisSpec reads = axis("atomic_reads", AxisKind::Bool, 0, 0);
  reads.owner = "psppsll";
  v.parameters = {{"ppfla", {k}}, {"hbao", {jitter}}, {"psppsll", {reads}}};
  // A run-wide setting of every kind, top level and grouped (ldmbench's own come from
  // harness/settings/run_setting_table.h).
  // (SettingRule's fields in order: path, kind, min, max, positive, choices.)
  using Kind = ldm::SettingRule::Kind;
  v.settings = {{"timing.repetitions", Kind::Integer, 1, 1000},
                {"timing.isolation", Kind::Choice, 0, 0, false, {"context", "process"}},
                {"timing.cap_s", Kind::Real, 0, 86400},
                {"timer", Kind::Choice, 0, 0, false, {"auto", "gl_timestamp", "fenced_wall_clock"}},
                {"reference.enabled", Kind::Flag},
                {"reference.spp", Kind::Integer, 0, 1 << 20},
                {"reference.noise", Kind::Real, 0, 0, true},
                {"reference.max_spp", Kind::Integer, 1, 1 << 20},
                {"images", Kind::Flag}};
  return v;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  static const ldm::SweepVocabulary vocabulary = fuzz_vocabulary();
  try {
    ldm::SweepSpec spec = ldm::parse_sweep_spec(text, "fuzz.json", vocabulary);
    const auto combinations = ldm::sweep_combinations(spec);
    if (combinations.size() > ldm::kMaxSweepCombinations) __builtin_trap();
  } catch (const ldm::UserError&) {
    // The expected answer to bad input.
  }
  return 0;
}
