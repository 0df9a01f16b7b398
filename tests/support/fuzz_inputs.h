#pragma once
// The fuzzers' seed corpus and every crash input they found (tests/fuzz/{corpus,crashes}/
// TARGET/), replayed in the ordinary build through the same code as the fuzz target: each
// input is accepted or refused with a UserError, never anything else.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "harness/util/error.h"

namespace ldm::test {

// The inputs of fuzz target `target`, its corpus's then its crashes' (hidden files left out).
inline std::vector<std::filesystem::path> fuzz_inputs(const std::string& target) {
  namespace fs = std::filesystem;
  std::vector<fs::path> files;
  for (const char* kind : {"corpus", "crashes"}) {
    const fs::path dir = fs::path(LDM_TEST_SOURCE_DIR) / "fuzz" / kind / target;
    if (!fs::is_directory(dir)) continue;
    for (const auto& entry : fs::directory_iterator(dir))
      if (entry.is_regular_file() && entry.path().filename().string().front() != '.') files.push_back(entry.path());
  }
  return files;
}

struct FuzzReplay {
  size_t inputs = 0;    // how many inputs were replayed
  size_t accepted = 0;  // how many of them `judge` accepted (returned from)
};

// judge(file, bytes) on every input of `target`: it returns (accepted) or throws UserError
// (refused); any other exception fails the test.
template <typename Judge>
FuzzReplay replay_fuzz_inputs(const std::string& target, Judge judge) {
  FuzzReplay replay;
  for (const std::filesystem::path& file : fuzz_inputs(target)) {
    std::ifstream in(file, std::ios::binary);
    std::stringstream bytes;
    bytes << in.rdbuf();
    ++replay.inputs;
    try {
      judge(file, bytes.str());
      ++replay.accepted;
    } catch (const UserError&) {
    } catch (const std::exception& e) {
      ADD_FAILURE() << file << ": " << e.what();
    }
  }
  return replay;
}

}  // namespace ldm::test
