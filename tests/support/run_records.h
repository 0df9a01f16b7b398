#pragma once
// `ldmbench run` end to end for the suites that check its records: a run into fresh temporary
// folders, its records read back from records.json.
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "support/test_support.h"

namespace ldm::test {

struct RunRecords {
  std::filesystem::path out;  // the run folder
  nlohmann::json records;     // records.json's records; an empty array where the run failed
};

// `ldmbench run ARGS` with a --cache-dir and an --out of its own (temporary folders named
// after `name`); a run that does not exit 0 fails the test.
inline RunRecords run_records(const std::string& name, const std::string& args) {
  RunRecords run{std::filesystem::path(make_temp_dir("ldm-" + name)) / "run", nlohmann::json::array()};
  const std::string cache = make_temp_dir("ldm-" + name + "-cache");
  const Outcome o = ldmbench("run " + args + " --cache-dir " + cache + " --out " + run.out.string());
  EXPECT_EQ(o.status, 0) << o.output;
  if (o.status == 0) run.records = nlohmann::json::parse(read_text((run.out / "records.json").string()))["records"];
  return run;
}

// `ldmbench run ARGS` refused before any work (exit status 2, no --out written); its output.
inline std::string refused_run(const std::string& args) {
  const Outcome o = ldmbench("run " + args + " --out /nonexistent/never");
  EXPECT_EQ(o.status, 2) << args << ": " << o.output;
  return o.output;
}

}  // namespace ldm::test
