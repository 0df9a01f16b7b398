// Work counters of the HA-buffer, PPFLA and PSPPFLA (issue 33): what their build, sort and
// query shaders count in the counting replay, checked against facts known independently of
// the counters (the census's fragments and depth profile, the AO pass's own entries read,
// the algorithms' own invariants), equal between two runs where declared deterministic, and
// larger for a heavier configuration. The HA-buffer's 64-bit keys need 64-bit atomics, which
// llvmpipe lacks: that case is skipped there and runs under zink.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "harness/measuring/measurement.h"
#include "harness/settings/record_schema.h"
#include "harness/scene/scene_loader.h"
#include "support/test_support.h"
#include "work/counted_measurement.h"

namespace ldm {
namespace {

namespace fs = std::filesystem;

using work_test::Counted;
using work_test::count;
using work_test::over_pixels;
using work_test::as_number;

uint64_t pixel_count(uint32_t views, uint32_t resolution) { return uint64_t(views) * resolution * resolution; }

// Every counter the schema declares deterministic equal between two runs; the arrival-
// dependent ones present in both.
void expect_deterministic_equal(const Counted& a, const Counted& b, const std::string& what) {
  size_t compared = 0;
  for (const auto& [column, value] : a.work) {
    ASSERT_TRUE(b.work.count(column)) << what << " " << column << " in one run only";
    const ColumnSpec* spec = find_column(column);
    ASSERT_NE(spec, nullptr) << column << " is not in the schema";
    if (!spec->deterministic) continue;
    ++compared;
    EXPECT_EQ(value, b.work.at(column)) << what << " " << column;
  }
  EXPECT_EQ(a.work.size(), b.work.size()) << what;
  EXPECT_GE(compared, 10u) << what;
}

bool hash_declared_deterministic(const std::string& column) {
  const ColumnSpec* spec = find_column(column);
  return spec && spec->deterministic;
}

TEST(HashAndArrayWork, PpflaCountsWhatTheCensusAndTheTraceSay) {
  const Counted c = count("ppfla", 4, 32);
  const double fragments = c.fragments;
  EXPECT_EQ(c["work_construct_fragments"], fragments);
  // One atomicAdd per fragment; nothing dropped (k from the census).
  EXPECT_EQ(c["work_construct_atomic_add"], fragments);
  EXPECT_EQ(c["work_construct_fragments_dropped"], 0);
  EXPECT_EQ(c["work_construct_bytes_loaded_counts"], 4 * fragments);
  EXPECT_EQ(c["work_construct_bytes_stored_counts"], 4 * fragments);
  EXPECT_EQ(c["work_construct_bytes_stored_entries"], 4 * fragments);
  // The sort: one invocation per pixel in groups of 64, one list per pixel.
  const double all_pixels = double(pixel_count(4, 32));
  EXPECT_GE(c["work_sort_invocations"], all_pixels);
  EXPECT_EQ(std::fmod(c["work_sort_invocations"], 64.0), 0.0);
  EXPECT_EQ(c["work_sort_bytes_loaded_counts"], 4 * all_pixels);
  EXPECT_EQ(c["work_sort_list_length_total"], fragments);
  EXPECT_EQ(c["work_sort_list_length_max"], c.m.number(columns::kMaxDepthComplexity));
  EXPECT_DOUBLE_EQ(c["work_sort_list_length_mean"], fragments / all_pixels);
  // A heap sort of n >= 2 entries reads every one at least once and writes every one.
  const double sorted_entries = over_pixels(c, [](double n) { return n >= 2 ? n : 0.0; });
  EXPECT_GE(c["work_sort_bytes_loaded_entries"], 4 * sorted_entries);
  EXPECT_GE(c["work_sort_bytes_stored_entries"], 4 * sorted_entries);
  EXPECT_TRUE(c.work.count("work_sort_comparisons"));  // declared for ldm/common/heap_sort.glsl
  EXPECT_TRUE(c.work.count("work_sort_moves"));
  // Queries: a slot per entry the trace read (the AO pass's own count), its bytes where read.
  EXPECT_EQ(c["work_ao_slots_scanned_total"], c["work_ao_entries_read_total"]);
  EXPECT_EQ(c["work_ao_slots_scanned_max"], 1);
  EXPECT_EQ(c["work_ao_bytes_loaded_entries"], 4 * c["work_ao_entries_read_total"]);
  // A count per walk: at most one walk per covered pixel and view.
  EXPECT_GT(c["work_ao_bytes_loaded_counts"], 0);
  EXPECT_LE(c["work_ao_bytes_loaded_counts"], 4 * 4 * c["work_ao_covered_pixels"]);
}

TEST(HashAndArrayWork, PsppflaCountsWhatTheCensusAndTheTraceSay) {
  const Counted c = count("psppfla", 4, 32);
  const double fragments = c.fragments;
  // Each walk ends at the first empty entry: a pixel of n fragments takes 1 + ... + n
  // atomicMin whatever the order (k from the census: nothing dropped).
  const double walked = over_pixels(c, [](double n) { return n * (n + 1) / 2; });
  EXPECT_EQ(c["work_construct_atomic_min"], walked);
  EXPECT_TRUE(hash_declared_deterministic("work_construct_atomic_min"));
  EXPECT_EQ(c["work_construct_bytes_loaded_entries"], 4 * walked);
  EXPECT_EQ(c["work_construct_bytes_stored_entries"], 4 * walked);
  EXPECT_EQ(c["work_construct_fragments_dropped"], 0);
  EXPECT_EQ(c["work_construct_atomic_add"], 0);
  // A fragment shifts at most the entries it walked past (all but the empty one it took).
  EXPECT_LE(c["work_construct_slots_shifted_total"], walked - fragments);
  EXPECT_LE(c["work_construct_slots_shifted_max"], c.m.number(columns::kMaxDepthComplexity) - 1.0);
  EXPECT_DOUBLE_EQ(c["work_construct_slots_shifted_mean"] * fragments,
                   c["work_construct_slots_shifted_total"]);
  EXPECT_FALSE(hash_declared_deterministic("work_construct_slots_shifted_total"));
  // Queries: a slot per entry read, plus the empty one that ends a walk that reached it.
  EXPECT_GE(c["work_ao_slots_scanned_total"], c["work_ao_entries_read_total"]);
  EXPECT_EQ(c["work_ao_slots_scanned_max"], 1);
  EXPECT_EQ(c["work_ao_bytes_loaded_entries"], 4 * c["work_ao_slots_scanned_total"]);
}

TEST(HashAndArrayWork, HaBufferCountsWhatItsInsertionsAndTheTraceSay) {
  const Counted c = count("habuffer", 4, 32);  // 32-bit keys, every device
  const double fragments = c.fragments;
  const double probes = c["work_construct_hash_probes_total"];
  const double evictions = c["work_construct_evictions"];
  // Every insertion ends in one empty slot; each other slot it tried aged it by one.
  EXPECT_GE(probes, fragments);
  EXPECT_EQ(c["work_construct_hash_probes_mean"] * fragments, probes);
  EXPECT_EQ(c["work_construct_age_bumps"], probes - fragments);
  // atomicMax: one per slot tried, one on the age table per placement (the fragment's own
  // and every evicted entry's); those that took no slot failed.
  EXPECT_EQ(c["work_construct_atomic_max"], probes + fragments + evictions);
  EXPECT_EQ(c["work_construct_atomic_max_64"], 0);
  EXPECT_EQ(c["work_construct_atomic_max_failed"], probes - fragments - evictions);
  EXPECT_EQ(c["work_construct_atomic_add_on_loss"], 0);
  EXPECT_EQ(c["work_construct_bytes_loaded_table"], 4 * probes);
  EXPECT_EQ(c["work_construct_bytes_stored_table"], 4 * probes);
  EXPECT_EQ(c["work_construct_bytes_loaded_age_table"], 4 * (fragments + evictions));
  EXPECT_EQ(c["work_construct_bytes_loaded_ha_offsets"], 4 * (probes + evictions));
  EXPECT_FALSE(hash_declared_deterministic("work_construct_hash_probes_total"));
  // Queries: every entry the trace read was found by at least one probe.
  EXPECT_GE(c["work_ao_hash_probes_total"], c["work_ao_entries_read_total"]);
  EXPECT_GE(c["work_ao_hash_probes_max"], 1);
  EXPECT_EQ(c["work_ao_bytes_loaded_table"], 4 * c["work_ao_hash_probes_total"]);
  EXPECT_EQ(c["work_ao_bytes_loaded_ha_offsets"], 4 * c["work_ao_hash_probes_total"]);
  EXPECT_LE(c["work_ao_bytes_loaded_age_table"], 4 * 4 * c["work_ao_covered_pixels"]);
  EXPECT_TRUE(hash_declared_deterministic("work_ao_hash_probes_total"));
}

TEST(HashAndArrayWork, DeterministicCountersAreEqualInTwoRuns) {
  for (const std::string structure : {"habuffer", "ppfla", "psppfla"}) {
    const Counted a = count(structure, 4, 32), b = count(structure, 4, 32);
    expect_deterministic_equal(a, b, structure);
  }
}

TEST(HashAndArrayWork, AHeavierConfigurationCountsMore) {
  const std::vector<std::pair<std::string, std::vector<std::string>>> grow = {
      {"habuffer", {"work_construct_hash_probes_total", "work_construct_atomic_max", "work_ao_hash_probes_total",
                    "work_ao_bytes_loaded_table"}},
      {"ppfla", {"work_construct_atomic_add", "work_sort_list_length_total", "work_sort_invocations",
                 "work_sort_bytes_loaded_entries", "work_ao_slots_scanned_total"}},
      {"psppfla", {"work_construct_atomic_min", "work_construct_bytes_stored_entries", "work_ao_slots_scanned_total"}},
  };
  for (const auto& [structure, columns] : grow) {
    const Counted light = count(structure, 4, 32), heavy = count(structure, 8, 32);
    for (const auto& column : columns) EXPECT_GT(heavy[column], light[column]) << structure << " " << column;
  }
}

// 64-bit keys: the table's atomicMax become 64-bit ones of 8 bytes; the table holds its
// entries in the same slots as with 32-bit keys, so the queries probe exactly as much.
TEST(HashAndArrayWork, HaBufferSixtyFourBitKeysCountSixtyFourBitAtomics) {
  if (!test::gl_context().device().has_int64_atomics)
    GTEST_SKIP() << "64-bit keys need GL_NV_shader_atomic_int64 (llvmpipe lacks it; run under zink)";
  const Counted wide = count("habuffer", 4, 32, {{"key_bits", "64"}});
  const Counted narrow = count("habuffer", 4, 32, {{"key_bits", "32"}});
  const double fragments = wide.fragments;
  const double probes = wide["work_construct_hash_probes_total"];
  EXPECT_EQ(wide["work_construct_atomic_max_64"], probes);
  EXPECT_EQ(wide["work_construct_atomic_max"], fragments + wide["work_construct_evictions"]);
  EXPECT_EQ(wide["work_construct_bytes_loaded_table"], 8 * probes);
  EXPECT_EQ(wide["work_ao_bytes_loaded_table"], 8 * wide["work_ao_hash_probes_total"]);
  EXPECT_EQ(wide["work_ao_hash_probes_total"], narrow["work_ao_hash_probes_total"]);
  EXPECT_EQ(wide["work_ao_hash_probes_max"], narrow["work_ao_hash_probes_max"]);
}

// Why the HA-buffer's query probes are deterministic although its insertions race: a model of
// ha_build.frag (one atomicMax per step on age-and-depth keys, the evicted entry carried on)
// under random interleavings of the insertions in flight ends in one table, always, even a
// table too small that drops entries at max age. Which slot holds which pixel's entry is what
// a query probes, so its probes do not depend on the order of arrival.
TEST(HashAndArrayWork, HaBufferTableDoesNotDependOnInsertionOrder) {
  struct Table {
    std::vector<uint32_t> keys;
    uint32_t dropped = 0;
  };
  auto build = [](const std::vector<std::pair<uint32_t, uint32_t>>& fragments, uint32_t size,
                  const std::vector<uint32_t>& offsets, uint32_t max_age, uint32_t seed) {
    struct Carried {
      uint32_t pixel, age, key;
    };
    auto key = [](uint32_t age, uint32_t depth_bits) { return ((age + 1) << 24) | depth_bits; };
    std::mt19937 random(seed);
    std::vector<Carried> waiting, flying;
    for (const auto& [pixel, depth] : fragments) waiting.push_back({pixel, 0, key(0, 0xFFFFFFu - depth)});
    std::shuffle(waiting.begin(), waiting.end(), random);
    Table t{std::vector<uint32_t>(size, 0u), 0};
    while (!waiting.empty() || !flying.empty()) {
      if (!waiting.empty() && (flying.empty() || random() % 2)) {
        flying.push_back(waiting.back());
        waiting.pop_back();
      }
      const size_t i = random() % flying.size();
      Carried& c = flying[i];
      const uint32_t slot = (c.pixel + offsets[c.age]) % size;
      const uint32_t previous = t.keys[slot];
      t.keys[slot] = std::max(previous, c.key);  // atomicMax
      bool done = false;
      if (previous < c.key) {
        if (previous == 0) {
          done = true;
        } else {
          c.key = previous;
          c.age = (previous >> 24) - 1;
          c.pixel = (slot + size - offsets[c.age]) % size;  // age equivalence
        }
      }
      if (!done && c.age == max_age) {
        ++t.dropped;
        done = true;
      }
      if (done) {
        flying.erase(flying.begin() + long(i));
        continue;
      }
      ++c.age;
      c.key = key(c.age, c.key & 0xFFFFFFu);
    }
    return t;
  };
  std::mt19937 random(33);
  size_t lossy = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const uint32_t pixels = 5 + random() % 40, size = pixels + random() % 40;
    const uint32_t max_age = std::vector<uint32_t>{3, 8, 30}[random() % 3];
    std::vector<uint32_t> offsets(max_age + 1);
    for (auto& o : offsets) o = random() % size;
    const double load = std::vector<double>{0.5, 0.9, 1.3}[random() % 3];
    std::vector<std::pair<uint32_t, uint32_t>> fragments(1 + random() % uint32_t(size * load));
    for (auto& f : fragments) f = {uint32_t(random() % pixels), uint32_t(random() % 50)};  // ties too
    const Table first = build(fragments, size, offsets, max_age, 0);
    lossy += first.dropped > 0;
    for (uint32_t seed = 1; seed < 6; ++seed) {
      const Table other = build(fragments, size, offsets, max_age, seed);
      ASSERT_EQ(other.keys, first.keys) << "trial " << trial << " order " << seed;
      ASSERT_EQ(other.dropped, first.dropped) << "trial " << trial << " order " << seed;
    }
  }
  EXPECT_GT(lossy, 10u) << "the model should also have run tables that drop entries";
}

// The regression guard's deliberate slowdown (tests/compare): one more probe at the start of
// every seek that has an age left, its key ignored, raises the deterministic
// work_ao_hash_probes_total by exactly the entries the trace found (each such seek finds one)
// and changes nothing the records judge.
TEST(HashAndArrayWork, OneMoreProbePerSeekRaisesTheDeterministicProbes) {
  const fs::path source = fs::path(LDM_TEST_SOURCE_DIR) / ".." / "shaders";
  const fs::path copy = fs::path(test::make_temp_dir("ldm-ha-probe")) / "shaders";
  fs::copy(source, copy, fs::copy_options::recursive);
  const fs::path query = copy / "ldm" / "habuffer" / "ha_query.glsl";
  std::stringstream text;
  text << std::ifstream(query).rdbuf();
  std::string shader = text.str();
  const std::string from = "  for (; c.age < c.end; ++c.age) {\n";
  ASSERT_NE(shader.find(from), std::string::npos) << "ha_query.glsl no longer holds the patched line";
  ASSERT_EQ(shader.find(from, shader.find(from) + 1), std::string::npos);
  shader.replace(shader.find(from), from.size(),
                 "  if (c.age < c.end) ha_probe(c.pixel, c.age);  // slowdown: one probe more, its key ignored\n" + from);
  std::ofstream(query) << shader;

  auto run = [](const std::string& environment) {
    const std::string out = test::make_temp_dir("ldm-ha-probe-run");
    const test::Outcome o = test::ldmbench(
        "run --scene cornell --structure habuffer --pass ao -N 4 -R 32 --width 48 --height 40 --frames 2 "
        "--warmup 1 --time-target 0 --reference-spp 16 --no-images --out " + out,
        environment);
    EXPECT_EQ(o.status, 0) << o.output;
    std::ifstream in(out + "/records.json");
    return nlohmann::json::parse(in).at("records").at(0);
  };
  const nlohmann::json plain = run(""), patched = run("LDM_SHADER_DIR=" + copy.string());
  EXPECT_EQ(plain.at("status"), "ok");
  EXPECT_EQ(patched.at("status"), "ok") << patched.value("status_detail", "");
  EXPECT_EQ(patched.at("lists_checksum"), plain.at("lists_checksum"));
  EXPECT_EQ(patched.at("mse"), plain.at("mse"));
  EXPECT_EQ(patched.at("work_ao_hash_probes_total").get<double>(),
            plain.at("work_ao_hash_probes_total").get<double>() + plain.at("work_ao_entries_read_total").get<double>());
  EXPECT_EQ(patched.at("work_ao_entries_read_total"), plain.at("work_ao_entries_read_total"));
  EXPECT_EQ(patched.at("work_construct_fragments"), plain.at("work_construct_fragments"));
}

}  // namespace
}  // namespace ldm
