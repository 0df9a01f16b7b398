// The sampled verification of builds (ldm_impls/common/build_verifier.h), for every registered
// structure: samples of identical builds find nothing, the rotation visits every pixel once
// per stride, and a build whose lists were deliberately changed is caught by a sample alone
// (no full check), as it is by the full check of --verify every.
#include <gtest/gtest.h>

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

TEST_P(Verification, SamplesOfIdenticalBuildsFindNothingAndCoverEveryPixelOncePerStride) {
  const LdmFixture f("cornell", 8, 32);
  const auto s = f.build(structure());
  const LdmInspector inspector(*s, *f.inputs);
  BuildHealth health(f.census);
  constexpr uint32_t kStride = 4;
  BuildVerifier verifier(*s, inspector, health, VerifyMode::Sampled, kStride);
  verifier.verify(false);  // the first build: in full
  for (uint32_t i = 0; i < kStride; ++i) {
    s->build(*f.inputs, nullptr);
    verifier.verify(false);
  }
  EXPECT_EQ(health.status(), BuildStatus::Ok) << health.detail();
  EXPECT_EQ(health.checksum_changes(), 0u);
  EXPECT_EQ(verifier.counts().full, 1u);
  EXPECT_EQ(verifier.counts().sampled, kStride);
  // Phases 0 .. stride-1 visit every block exactly once.
  EXPECT_EQ(verifier.counts().sampled_pixels, f.views.total_pixels());
  EXPECT_EQ(verifier.last_stats().fragments_stored + verifier.last_stats().fragments_lost,
            f.census.total_fragments);
}

TEST_P(Verification, AChangedBuildIsCaughtByOneSample) {
  const LdmFixture f("cornell", 8, 32);
  const auto s = f.build(structure());
  const LdmInspector inspector(*s, *f.inputs);
  BuildHealth health(f.census);
  BuildVerifier verifier(*s, inspector, health, VerifyMode::Sampled, 4);
  verifier.verify(false);
  ASSERT_EQ(health.status(), BuildStatus::Ok) << health.detail();
  shift_view_eyes(f, 0.01f * f.views.views[0].depth_range);
  s->build(*f.inputs, nullptr);
  verifier.verify(false);
  EXPECT_EQ(verifier.counts().full, 1u) << "the changed build must be judged by its sample";
  EXPECT_EQ(verifier.counts().sampled, 1u);
  EXPECT_EQ(health.checksum_changes(), 1u);
  EXPECT_EQ(health.status(), BuildStatus::Invalid);
  EXPECT_NE(health.detail().find("sampled 64-pixel blocks differ"), std::string::npos)
      << health.detail();
}

TEST_P(Verification, EveryChecksEachBuildInFullAndCatchesTheSameChange) {
  const LdmFixture f("cornell", 8, 32);
  const auto s = f.build(structure());
  const LdmInspector inspector(*s, *f.inputs);
  BuildHealth health(f.census);
  BuildVerifier verifier(*s, inspector, health, VerifyMode::Every);
  verifier.verify(false);
  s->build(*f.inputs, nullptr);
  verifier.verify(false);
  EXPECT_EQ(health.status(), BuildStatus::Ok) << health.detail();
  shift_view_eyes(f, 0.01f * f.views.views[0].depth_range);
  s->build(*f.inputs, nullptr);
  verifier.verify(false);
  EXPECT_EQ(verifier.counts().full, 3u);
  EXPECT_EQ(verifier.counts().sampled, 0u);
  EXPECT_EQ(health.checksum_changes(), 1u);
  EXPECT_EQ(health.status(), BuildStatus::Invalid);
}

TEST_P(Verification, ANewStorageIsCheckedInFullAndBecomesTheReference) {
  const LdmFixture f("cornell", 8, 32);
  const auto s = f.build(structure());
  const LdmInspector inspector(*s, *f.inputs);
  BuildHealth health(f.census);
  BuildVerifier verifier(*s, inspector, health, VerifyMode::Sampled, 4);
  verifier.verify(false);
  s->build(*f.inputs, nullptr);
  verifier.verify(true);  // as after a rebuild or reallocation by the sizing policy
  s->build(*f.inputs, nullptr);
  verifier.verify(false);
  EXPECT_EQ(verifier.counts().full, 2u);
  EXPECT_EQ(verifier.counts().sampled, 1u);
  EXPECT_EQ(health.status(), BuildStatus::Ok) << health.detail();
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
