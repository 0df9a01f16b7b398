// libFuzzer target: any bytes as a sweep file. The parser must either give combinations
// (each naming only known axes) or throw UserError; anything else (another exception, a
// crash, undefined behaviour, a hang) is a finding. The vocabulary is fixed: the parser
// knows the registries only through it (harness/app/sweep_spec.h).
#include <cstddef>
#include <cstdint>
#include <string>

#include "harness/app/sweep_spec.h"
#include "harness/util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const ldm::SweepVocabulary vocabulary = {
      {"psppsll", "ppsll", "dfbuffer", "habuffer", "ppfla", "psppfla"},
      {"ao", "hbao"},
      {"listing5", "interval", "plane"},
      {"eq13", "normalized"}};
  try {
    ldm::SweepSpec spec = ldm::parse_sweep_spec(text, "fuzz.json", vocabulary);
    const auto combinations = ldm::sweep_combinations(spec);
    if (combinations.size() > ldm::kMaxSweepCombinations) __builtin_trap();
  } catch (const ldm::UserError&) {
    // The expected answer to bad input.
  }
  return 0;
}
