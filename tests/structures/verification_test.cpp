// The sampled verification of builds (ldm_impls/common/build_verifier.h), for every registered
// structure: samples of identical builds find nothing, the rotation visits every pixel once
// per stride, and a build whose lists were deliberately changed is caught by a sample alone
// (no full check), as it is by the full check of --verify every.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

#include "harness/gl/bindings.h"
#include "ldm_impls/common/build_verifier.h"
#include "harness/util/error.h"
#include "ldm_impls/ldm_structure.h"
#include "support/ldm_fixture.h"

namespace ldm {
namespace {

using test::LdmFixture;

class Verification : public ::testing::TestWithParam<std::string> {
 protected:
  const std::string& structure() const { return GetParam(); }
};

// Moves every view's eye back along its forward axis by `shift` in the GPU's view buffer,
// leaving the projection alone: the next build covers the same pixels with the same number
// of fragments, every depth `shift` farther. A change no capacity check or count can see,
// as a race that reorders or replaces nodes would be. The layout is GpuView's
// (harness/views/view_set.cpp): 144 bytes a view, eye.xyz at byte 64, forward.xyz at 80.
void shift_view_eyes(const LdmFixture& f, float shift) {
  f.gpu_views->bind();
  GLint buffer = 0;
  glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, kViewsBinding, &buffer);
  ASSERT_NE(buffer, 0);
  constexpr size_t kViewBytes = 144, kEye = 64, kForward = 80;
  std::vector<unsigned char> bytes(kViewBytes * f.views.size());
  glGetNamedBufferSubData(GLuint(buffer), 0, GLsizeiptr(bytes.size()), bytes.data());
  for (size_t v = 0; v < f.views.size(); ++v) {
    float eye[3], forward[3];
    std::memcpy(eye, &bytes[v * kViewBytes + kEye], sizeof eye);
    std::memcpy(forward, &bytes[v * kViewBytes + kForward], sizeof forward);
    for (int i = 0; i < 3; ++i) eye[i] -= forward[i] * shift;
    std::memcpy(&bytes[v * kViewBytes + kEye], eye, sizeof eye);
  }
  // The view buffer is immutable storage (no dynamic flag): replace its contents through a
  // copy from a buffer that holds the edited bytes.
  GlBuffer edited("edited_views", bytes.size(), bytes.data(), 0);
  glCopyNamedBufferSubData(edited.id(), GLuint(buffer), 0, 0, GLsizeiptr(bytes.size()));
  glMemoryBarrier(GL_ALL_BARRIER_BITS);
}

// One structure built on the Cornell box (N 8, R_LDM 32: 128 blocks), its first build
// verified; `rebuild()` builds again and verifies that build.
struct CheckedBuilds {
  CheckedBuilds(const std::string& structure, VerifyMode mode, uint32_t stride = 4)
      : f("cornell", 8, 32),
        s(f.build(structure)),
        inspector(*s, *f.inputs),
        health(f.census),
        verifier(*s, inspector, health, mode, stride) {
    verifier.verify(false);  // the first build: in full
  }
  // `storage_changed`: as after a rebuild or reallocation by the sizing policy.
  void rebuild(bool storage_changed = false) {
    s->build(*f.inputs, nullptr);
    verifier.verify(storage_changed);
  }
  void change_the_next_build() { shift_view_eyes(f, 0.01f * f.views.views[0].depth_range); }

