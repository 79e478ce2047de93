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

struct SampleDetail {
  int code = 0;
};

TEST(Error, CarriesATypedDetailThroughCopiesAndPrefixes) {
  const Error plain{ErrorKind::io, "write to /dev/ttyUSB0 failed"};
  EXPECT_EQ(plain.detail_as<SampleDetail>(), nullptr);
  const Error e{ErrorKind::device, "refused", SampleDetail{940}};
  const Error copy = e.prefixed("joint 3: ");
  ASSERT_NE(copy.detail_as<SampleDetail>(), nullptr);
  EXPECT_EQ(copy.detail_as<SampleDetail>()->code, 940);
  EXPECT_EQ(copy.detail_as<int>(), nullptr) << "a detail is found only as its own type";
  EXPECT_EQ(copy.message, "joint 3: refused");
  EXPECT_EQ(copy.kind, ErrorKind::device);
}

TEST(Error, CatchErrorTurnsAThrowIntoTheReturnedError) {
  const Result<int> thrown = catch_error([]() -> Result<int> {
    throw ArmctlError(ErrorKind::timeout, "no reply");
  });
  ASSERT_FALSE(thrown.ok());
  EXPECT_EQ(thrown.error().kind, ErrorKind::timeout);
  EXPECT_EQ(thrown.error().message, "no reply");
  EXPECT_EQ(*catch_error([]() -> Result<int> { return 5; }), 5);
}

}  // namespace
}  // namespace armctl
