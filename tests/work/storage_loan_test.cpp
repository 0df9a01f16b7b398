// The counting replay's storage lending (harness/gl/gl_objects.h: GlBufferOwnerScope,
// GlBufferLoanScope): a buffer asked for inside a loan takes a live buffer of the lender with
// the same name, size and flags, at most once, shares its storage and never frees it;
// outside the scopes nothing is lent.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "harness/gl/gl_objects.h"
#include "support/test_support.h"

namespace ldm {
namespace {

TEST(StorageLoan, ABufferOfTheSameNameSizeAndFlagsSharesTheLendersStorage) {
  test::gl_context();
  int owner_tag = 0, other_tag = 0;
  std::vector<GlBuffer> lender;
  {
    const GlBufferOwnerScope owner(&owner_tag);
    lender.emplace_back("nodes", 64);
    lender.emplace_back("heads", 32);
  }
  const GlBuffer untagged("nodes", 64);  // allocated outside an owner scope: never lent
  const GLuint nodes_id = lender[0].id();
  {
    const GlBufferLoanScope loan(&owner_tag);
    GlBuffer borrowed("nodes", 64);
    EXPECT_TRUE(borrowed.borrowed());
    EXPECT_EQ(borrowed.id(), nodes_id);
    GlBuffer second("nodes", 64);  // lent once only: new storage
    EXPECT_FALSE(second.borrowed());
    EXPECT_NE(second.id(), nodes_id);
    EXPECT_NE(second.id(), untagged.id());
    GlBuffer other_size("heads", 48), other_name("tails", 32);
    EXPECT_FALSE(other_size.borrowed());
    EXPECT_FALSE(other_name.borrowed());
    const std::vector<uint32_t> data = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16};
    GlBuffer with_data("heads", 32, data.data());  // initial data: its own storage
    EXPECT_FALSE(with_data.borrowed());
    // What the borrower writes, the lender holds.
    borrowed.upload(data.data(), 64);
    EXPECT_EQ(lender[0].download_all<uint32_t>(), data);
    EXPECT_EQ(loan.buffers_lent(), 1u);
    EXPECT_EQ(loan.bytes_lent(), 64u);
    GlBuffer moved = std::move(borrowed);  // a move keeps the loan
    EXPECT_TRUE(moved.borrowed());
  }
  // The borrower's end did not free the lender's storage; it may be lent again.
  EXPECT_TRUE(glIsBuffer(nodes_id));
  EXPECT_EQ(lender[0].download_all<uint32_t>().size(), 16u);
  {
    const GlBufferLoanScope loan(&other_tag);  // another owner's loan finds nothing
    EXPECT_FALSE(GlBuffer("nodes", 64).borrowed());
  }
  {
    const GlBufferLoanScope loan(&owner_tag);
    EXPECT_TRUE(GlBuffer("nodes", 64).borrowed());
  }
  lender.clear();  // the lender frees it: nothing left to lend
  {
    const GlBufferLoanScope loan(&owner_tag);
    EXPECT_FALSE(GlBuffer("nodes", 64).borrowed());
  }
}

}  // namespace
}  // namespace ldm
