// scripts/same_records.py, the Slurm CI step's check (scripts/slurm-ci.sh) that a merged
// array equals a single run: equal when only time or host columns differ, unequal (exit 1,
// naming configuration and column) for any other column, a missing record or column, or a
// missing image; exit 2 for a folder without records.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "support/test_support.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct Check {
  int status;
  std::string output;
};

class SameRecords : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::make_temp_dir("ldm-same-records");
    base_ = json::array();
    for (const char* id : {"cornell-ppfla-ao-n4", "cornell-ppfla-ao-n8"})
      base_.push_back({{"config_id", id}, {"status", "ok"}, {"mse", 0.0213}, {"n_views", 4},
                       {"lists_checksum", "ab12"}, {"build_ms_median", 2.1}, {"frame_ms_ci_high", 15.0},
                       {"wall_seconds", 0.3}, {"ref_render_seconds", 0.15}, {"ref_from_cache", false},
                       {"host", "vm"}, {"slurm_job_id", "7"}, {"image_png", std::string("images/") + id + ".png"}});
  }

  // Writes the records as a run folder NAME (with the images they name) and returns its path.
  std::string run(const std::string& name, const json& records) const {
    const fs::path folder = dir_ / name;
    fs::create_directories(folder / "images");
    std::ofstream(folder / "records.json") << json{{"run", json::object()}, {"records", records}}.dump();
    for (const auto& r : records)
      if (r.contains("image_png")) std::ofstream(folder / r["image_png"].get<std::string>()) << "png";
    return folder.string();
  }

  Check compare(const std::string& a, const std::string& b) const {
    Check c{};
    c.status = test::run_command(std::string(LDM_PYTHON) + " " + LDM_TEST_SOURCE_DIR +
                                     "/../scripts/same_records.py " + a + " " + b, &c.output);
    return c;
  }

  fs::path dir_;
  json base_;
};

TEST_F(SameRecords, TimeHostAndOrderDoNotCount) {
  json other = json::array({base_[1], base_[0]});  // a merge's order
  for (auto& r : other) {
    r["build_ms_median"] = 9.9;
    r["frame_ms_ci_high"] = 99.0;
    r["wall_seconds"] = 5.0;
    r["ref_render_seconds"] = 0.0;
    r["ref_from_cache"] = true;
    r["host"] = "node7";
    r["slurm_job_id"] = "8";
  }
  const Check c = compare(run("a", base_), run("b", other));
  EXPECT_EQ(c.status, 0) << c.output;
  EXPECT_NE(c.output.find("the same 2 records"), std::string::npos) << c.output;
}

TEST_F(SameRecords, AnyOtherDifferenceFails) {
  const std::string a = run("a", base_);
  json value = base_;
  value[1]["mse"] = 0.0214;
  Check c = compare(a, run("value", value));
  EXPECT_EQ(c.status, 1) << c.output;
  EXPECT_NE(c.output.find("cornell-ppfla-ao-n8: mse: 0.0213 != 0.0214"), std::string::npos) << c.output;

  json missing_record = json::array({base_[0]});
  c = compare(a, run("missing_record", missing_record));
  EXPECT_EQ(c.status, 1) << c.output;
  EXPECT_NE(c.output.find("cornell-ppfla-ao-n8: missing from"), std::string::npos) << c.output;

  json missing_column = base_;
  missing_column[0].erase("lists_checksum");
  c = compare(run("missing_column", missing_column), a);
  EXPECT_EQ(c.status, 1) << c.output;
  EXPECT_NE(c.output.find("column lists_checksum only in"), std::string::npos) << c.output;

  const std::string no_image = run("no_image", base_);
  fs::remove(fs::path(no_image) / "images" / "cornell-ppfla-ao-n4.png");
  c = compare(a, no_image);
  EXPECT_EQ(c.status, 1) << c.output;
  EXPECT_NE(c.output.find("does not exist"), std::string::npos) << c.output;

  c = compare(a, (dir_ / "nothing").string());
  EXPECT_EQ(c.status, 2) << c.output;
  EXPECT_NE(c.output.find("cannot read its records"), std::string::npos) << c.output;
}

}  // namespace
}  // namespace ldm
