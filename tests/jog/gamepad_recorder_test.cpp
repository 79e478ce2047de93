// Recording a gamepad (jog/gamepad_recorder.hpp): a recorded pad recorded again comes out as
// it went in, the file reads back, and a session without a pad records nothing.
#include "jog/gamepad_recorder.hpp"

#include <unistd.h>

#include <gtest/gtest.h>

#include <filesystem>

namespace armctl::jog {
namespace {

using std::chrono::milliseconds;

TEST(GamepadRecorder, WhatAPadDidReadsBackAsIt) {
  auto original = read_pad_recording(ARMCTL_SOURCE_DIR "/tests/jog/recordings/xbox_forward.txt");
  ASSERT_TRUE(original) << original.error().message;
  GamepadRecorder recorder(std::make_unique<GamepadReplay>(*original, "test"));
  TimePoint now = TimePoint{} + milliseconds(777);  // the session's clock, not zero
  for (int k = 0; k < 1000 && !recorder.poll(now).ended; ++k) now += milliseconds(10);

  const auto path = std::filesystem::temp_directory_path() / ("armctl-pad-" + std::to_string(::getpid()) + ".txt");
  ASSERT_TRUE(recorder.save(path));
  auto again = read_pad_recording(path);
  std::filesystem::remove(path);
  ASSERT_TRUE(again) << again.error().message;
  EXPECT_EQ(again->pad.name, original->pad.name);
  EXPECT_EQ(again->pad.axes.size(), original->pad.axes.size());
  ASSERT_EQ(again->lines.size(), original->lines.size());
  for (std::size_t i = 0; i < original->lines.size(); ++i) {
    const auto &a = original->lines[i], &b = again->lines[i];
    EXPECT_EQ(a.kind, b.kind);
    EXPECT_EQ(a.type, b.type);
    EXPECT_EQ(a.code, b.code);
    EXPECT_EQ(a.value, b.value);
    // Events keep their times; a loss or a return is seen at the poll after it (10 ms apart).
    EXPECT_NEAR(a.time, b.time, a.kind == PadRecordingLine::Kind::event ? 1e-6 : 0.01);
  }
}

TEST(GamepadRecorder, ANameWithACommentSignStillReadsBack) {
  PadRecording r;
  r.pad.name = "pad #2";
  r.pad.axes[0] = PadAxis{0, 255, std::nullopt};
  r.pad.axes[1] = PadAxis{0, 255, std::nullopt};
  auto again = parse_pad_recording(format_pad_recording(r), "formatted");
  ASSERT_TRUE(again) << again.error().message;
  EXPECT_EQ(again->pad.name, "pad _2");
}

// A source whose pad never comes (a device not plugged in).
struct NoPad final : GamepadSource {
  PadPoll poll(TimePoint) override { return {}; }
  std::string description() const override { return "no pad"; }
};

TEST(GamepadRecorder, NoPadNothingRecorded) {
  GamepadRecorder recorder(std::make_unique<NoPad>());
  recorder.poll(TimePoint{});
  EXPECT_FALSE(recorder.recording());
  auto s = recorder.save("/tmp/never-written.txt");
  ASSERT_FALSE(s);
  EXPECT_EQ(s.error().message, "no gamepad was opened: nothing to record in /tmp/never-written.txt");
  EXPECT_FALSE(std::filesystem::exists("/tmp/never-written.txt"));
}

}  // namespace
}  // namespace armctl::jog
