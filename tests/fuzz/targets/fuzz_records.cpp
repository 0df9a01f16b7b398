// libFuzzer target: the records reader of `ldmbench merge`, `compare` and `report` (issue 19):
// a journal, a records.csv and a records.json in one input (records_input.h). UserError is
// the expected answer to bad input; anything else (the derived tables disagreeing with their
// journal, another exception, a crash, undefined behaviour, a hang) is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "tests/fuzz/targets/records_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    ldm::fuzz::judge_records_input(std::string(reinterpret_cast<const char*>(data), size));
  } catch (const std::logic_error&) {
    __builtin_trap();
  }
  return 0;
}
