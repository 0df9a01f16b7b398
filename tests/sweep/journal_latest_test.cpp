// latest_per_configuration (harness/records/journal.h): a configuration measured again
// (--redo-failed) counts once, with its later record, in its first place.
#include <gtest/gtest.h>

#include "harness/records/journal.h"

namespace ldm {
namespace {

Record record(const std::string& id, const std::string& status) {
  Record r;
  r.set("config_id", id);
  r.set("status", status);
  return r;
}

TEST(SweepJournal, TheLaterRecordOfAConfigurationCountsInItsFirstPlace) {
  const auto latest = latest_per_configuration(
      {record("a", "failed"), record("b", "ok"), record("a", "ok"), record("c", "failed")});
  ASSERT_EQ(latest.size(), 3u);
  EXPECT_EQ(std::get<std::string>(*latest[0].get("config_id")), "a");
  EXPECT_EQ(std::get<std::string>(*latest[0].get("status")), "ok");
  EXPECT_EQ(std::get<std::string>(*latest[1].get("config_id")), "b");
  EXPECT_EQ(std::get<std::string>(*latest[2].get("config_id")), "c");
}

}  // namespace
}  // namespace ldm
