// Keyboard jogging (jog/key_jog.hpp): what a terminal sends decoded into keys, a held key's
// repeats keeping the motion going and its end stopping it, the settings keys; then a typed
// key stream driving the simulated xArm through the servo mode, on simulated time.
#include "jog/key_jog.hpp"

#include <gtest/gtest.h>

#include "arm/arm.hpp"
#include "arm/rc_arm_device.hpp"
#include "arm/run_servo.hpp"
#include "arm/arm_files.hpp"
#include "robot_commands/sim_links.hpp"

namespace armctl::jog {
namespace {

using std::chrono::milliseconds;
using K = Key::Kind;

TEST(DecodeKeys, LettersArrowsPageKeysEscapeAndCtrlC) {
  const auto keys = decode_keys("w\x1b[A\x1b[D\x1b[5~\x1b[6~ \x1b\x03q");
  const std::vector<Key> expected{{K::character, 'w'}, {K::up, 0},        {K::left, 0},
                                  {K::page_up, 0},     {K::page_down, 0}, {K::character, ' '},
                                  {K::escape, 0},      {K::interrupt, 0}, {K::character, 'q'}};
  EXPECT_EQ(keys, expected);
  // An unknown sequence is dropped whole; one cut off at the end is dropped.
  EXPECT_EQ(decode_keys("\x1b[15~a"), (std::vector<Key>{{K::character, 'a'}}));
  EXPECT_TRUE(decode_keys("\x1b[1;").empty());
  EXPECT_TRUE(decode_keys("\x01\x7f").empty());
}

class KeyJogTest : public ::testing::Test {
 protected:
  arm::ArmModel model = arm::testing::shipped("xarm");
  KeyJog keys{model};
  TimePoint t0{};
  static Eigen::Vector3d linear(const arm::ServoCommand& c) { return std::get<arm::ToolTwist>(c.motion).linear; }
};

TEST_F(KeyJogTest, AHeldKeyMovesWhileItRepeatsAndStopsWhenTheRepeatsStop) {
  keys.press({K::character, 'w'}, t0);
  // Before the terminal's repeat starts (a quarter to two thirds of a second), it still moves.
  EXPECT_NEAR(linear(keys.command(t0 + milliseconds(500))).x(), 0.025, 1e-12);
  // Repeats every 33 ms keep it going...
  TimePoint t = t0 + milliseconds(600);
  for (int k = 0; k < 30; ++k, t += milliseconds(33)) {
    keys.press({K::character, 'w'}, t);
    EXPECT_TRUE(keys.moving(t + milliseconds(30)));
  }
  // ...and once they stop, so does the motion within the repeat hold.
  EXPECT_FALSE(keys.moving(t + KeyJog::kRepeatHold));
  EXPECT_EQ(linear(keys.command(t + KeyJog::kRepeatHold)), Eigen::Vector3d::Zero());
}

TEST_F(KeyJogTest, ATapIsAShortNudgeAndSpaceStopsAtOnce) {
  keys.press({K::character, 'r'}, t0);
  EXPECT_TRUE(keys.moving(t0 + milliseconds(100)));
  EXPECT_FALSE(keys.moving(t0 + KeyJog::kFirstHold));
  keys.press({K::down, 0}, t0 + milliseconds(800));  // the down arrow is 's': x-
  EXPECT_NEAR(linear(keys.command(t0 + milliseconds(810))).x(), -0.025, 1e-12);
  keys.press({K::character, ' '}, t0 + milliseconds(820));
  EXPECT_FALSE(keys.moving(t0 + milliseconds(821)));
}

TEST_F(KeyJogTest, SettingsKeysChangeSpeedFrameModeJointAndGripper) {
  EXPECT_EQ(*keys.press({K::character, '+'}, t0), "tool moves in the base frame at 50 mm/s, 40 deg/s");
  keys.press({K::character, '+'}, t0);
  EXPECT_EQ(*keys.press({K::character, '+'}, t0), "tool moves in the base frame at 100 mm/s, 60 deg/s");
  EXPECT_EQ(*keys.press({K::character, 't'}, t0), "tool moves in the tool frame at 100 mm/s, 60 deg/s");
  keys.press({K::character, 'q'}, t0);
  const auto twist = std::get<arm::ToolTwist>(keys.command(t0).motion);
  EXPECT_EQ(twist.frame, arm::ServoFrame::tool);
  EXPECT_NEAR(twist.angular.z(), 60 * std::numbers::pi / 180, 1e-12);

  EXPECT_EQ(*keys.press({K::character, '3'}, t0), "joint 3 (servo4) at 100 % of its velocity limit");
  keys.press({K::character, 's'}, t0);
  const auto v = std::get<arm::JointVelocities>(keys.command(t0).motion).values;
  EXPECT_DOUBLE_EQ(v[2], -model.joints[2].limits.velocity);
  EXPECT_EQ(v[0], 0.0);
  EXPECT_EQ(*keys.press({K::right, 0}, t0), "joint 4 (servo3) at 100 % of its velocity limit");
  EXPECT_EQ(*keys.press({K::character, '9'}, t0), "no joint 9: arm 'xarm' has joints 1..5");

  EXPECT_EQ(*keys.press({K::character, 'c'}, t0), "gripper closing");
  EXPECT_EQ(keys.command(t0).gripper, 1.0);
  EXPECT_FALSE(keys.quit());
  keys.press({K::escape, 0}, t0);
  EXPECT_TRUE(keys.quit());
}

// Keys typed on a simulated clock drive the simulated xArm: y+ held for a second, then x.
TEST(KeyJogOnTheArm, TypedKeysMoveTheToolAndItComesToRestAfterQuit) {
  robot_commands::testing::EmulatedLink link{115200};
  robot_commands::Client client{link};
  arm::Arm arm{arm::testing::shipped("xarm"), std::make_unique<arm::RcArmDevice>(arm::testing::shipped("xarm"), client)};
  // Away from the upright start (a singularity) first.
  ASSERT_TRUE(arm.move_joints({0.0, 0.5, 1.0, 1.0, 0.0, std::nullopt}));
  ASSERT_TRUE(arm.wait());
  const Eigen::Vector3d before = arm.pose().value().position;
  KeyJog keys(arm.model());
  arm::ServoInput input(arm.model());
  std::optional<TimePoint> start;
  TimePoint next_key{};
  arm::ServoOptions o;
  o.before_cycle = [&](TimePoint now) {
    if (!start) start = next_key = now;
    // 'a' (y+) pressed and repeated every 33 ms for a second, then 'x'.
    if (now - *start < milliseconds(1000) && now >= next_key) {
      keys.press({K::character, 'a'}, now);
      next_key += milliseconds(33);
    }
    if (now - *start >= milliseconds(1500)) keys.press({K::character, 'x'}, now);
    if (keys.quit()) input.finish();
    else ASSERT_TRUE(input.send(keys.command(now)));
  };
  auto r = arm::run_servo(arm, input, o);
  ASSERT_TRUE(r) << r.error().message;
  ASSERT_TRUE(arm.wait());
  const Eigen::Vector3d moved = (arm.pose().value().position - before) * 1000;
  // 25 mm/s for a second and the repeat hold after the last repeat.
  EXPECT_NEAR(moved.y(), 25 * 1.12, 3);
  EXPECT_LT(std::abs(moved.x()), 1.0);
  EXPECT_LT(std::abs(moved.z()), 1.0);
}

}  // namespace
}  // namespace armctl::jog
