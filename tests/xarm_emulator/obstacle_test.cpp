// The emulated servos against an obstacle (XarmServosOptions::touches; the scene of
// `armctl sim xarm --scene`): a servo whose next step would touch stays where it is, stalled,
// while the others go on; it goes on again, never faster than a servo can, once its way is
// free; an arm already touching is let move.
#include <gtest/gtest.h>

#include <chrono>

#include "devices/xarm_emulator/xarm_servos.hpp"

namespace armctl::xarm {
namespace {

using std::chrono::milliseconds;

// A wall at servo 4's 600 units while servo 3 is below 700 (shafts: servos 1..6 at 0..5).
struct Wall {
  bool open = false;
  bool operator()(std::span<const double> shafts) const { return !open && shafts[3] > 600 && shafts[2] < 700; }
};

TEST(XarmObstacle, AServoStallsAtTheWallWhileTheOthersMoveOn) {
  auto wall = std::make_shared<Wall>();
  XarmServosOptions o;
  o.touches = [wall](std::span<const double> s) { return (*wall)(s); };
  XarmServos servos(o, TimePoint{});
  const std::array<ServoTarget, 2> targets{ServoTarget{4, 800}, ServoTarget{5, 300}};
  ASSERT_TRUE(servos.move(targets, milliseconds(1000), TimePoint{}));
  servos.advance_to(TimePoint{} + milliseconds(2000));
  // Servo 4 stopped within one step (1 ms at its move's speed) of the wall; servo 5 arrived.
  EXPECT_LE(servos.position(4), 600);
  EXPECT_GE(servos.position(4), 599);
  EXPECT_EQ(servos.position(5), 300);
  // The wall goes: servo 4 goes on to its target at no more than its top speed.
  wall->open = true;
  servos.advance_to(TimePoint{} + milliseconds(2050));
  EXPECT_LE(servos.position(4), 600 + XarmServos::kMaxSpeed * 0.05 + 1);
  servos.advance_to(TimePoint{} + milliseconds(3000));
  EXPECT_EQ(servos.position(4), 800);
}

TEST(XarmObstacle, AnArmAlreadyTouchingIsLetMove) {
  XarmServosOptions o;
  o.touches = [](std::span<const double> shafts) { return shafts[3] > 400; };  // servo 4 starts at 500: inside
  XarmServos servos(o, TimePoint{});
  const std::array<ServoTarget, 1> deeper{ServoTarget{4, 700}};
  ASSERT_TRUE(servos.move(deeper, milliseconds(500), TimePoint{}));
  servos.advance_to(TimePoint{} + milliseconds(1000));
  EXPECT_EQ(servos.position(4), 700);
}

}  // namespace
}  // namespace armctl::xarm
