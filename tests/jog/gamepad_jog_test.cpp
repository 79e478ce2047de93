// Gamepad jogging's mapping (jog/gamepad_jog.hpp) on a simulated clock: the dead zone and
// its rescaling, the dead-man, both layouts (told apart by name and by range), the axes'
// directions, the buttons, lost events and a lost pad.
#include "jog/gamepad_jog.hpp"

#include <linux/input-event-codes.h>

#include <gtest/gtest.h>

#include <numbers>

#include "arm/arm_files.hpp"

namespace armctl::jog {
namespace {

using std::chrono::milliseconds;

constexpr double kDeg = std::numbers::pi / 180;

PadDescription xbox() {
  PadDescription p{"Microsoft X-Box 360 pad", {}};
  for (std::uint16_t c : {ABS_X, ABS_Y, ABS_RX, ABS_RY}) p.axes[c] = PadAxis{-32768, 32767, 0};
  for (std::uint16_t c : {ABS_Z, ABS_RZ}) p.axes[c] = PadAxis{0, 255, 0};
  for (std::uint16_t c : {ABS_HAT0X, ABS_HAT0Y}) p.axes[c] = PadAxis{-1, 1, 0};
  return p;
}

PadDescription playstation(std::string name = "Sony Interactive Entertainment Wireless Controller") {
  PadDescription p{std::move(name), {}};
  for (std::uint16_t c : {ABS_X, ABS_Y, ABS_RX, ABS_RY}) p.axes[c] = PadAxis{0, 255, 128};
  for (std::uint16_t c : {ABS_Z, ABS_RZ}) p.axes[c] = PadAxis{0, 255, 0};
  for (std::uint16_t c : {ABS_HAT0X, ABS_HAT0Y}) p.axes[c] = PadAxis{-1, 1, 0};
  return p;
}

TEST(DeadZone, NothingInsideThenLinearFromItsEdge) {
  EXPECT_EQ(past_dead_zone(0.0), 0.0);
  EXPECT_EQ(past_dead_zone(0.05), 0.0);
  EXPECT_EQ(past_dead_zone(-kDeadZone), 0.0);
  // Just past the edge the motion is just above zero: no jump.
  EXPECT_NEAR(past_dead_zone(kDeadZone + 1e-3), 1e-3 / (1 - kDeadZone), 1e-12);
  EXPECT_NEAR(past_dead_zone(0.55), 0.5, 1e-12);
  EXPECT_NEAR(past_dead_zone(-0.55), -0.5, 1e-12);
  EXPECT_EQ(past_dead_zone(1.0), 1.0);
  EXPECT_EQ(past_dead_zone(1.3), 1.0);  // a stick reporting beyond its stated range
}

TEST(PadLayouts, ToldApartByNameAndByTheSticksRange) {
  EXPECT_EQ(layout_of(xbox()), PadLayout::xbox);
  EXPECT_EQ(layout_of(playstation()), PadLayout::playstation);
  EXPECT_EQ(layout_of(playstation("DualSense Wireless Controller")), PadLayout::playstation);
  // No telling name: a stick range that does not straddle 0 is hid-sony's or hid-playstation's.
  EXPECT_EQ(layout_of(playstation("Generic USB Gamepad")), PadLayout::playstation);
  auto x = xbox();
  x.name = "Generic X-Box pad";
  EXPECT_EQ(layout_of(x), PadLayout::xbox);
}

class GamepadJogTest : public ::testing::Test {
 protected:
  arm::ArmModel model = arm::testing::shipped("xarm");
  GamepadJog pad{model};
  TimePoint t0{};

