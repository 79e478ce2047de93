// Gamepad recordings (jog/gamepad_replay.hpp): the format read, every kind of bad line
// refused with its place and what is allowed there, and a replay handing over each line
// when its time has come on a simulated clock.
#include "jog/gamepad_replay.hpp"

#include <linux/input-event-codes.h>

#include <gtest/gtest.h>

namespace armctl::jog {
namespace {

using std::chrono::milliseconds;

constexpr const char* kHeader =
    "device Microsoft X-Box 360 pad   # xpad\n"
    "axis ABS_X -32768 32767\n"
    "axis 1 -32768 32767\n";  // ABS_Y by its number

TEST(PadRecordingFormat, ReadsTheDeviceAxesEventsAndPlugLines) {
  const std::string text = std::string(kHeader) +
                           "0 EV_KEY BTN_TL 1\n"
                           "0.25 3 ABS_Y -32768   # EV_ABS by its number\n"
                           "0.25 EV_SYN SYN_REPORT 0\n"
                           "1.5 unplugged\n"
                           "2 plugged\n";
  auto r = parse_pad_recording(text, "pad.txt");
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_EQ(r->pad.name, "Microsoft X-Box 360 pad");
  ASSERT_EQ(r->pad.axes.size(), 2u);
  EXPECT_EQ(r->pad.axes.at(ABS_Y).minimum, -32768);
  ASSERT_EQ(r->lines.size(), 5u);
  EXPECT_EQ(r->lines[0].type, EV_KEY);
  EXPECT_EQ(r->lines[0].code, BTN_TL);
  EXPECT_EQ(r->lines[1].type, EV_ABS);
  EXPECT_EQ(r->lines[1].value, -32768);
  EXPECT_DOUBLE_EQ(r->lines[1].time, 0.25);
  EXPECT_EQ(r->lines[3].kind, PadRecordingLine::Kind::unplugged);
  EXPECT_EQ(r->lines[4].kind, PadRecordingLine::Kind::plugged);
}

TEST(PadRecordingFormat, EveryBadLineIsNamedWithWhatIsAllowed) {
  const std::string h = kHeader;
  const std::vector<std::pair<std::string, std::string>> cases{
      {"", "pad.txt:1:1: found the end of the file; expected a line 'device NAME' naming the pad"},
      {"0 EV_KEY BTN_TL 1\n", "pad.txt:1:1: found '0'; expected 'device NAME' as the first line"},
      {"device\n", "pad.txt:1:7: found the end of the line; expected the pad's name"},
      {"device a\ndevice b\n", "pad.txt:2:1: found a second 'device' line; expected one 'device NAME' line, first"},
      {"device a\naxis ABS_X 0 255\n",
       "pad.txt:3:1: found no line 'axis ABS_Y ...'; expected the left stick's axes ABS_X and ABS_Y with their "
       "ranges: a gamepad has them"},
      {"device a\naxis ABS_X 10 10\n",
       "pad.txt:2:15: found '10'; expected the axis's maximum, a whole number above its minimum"},
      {"device a\naxis BTN_TL 0 1\n",
       "pad.txt:2:6: found 'BTN_TL'; expected an absolute axis: a name such as ABS_X, or 0..63"},
      {"device a\naxis ABS_X 0 1\naxis ABS_X 0 1\n", "pad.txt:3:6: found 'ABS_X' again; expected each axis once"},
      {h + "0 EV_KEY BTN_TL 1\naxis ABS_Z 0 255\n",
       "pad.txt:5:1: found an 'axis' line after events; expected every axis before the first event"},
      {h + "soon EV_KEY BTN_TL 1\n",
       "pad.txt:4:1: found 'soon'; expected 'device', 'axis', or a time in s (0..86400) starting an event line"},
      {h + "-1 EV_KEY BTN_TL 1\n",
       "pad.txt:4:1: found '-1'; expected 'device', 'axis', or a time in s (0..86400) starting an event line"},
      {h + "2 EV_KEY BTN_TL 1\n1 EV_KEY BTN_TL 0\n",
       "pad.txt:5:1: found '1'; expected a time not before the line above's (2 s)"},
      {h + "0 EV_KEY BTN_TL\n",
       "pad.txt:4:1: found 2 values after the time; expected 'TIME TYPE CODE VALUE' or 'TIME unplugged' or 'TIME "
       "plugged'"},
      {h + "0 EV_NOPE 1 1\n",
       "pad.txt:4:3: found 'EV_NOPE'; expected an event type: EV_SYN, EV_KEY, EV_ABS, EV_MSC ... or its number"},
      {h + "0 EV_KEY ABS_X 1\n", "pad.txt:4:10: found 'ABS_X'; expected a code of that type (such as KEY_RESERVED) or 0..767"},
      {h + "0 EV_ABS ABS_Z 1\n", "pad.txt:4:10: found 'ABS_Z'; expected an axis with a line 'axis ABS_Z MIN MAX' above"},
      {h + "0 EV_KEY BTN_TL 3\n", "pad.txt:4:17: found '3'; expected 0 (released), 1 (pressed) or 2 (repeated) for a button"},
      {h + "0 EV_ABS ABS_X 1.5\n", "pad.txt:4:16: found '1.5'; expected a whole number value"},
      {h + "0 plugged\n", "pad.txt:4:3: found 'plugged'; expected 'unplugged' first: the pad is plugged in"},
      {h + "0 unplugged\n1 unplugged\n", "pad.txt:5:3: found 'unplugged'; expected 'plugged' first: the pad is unplugged"},
      {h + "0 unplugged\n1 EV_KEY BTN_TL 1\n", "pad.txt:5:3: found an event while the pad is unplugged; expected 'plugged' first"},
  };
  for (const auto& [text, message] : cases) {
    auto r = parse_pad_recording(text, "pad.txt");
    ASSERT_FALSE(r) << text;
    EXPECT_EQ(r.error().kind, ErrorKind::invalid_config);
    EXPECT_EQ(r.error().message, message) << text;
  }
}

TEST(PadRecordingFormat, AMissingFileIsNamed) {
  auto r = read_pad_recording("/nonexistent/pad.txt");
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("/nonexistent/pad.txt"), std::string::npos);
}

TEST(GamepadReplay, HandsOverEachLineWhenItsTimeHasCome) {
  auto rec = parse_pad_recording(std::string(kHeader) +
                                     "0 EV_KEY BTN_TL 1\n"
                                     "0.5 EV_ABS ABS_Y -32768\n"
                                     "0.5 EV_SYN SYN_REPORT 0\n"
                                     "1 unplugged\n"
                                     "1 plugged\n"
                                     "1 EV_KEY BTN_TL 1\n",
                                 "pad.txt");
  ASSERT_TRUE(rec) << rec.error().message;
  GamepadReplay replay(std::move(*rec), "the recording pad.txt");
  const TimePoint t0 = TimePoint{} + milliseconds(123);  // the session's clock, not zero
  PadPoll p = replay.poll(t0);
  ASSERT_TRUE(p.connected);
  EXPECT_EQ(p.connected->name, "Microsoft X-Box 360 pad");
  ASSERT_EQ(p.events.size(), 1u);
  EXPECT_EQ(p.events[0].code, BTN_TL);
  EXPECT_EQ(p.events[0].time, t0);
  EXPECT_TRUE(replay.poll(t0 + milliseconds(499)).events.empty());
  p = replay.poll(t0 + milliseconds(500));
  ASSERT_EQ(p.events.size(), 2u);
  EXPECT_EQ(p.events[1].type, EV_SYN);
  EXPECT_EQ(p.events[0].time, t0 + milliseconds(500));
  // The loss ends a poll; plugging in again starts the next with the pad, then its events.
  p = replay.poll(t0 + milliseconds(2000));
  EXPECT_TRUE(p.unplugged);
  EXPECT_FALSE(p.connected);
  EXPECT_FALSE(p.ended);
  p = replay.poll(t0 + milliseconds(2000));
  EXPECT_TRUE(p.connected);
  ASSERT_EQ(p.events.size(), 1u);
  EXPECT_TRUE(p.ended);
}

}  // namespace
}  // namespace armctl::jog
