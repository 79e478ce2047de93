#include "core/error.hpp"

#include <gtest/gtest.h>

namespace armctl {
namespace {

TEST(Result, HoldsValueOrError) {
  Result<int> good = 7;
  EXPECT_TRUE(good.ok());
  EXPECT_EQ(*good, 7);
  Result<int> bad = Error{ErrorKind::timeout, "joint 3 did not answer"};
  EXPECT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().kind, ErrorKind::timeout);
  EXPECT_THROW((void)bad.value(), ArmctlError);
}

}  // namespace
}  // namespace armctl
