// Recording files: round trip, every error with file:line:column, the rate, and the replay's
// smoothing and decimation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "files/recording_file.hpp"

namespace armctl::files {
namespace {

using motion::Recording;
using motion::RecordingJoint;
using motion::RecordingSample;
using motion::keep_samples;
using motion::smooth;

Recording two_joints() {
  Recording r;
  r.arm = "scara";
  r.rate = 20;
  r.joints = {{"shoulder", Dimension::angle}, {"lift", Dimension::length}};
  for (int i = 0; i < 5; ++i) r.samples.push_back({i * 0.05, {0.1 * i + 1e-7 / 3, 0.01 * i / 3}});
  return r;
}

std::string error_of(std::string_view text) {
  auto r = parse_recording(text, "t.rec");
  EXPECT_FALSE(r);
  if (r) return "";
  EXPECT_EQ(r.error().kind, ErrorKind::invalid_config);
  return r.error().message;
}

constexpr std::string_view kHead = "arm scara\nrate 20Hz\njoints shoulder:deg lift:mm\n";

TEST(Recording, RoundTrips) {
  const Recording r = two_joints();
  auto back = parse_recording(format_recording(r), "t.rec");
  ASSERT_TRUE(back) << back.error().message;
  ASSERT_EQ(back->samples.size(), r.samples.size());
  EXPECT_EQ(back->arm, r.arm);
  EXPECT_EQ(back->rate, r.rate);
  EXPECT_EQ(back->joints, r.joints);
  for (std::size_t i = 0; i < r.samples.size(); ++i) {
    EXPECT_EQ(back->samples[i].time, r.samples[i].time);
    for (std::size_t j = 0; j < 2; ++j) EXPECT_NEAR(back->samples[i].positions[j], r.samples[i].positions[j], 1e-15);
  }
}

// A value too small to show on a screen (under 5e-7 deg) is still written as it is: the file
// read back is the recording (fuzz_recording found 1e-7 deg written as 0).
TEST(Recording, TinyValuesReadBackAsWritten) {
  auto r = parse_recording(std::string(kHead) + "0 1e-7 -3e-9\n0.05 -0 0\n", "t.rec");
  ASSERT_TRUE(r) << r.error().message;
  const std::string text = format_recording(*r);
  EXPECT_EQ(text.find("-0 "), std::string::npos) << text;
  auto back = parse_recording(text, "t.rec");
  ASSERT_TRUE(back) << back.error().message;
  for (std::size_t i = 0; i < 2; ++i)
    for (std::size_t j = 0; j < 2; ++j)
      EXPECT_NEAR(back->samples[i].positions[j], r->samples[i].positions[j], 1e-12 * 1e-7) << text;
  EXPECT_NE(back->samples[0].positions[0], 0.0);
}

TEST(Recording, ReadsUnitsCommentsAndBlankLines) {
  auto r = parse_recording("# taught\narm scara  # the arm\n\nrate 50\njoints a:rad b:m\n0 1.5 0.25\n0.02 -1 0.5\n", "t.rec");
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_EQ(r->rate, 50);
  EXPECT_EQ(r->samples[1].positions, (std::vector<double>{-1, 0.5}));
  auto deg = parse_recording(std::string(kHead) + "0 90 100\n", "t.rec");
  ASSERT_TRUE(deg);
  EXPECT_NEAR(deg->samples[0].positions[0], M_PI / 2, 1e-15);
  EXPECT_NEAR(deg->samples[0].positions[1], 0.1, 1e-15);
}

TEST(Recording, EveryErrorNamesLineAndColumn) {
  EXPECT_EQ(error_of(""), "t.rec:1:1: found the end of the file; expected 'arm ...' (a header line)");
  EXPECT_EQ(error_of("rate 20Hz\n"), "t.rec:1:1: found 'rate'; expected the header line 'arm ...'");
  EXPECT_EQ(error_of("arm\n"), "t.rec:1:4: found the end of the line; expected a value after 'arm'");
  EXPECT_EQ(error_of("arm a b\n"), "t.rec:1:7: found 'b'; expected the end of the line");
  EXPECT_EQ(error_of("arm 9x\n"), "t.rec:1:5: found '9x'; expected an arm name (letters, digits, '_', '-')");
  EXPECT_EQ(error_of("arm x\nrate 0Hz\n"), "t.rec:2:6: found '0Hz'; expected a rate of 1..1000 Hz such as '20Hz'");
  EXPECT_EQ(error_of("arm x\nrate 20Hz\njoints a\n"),
            "t.rec:3:9: found no unit; expected ':deg', ':rad' (angles), ':mm' or ':m' (lengths) after the joint name");
  EXPECT_EQ(error_of("arm x\nrate 20Hz\njoints a:inch\n"),
            "t.rec:3:10: found unit 'inch'; expected ':deg', ':rad' (angles), ':mm' or ':m' (lengths) after the joint name");
  EXPECT_EQ(error_of("arm x\nrate 20Hz\njoints a:deg a:deg\n"), "t.rec:3:14: found 'a:deg'; expected each joint named once");
  EXPECT_EQ(error_of("arm x\nrate 20Hz\njoints 1:deg\n"),
            "t.rec:3:8: found '1:deg'; expected a joint name then ':' and its unit (base:deg)");
  EXPECT_EQ(error_of(std::string(kHead)), "t.rec:4:1: found no samples; expected at least one sample line after the header");
  EXPECT_EQ(error_of(std::string(kHead) + "-1 0 0\n"), "t.rec:4:1: found '-1'; expected a time in s, 0..1e+06");
  EXPECT_EQ(error_of(std::string(kHead) + "0.1 0 0\n0.1 0 0\n"),
            "t.rec:5:1: found '0.1'; expected a time after the previous sample's 0.1");
  EXPECT_EQ(error_of(std::string(kHead) + "0 0\n"),
            "t.rec:4:4: found the end of the line; expected 2 joint values after the time (one per joint), found 1");
  EXPECT_EQ(error_of(std::string(kHead) + "0 0 0 0\n"), "t.rec:4:7: found '0'; expected the end of the line");
  EXPECT_EQ(error_of(std::string(kHead) + "0 0 nan\n"), "t.rec:4:5: found 'nan'; expected a number (joint lift in mm)");
  EXPECT_EQ(error_of(std::string(kHead) + "0 1e300 0\n"), "t.rec:4:3: found '1e300'; expected a number (joint shoulder in deg)");
  EXPECT_EQ(error_of(std::string(kHead) + "0 \x01 0\n"), "t.rec:4:3: found '\\x01'; expected a number (joint shoulder in deg)");
}

TEST(Recording, Rate) {
  EXPECT_EQ(*parse_rate("20Hz"), 20);
  EXPECT_EQ(*parse_rate("20 Hz"), 20);
  EXPECT_EQ(*parse_rate("12.5"), 12.5);
  EXPECT_EQ(parse_rate("0.5Hz").error().message, "rate '0.5Hz': allowed is 1..1000 Hz, such as '20Hz'");
  EXPECT_FALSE(parse_rate("2kHz"));
  EXPECT_FALSE(parse_rate(""));
}

TEST(Recording, WritesAtomically) {
  const std::string path = ::testing::TempDir() + "/teach_test.rec";
  ASSERT_TRUE(write_recording(path, two_joints()));
  auto back = read_recording(path);
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_EQ(back->samples.size(), 5u);
  EXPECT_EQ(write_recording("/nonexistent-dir/x.rec", two_joints()).error().kind, ErrorKind::io);
}

TEST(Recording, SmoothKeepsEndsAndTakesOutNoise) {
  std::vector<RecordingSample> s;
  for (int i = 0; i < 101; ++i) s.push_back({i * 0.01, {i * 0.01 + (i % 2 ? 0.002 : -0.002)}});
  const auto m = smooth(s, 2);
  EXPECT_EQ(m.front(), s.front());
  EXPECT_EQ(m.back(), s.back());
  double worst = 0;
  for (int i = 2; i < 99; ++i) worst = std::max(worst, std::abs(m[std::size_t(i)].positions[0] - i * 0.01));
  EXPECT_LT(worst, 0.0005);  // the +-2 mrad zigzag down to a fifth
}

TEST(Recording, KeepSamplesWithinTolerance) {
  // A straight line then a corner: the line needs only its ends, the corner its apex.
  std::vector<RecordingSample> s;
  for (int i = 0; i <= 100; ++i) s.push_back({i * 0.01, {i <= 50 ? i * 0.01 : 1.0 - i * 0.01, 0.0}});
  const auto kept = keep_samples(s, {0.001, 0.001});
  EXPECT_EQ(kept, (std::vector<std::size_t>{0, 50, 100}));
  // A sine: every dropped sample within the tolerance of the line through the kept ones.
  std::vector<RecordingSample> w;
  for (int i = 0; i <= 400; ++i) w.push_back({i * 0.01, {std::sin(i * 0.02), std::cos(i * 0.03)}});
  const auto k = keep_samples(w, {0.01, 0.01});
  EXPECT_LT(k.size(), 60u);
  for (std::size_t n = 0; n + 1 < k.size(); ++n)
    for (std::size_t i = k[n]; i <= k[n + 1]; ++i)
      for (std::size_t j = 0; j < 2; ++j) {
        const double f = (w[i].time - w[k[n]].time) / (w[k[n + 1]].time - w[k[n]].time);
        const double line = w[k[n]].positions[j] + f * (w[k[n + 1]].positions[j] - w[k[n]].positions[j]);
        EXPECT_LE(std::abs(w[i].positions[j] - line), 0.01 + 1e-12);
      }
}

// A recording saved with a UTF-8 byte-order mark reads as without it; errors keep their columns.
TEST(Recording, AByteOrderMarkIsNotPartOfTheFile) {
  const std::string path = ::testing::TempDir() + "/teach_test_bom.rec";
  std::ofstream(path, std::ios::binary) << "\xEF\xBB\xBF" << kHead << "0 1 2\n";
  auto r = read_recording(path);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_EQ(r->arm, "scara");
  EXPECT_EQ(r->samples.size(), 1u);
  std::ofstream(path, std::ios::binary) << "\xEF\xBB\xBF" << "arm a b\n";
  EXPECT_EQ(read_recording(path).error().message, path + ":1:7: found 'b'; expected the end of the line");
  std::remove(path.c_str());
}

}  // namespace
}  // namespace armctl::files