  void connect(const PadDescription& d) { ASSERT_TRUE(pad.connect(d)); }
  std::optional<std::string> send(std::uint16_t type, std::uint16_t code, std::int32_t value,
                                  Duration at = Duration::zero()) {
    return pad.event(PadEvent{type, code, value, t0 + at});
  }
  std::optional<std::string> frame(std::uint16_t code, std::int32_t value, Duration at = Duration::zero()) {
    send(EV_ABS, code, value, at);
    return send(EV_SYN, SYN_REPORT, 0, at);
  }
  std::optional<std::string> press(std::uint16_t code, bool down = true, Duration at = Duration::zero()) {
    return send(EV_KEY, code, down ? 1 : 0, at);
  }
  arm::ToolTwist twist() const { return std::get<arm::ToolTwist>(pad.command().motion); }
};

TEST_F(GamepadJogTest, NothingMovesUntilTheDeadManIsHeldAndItsReleaseStops) {
  connect(xbox());
  frame(ABS_Y, -32768);  // left stick fully forward
  EXPECT_FALSE(pad.moving());
  EXPECT_EQ(twist().linear, Eigen::Vector3d::Zero());
  press(BTN_TL);
  EXPECT_TRUE(pad.moving());
  EXPECT_NEAR(twist().linear.x(), 0.025, 1e-12);  // the starting speed step: 25 mm/s
  EXPECT_NEAR(twist().linear.y(), 0, 1e-12);
  press(BTN_TL, false);
  EXPECT_FALSE(pad.moving());
  EXPECT_EQ(twist().linear, Eigen::Vector3d::Zero());
}

TEST_F(GamepadJogTest, AStickInsideTheDeadZoneIsStillAndPastItGrowsFromZero) {
  connect(xbox());
  press(BTN_TL);
  frame(ABS_X, 3000);  // 9 % of the half range
  EXPECT_FALSE(pad.moving());
  EXPECT_EQ(twist().linear, Eigen::Vector3d::Zero());
  // Right by 55 % of the half range (from the centre -0.5): y- at half the step's speed.
  frame(ABS_X, -1 + int(0.55 * 32767.5));
  EXPECT_NEAR(twist().linear.y(), -0.0125, 2e-5);
  // The axes of one frame change together: nothing until its SYN_REPORT.
  send(EV_ABS, ABS_X, 0);
  send(EV_ABS, ABS_Y, 32767);
  EXPECT_NEAR(twist().linear.y(), -0.0125, 2e-5);
  send(EV_SYN, SYN_REPORT, 0);
  EXPECT_NEAR(twist().linear.y(), 0, 1e-12);
  EXPECT_NEAR(twist().linear.x(), -0.025, 1e-12);  // stick pulled back: x-
}

TEST_F(GamepadJogTest, XboxAxesTriggersRightStickAndDpad) {
  auto one = xbox();
  one.axes[ABS_Z] = one.axes[ABS_RZ] = PadAxis{0, 1023, 0};  // the Xbox One's triggers
  connect(one);
  press(BTN_TL);
  frame(ABS_X, -32768);  // left: y+
  EXPECT_NEAR(twist().linear.y(), 0.025, 1e-12);
  frame(ABS_X, 0);
  frame(ABS_RZ, 1023);  // right trigger: up
  EXPECT_NEAR(twist().linear.z(), 0.025, 1e-12);
  frame(ABS_Z, 1023);  // both: they cancel
  EXPECT_NEAR(twist().linear.z(), 0, 1e-12);
  frame(ABS_RZ, 0);
  EXPECT_NEAR(twist().linear.z(), -0.025, 1e-12);
  frame(ABS_Z, 0);
  frame(ABS_RX, -32768);  // right stick left: yaw +
  EXPECT_NEAR(twist().angular.z(), 20 * kDeg, 1e-12);
  frame(ABS_RX, 0);
  frame(ABS_RY, -32768);  // right stick forward: pitch +
  EXPECT_NEAR(twist().angular.y(), 20 * kDeg, 1e-12);
  frame(ABS_RY, 0);
  frame(ABS_HAT0X, 1);  // d-pad right: roll -
  EXPECT_NEAR(twist().angular.x(), -20 * kDeg, 1e-12);
  EXPECT_EQ(twist().frame, arm::ServoFrame::base);
}

TEST_F(GamepadJogTest, PlayStationSticksAreCentredAt128) {
  connect(playstation());
  press(BTN_TL);
  EXPECT_FALSE(pad.moving());  // 128 of 0..255: centred
  frame(ABS_X, 0);             // left: y+
  frame(ABS_Y, 255);           // back: x-
  EXPECT_NEAR(twist().linear.y(), 0.025, 1e-12);
  EXPECT_NEAR(twist().linear.x(), -0.025, 1e-12);
  frame(ABS_Y, 140);  // 9 % off centre: inside the dead zone
  EXPECT_NEAR(twist().linear.x(), 0, 1e-12);
  frame(ABS_Z, 255);  // L2: down
  EXPECT_NEAR(twist().linear.z(), -0.025, 1e-12);
}

TEST_F(GamepadJogTest, TheTopButtonTogglesTheFrameOnEitherLayout) {
  connect(xbox());
  // xpad's Y (top) is BTN_Y, the code of BTN_WEST; its X (left) is BTN_X, that of BTN_NORTH.
  EXPECT_EQ(press(BTN_X), std::nullopt);
  EXPECT_EQ(*press(BTN_Y), "tool moves in the tool frame at up to 25 mm/s, 20 deg/s");
  EXPECT_EQ(pad.frame(), arm::ServoFrame::tool);

  GamepadJog ps(model);
  ASSERT_TRUE(ps.connect(playstation()));
  EXPECT_EQ(ps.event(PadEvent{EV_KEY, BTN_WEST, 1, t0}), std::nullopt);  // Square
  EXPECT_TRUE(ps.event(PadEvent{EV_KEY, BTN_NORTH, 1, t0}));             // Triangle
  EXPECT_EQ(ps.frame(), arm::ServoFrame::tool);
}

TEST_F(GamepadJogTest, DpadStepsTheSpeedGripperButtonsHelpAndStartHeldQuits) {
  connect(xbox());
  press(BTN_TL);
  EXPECT_EQ(*frame(ABS_HAT0Y, -1), "tool moves in the base frame at up to 50 mm/s, 40 deg/s");
  EXPECT_EQ(frame(ABS_HAT0Y, -1), std::nullopt);  // still held: one step per press
  frame(ABS_HAT0Y, 0);
  frame(ABS_HAT0Y, -1);
  frame(ABS_HAT0Y, 0);
  EXPECT_EQ(*frame(ABS_HAT0Y, -1), "tool moves in the base frame at up to 100 mm/s, 60 deg/s");  // the top
  frame(ABS_HAT0Y, 0);
  frame(ABS_HAT0Y, 1);
  EXPECT_EQ(pad.speed_step(), 3);
  frame(ABS_Y, -32768);
  EXPECT_NEAR(twist().linear.x(), 0.05, 1e-12);

  EXPECT_EQ(*press(BTN_SOUTH), "gripper closing");
  EXPECT_EQ(pad.command().gripper, 1.0);
  EXPECT_EQ(*press(BTN_EAST), "gripper opening");
  EXPECT_EQ(pad.command().gripper, 0.0);
  EXPECT_NE(press(BTN_SELECT)->find("hold LB to move"), std::string::npos);

  // START brushed: no quit; held a second: quit.
  press(BTN_START, true, milliseconds(0));
  press(BTN_START, false, milliseconds(300));
  EXPECT_FALSE(pad.quit(t0 + milliseconds(2000)));
  press(BTN_START, true, milliseconds(2000));
  EXPECT_FALSE(pad.quit(t0 + milliseconds(2999)));
  EXPECT_TRUE(pad.quit(t0 + milliseconds(3000)));
}

TEST_F(GamepadJogTest, LostEventsStopUntilAFreshDeadManPress) {
  connect(xbox());
  press(BTN_TL);
  frame(ABS_Y, -32768);
  ASSERT_TRUE(pad.moving());
  EXPECT_TRUE(send(EV_SYN, SYN_DROPPED, 0));
  EXPECT_FALSE(pad.moving());
  // What libevdev hands over after the loss: the state now. The axes are taken, a button
  // press in it is not (it may be stale).
  send(EV_ABS, ABS_Y, 32767);
  press(BTN_TL);
  send(EV_SYN, SYN_REPORT, 0);
  EXPECT_FALSE(pad.moving());
  press(BTN_TL);
  EXPECT_NEAR(twist().linear.x(), -0.025, 1e-12);
}

TEST_F(GamepadJogTest, AnUnpluggedPadStopsAtOnceAndAReturningOneNeedsAFreshPress) {
  connect(xbox());
  press(BTN_TL);
  frame(ABS_Y, -32768);
  ASSERT_TRUE(pad.moving());
  EXPECT_EQ(pad.unplug(), "gamepad lost: stopping; waiting for a gamepad");
  EXPECT_FALSE(pad.connected());
  EXPECT_EQ(twist().linear, Eigen::Vector3d::Zero());
  press(BTN_TL);  // nothing: no pad
  EXPECT_FALSE(pad.moving());
  // Plugged in again with the stick pushed (its value at open): still until LB is pressed.
  auto again = xbox();
  again.axes[ABS_Y].value = -32768;
  EXPECT_EQ(*pad.connect(again), "gamepad 'Microsoft X-Box 360 pad' (Xbox layout): hold LB to move");
  EXPECT_FALSE(pad.moving());
  press(BTN_TL);
  EXPECT_NEAR(twist().linear.x(), 0.025, 1e-12);
}

TEST_F(GamepadJogTest, AnAxisWithoutARangeIsRefused) {
  auto bad = xbox();
  bad.axes[ABS_RX] = PadAxis{5, 5, std::nullopt};
  auto r = pad.connect(bad);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().kind, ErrorKind::invalid_argument);
  EXPECT_EQ(r.error().message,
            "gamepad 'Microsoft X-Box 360 pad': axis ABS_RX has range 5..5; the minimum must be below the maximum");
  EXPECT_FALSE(pad.connected());
}

TEST_F(GamepadJogTest, AnArmWithoutAGripperSaysSo) {
  arm::ArmModel no_gripper = model;
  no_gripper.gripper.reset();
  GamepadJog p(no_gripper);
  ASSERT_TRUE(p.connect(xbox()));
  EXPECT_EQ(*p.event(PadEvent{EV_KEY, BTN_SOUTH, 1, t0}), "arm 'xarm' has no gripper");
  EXPECT_EQ(p.command().gripper, std::nullopt);
}

}  // namespace
}  // namespace armctl::jog
