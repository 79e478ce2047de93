// HID report framing as pure code (no hardware here): report ID, padding, both read forms.
#include <gtest/gtest.h>

#include "protocol/robot_commands/hid_report.hpp"

namespace armctl::rc {
namespace {

TEST(HidReport, WriteIsReportIdThenFrameThenZeroPadding) {
  const auto r = encode_hid_report(Frame{15, {}});
  ASSERT_EQ(r.size(), 65u);
  EXPECT_EQ(r[0], 0x00);
  EXPECT_EQ(r[1], 0x55);
  EXPECT_EQ(r[2], 0x55);
  EXPECT_EQ(r[3], 0x02);
  EXPECT_EQ(r[4], 0x0F);
  for (std::size_t i = 5; i < r.size(); ++i) EXPECT_EQ(r[i], 0) << i;
}

TEST(HidReport, LargestFrameFillsTheReport) {
  Frame f{3, std::vector<std::uint8_t>(kMaxData, 0x11)};
  const auto r = encode_hid_report(f);
  EXPECT_EQ(r[64], 0x11);
  EXPECT_THROW(encode_hid_report(Frame{3, std::vector<std::uint8_t>(kMaxData + 1)}), ArmctlError);
}

TEST(HidReport, ReadWithoutReportIdStripsPadding) {
  std::vector<std::uint8_t> report(64, 0xEE);  // padding need not be zero
  const std::uint8_t frame[] = {0x55, 0x55, 0x04, 0x0F, 0x4C, 0x1D};
  std::copy(std::begin(frame), std::end(frame), report.begin());
  auto f = decode_hid_report(report);
  ASSERT_TRUE(f) << f.error().message;
  EXPECT_EQ(*f, (Frame{15, {0x4C, 0x1D}}));
}

TEST(HidReport, ReadWithLeadingReportIdIsAccepted) {
  std::vector<std::uint8_t> report(65, 0);
  const std::uint8_t frame[] = {0x00, 0x55, 0x55, 0x05, 0x08, 0x02, 0x03, 0x00};
  std::copy(std::begin(frame), std::end(frame), report.begin());
  auto f = decode_hid_report(report);
  ASSERT_TRUE(f) << f.error().message;
  EXPECT_EQ(*f, (Frame{8, {2, 3, 0}}));
}

TEST(HidReport, RoundTripOfEveryLength) {
  for (std::size_t n = 0; n <= kMaxData; ++n) {
    Frame f{21, std::vector<std::uint8_t>(n, static_cast<std::uint8_t>(n))};
    const auto w = encode_hid_report(f);
    auto with_id = decode_hid_report(w);
    ASSERT_TRUE(with_id);
    EXPECT_EQ(*with_id, f);
    auto without_id = decode_hid_report(std::span<const std::uint8_t>(w).subspan(1));
    ASSERT_TRUE(without_id);
    EXPECT_EQ(*without_id, f);
  }
}

TEST(HidReport, BadReportsAreErrorsNamingTheProblem) {
  std::vector<std::uint8_t> zeros(64, 0);
  auto a = decode_hid_report(zeros);
  ASSERT_FALSE(a);
  EXPECT_NE(a.error().message.find("55 55"), std::string::npos);
  std::vector<std::uint8_t> bad_len{0x55, 0x55, 0x01, 0x0F};
  bad_len.resize(64);
  auto b = decode_hid_report(bad_len);
  ASSERT_FALSE(b);
  EXPECT_NE(b.error().message.find("LEN 1"), std::string::npos);
  std::vector<std::uint8_t> truncated{0x55, 0x55, 0x10, 0x03, 0x01};
  auto c = decode_hid_report(truncated);
  ASSERT_FALSE(c);
  EXPECT_NE(c.error().message.find("needs 18 bytes"), std::string::npos);
}

}  // namespace
}  // namespace armctl::rc