  const LdmFixture f;
  const std::unique_ptr<LdmStructure> s;
  const LdmInspector inspector;
  BuildHealth health;
  BuildVerifier verifier;
};

TEST_P(Verification, SamplesOfIdenticalBuildsFindNothingAndCoverEveryPixelOncePerStride) {
  constexpr uint32_t kStride = 4;
  CheckedBuilds c(structure(), VerifyMode::Sampled, kStride);
  for (uint32_t i = 0; i < kStride; ++i) c.rebuild();
  EXPECT_EQ(c.health.status(), BuildStatus::Ok) << c.health.detail();
  EXPECT_EQ(c.health.checksum_changes(), 0u);
  EXPECT_EQ(c.verifier.counts().full, 1u);
  EXPECT_EQ(c.verifier.counts().sampled, kStride);
  // Phases 0 .. stride-1 visit every block exactly once.
  EXPECT_EQ(c.verifier.counts().sampled_pixels, c.f.views.total_pixels());
  EXPECT_EQ(c.verifier.last_stats().fragments_stored + c.verifier.last_stats().fragments_lost,
            c.f.census.total_fragments);
}

TEST_P(Verification, AChangedBuildIsCaughtByOneSample) {
  CheckedBuilds c(structure(), VerifyMode::Sampled);
  ASSERT_EQ(c.health.status(), BuildStatus::Ok) << c.health.detail();
  c.change_the_next_build();
  c.rebuild();
  EXPECT_EQ(c.verifier.counts().full, 1u) << "the changed build must be judged by its sample";
  EXPECT_EQ(c.verifier.counts().sampled, 1u);
  EXPECT_EQ(c.health.checksum_changes(), 1u);
  EXPECT_EQ(c.health.status(), BuildStatus::Invalid);
  EXPECT_NE(c.health.detail().find("sampled 64-pixel blocks differ"), std::string::npos)
      << c.health.detail();
}

TEST_P(Verification, EveryChecksEachBuildInFullAndCatchesTheSameChange) {
  CheckedBuilds c(structure(), VerifyMode::Every);
  c.rebuild();
  EXPECT_EQ(c.health.status(), BuildStatus::Ok) << c.health.detail();
  c.change_the_next_build();
  c.rebuild();
  EXPECT_EQ(c.verifier.counts().full, 3u);
  EXPECT_EQ(c.verifier.counts().sampled, 0u);
  EXPECT_EQ(c.health.checksum_changes(), 1u);
  EXPECT_EQ(c.health.status(), BuildStatus::Invalid);
}

// A build on new storage is checked in full, and its block hashes replace the old ones: the
// samples after it compare with it. (Here its lists really differ, so the full check counts
// one change; samples against stale hashes would count one more per build.)
TEST_P(Verification, ANewStorageIsCheckedInFullAndBecomesTheReference) {
  CheckedBuilds c(structure(), VerifyMode::Sampled);
  c.change_the_next_build();
  c.rebuild(/*storage_changed=*/true);
  EXPECT_EQ(c.verifier.counts().full, 2u);
  EXPECT_EQ(c.health.checksum_changes(), 1u);
  c.rebuild();
  c.rebuild();
  EXPECT_EQ(c.verifier.counts().full, 2u);
  EXPECT_EQ(c.verifier.counts().sampled, 2u);
  EXPECT_EQ(c.health.checksum_changes(), 1u) << "a sample compared with the first build's hashes";
}

// The inspector's FNV-1a step on 32-bit words (shaders/ldm/inspect.comp's mix_hash).
uint32_t cpu_mix_hash(uint32_t h, uint32_t v) {
  h ^= v;
  h *= 0x01000193u;
  h ^= h >> 15;
  return h;
}

// The check's totals and checksum, which the shader sums per workgroup in shared memory
// before one atomic each, recomputed on the CPU from the lists the inspector reads back: a
// combination that lost or mixed up a share (an add taken for an xor, one pixel's share
// dropped) would still be self-consistent between builds, and only this catches it.
TEST_P(Verification, TheCheckIsTheListsCountedAndHashedOnTheCpu) {
  CheckedBuilds c(structure(), VerifyMode::Sampled);
  const LdmIntegrity gpu = c.inspector.check();
  uint64_t nodes = 0, unsorted = 0, ties = 0;
  uint32_t low = 0, high = 0;
  for (uint32_t v = 0; v < c.f.views.size(); ++v) {
    const std::vector<std::vector<float>> lists = c.inspector.read_back(v);
    ASSERT_EQ(lists.size(), c.f.views.pixels_per_view());
    for (size_t p = 0; p < lists.size(); ++p) {
      const uint32_t pixel = uint32_t(v * c.f.views.pixels_per_view() + p);
      uint32_t hash = 0x811c9dc5u;
      for (size_t i = 0; i < lists[p].size(); ++i) {
        uint32_t bits;
        std::memcpy(&bits, &lists[p][i], sizeof bits);
        hash = cpu_mix_hash(hash, bits);
        if (i > 0 && lists[p][i] == lists[p][i - 1]) ++ties;
      }
      nodes += lists[p].size();
      if (!std::is_sorted(lists[p].begin(), lists[p].end())) ++unsorted;
      if (lists[p].empty()) continue;
      low += cpu_mix_hash(hash, pixel);
      high ^= cpu_mix_hash(hash * 0x9e3779b9u, pixel + 0x68bc21ebu);
    }
  }
  ASSERT_GT(nodes, 0u);
  EXPECT_EQ(gpu.fragments, nodes);
  EXPECT_EQ(gpu.unsorted_pixels, unsorted);
  EXPECT_EQ(gpu.tied_depths, ties);
  EXPECT_EQ(gpu.checksum, (uint64_t(high) << 32) | low);
}

TEST(VerifyMode, NamesRoundTripAndBadOnesAreRefusedByName) {
  EXPECT_EQ(parse_verify_mode("every"), VerifyMode::Every);
  EXPECT_EQ(parse_verify_mode("sampled"), VerifyMode::Sampled);
  EXPECT_STREQ(verify_mode_name(VerifyMode::Sampled), "sampled");
  try {
    parse_verify_mode("some", "settings.verify");
    FAIL() << "accepted 'some'";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("settings.verify 'some'"), std::string::npos) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Registered, Verification, ::testing::ValuesIn(structure_names()),
                         [](const auto& info) { return info.param; });

}  // namespace
}  // namespace ldm
