// ContactStop alone, on simulated time: a joint driven into an obstacle is held where it was
// before it touched (an end stop on that side: it stalls, still driven), another joint goes
// on; the hold goes once its way is free; an arm that starts touching is let move.
#include <gtest/gtest.h>

#include <chrono>
#include <memory>

#include "devices/joint_sim/contact_stop.hpp"

namespace armctl::joint_sim {
namespace {

using std::chrono::milliseconds;

struct TwoJoints {
  JointHardware a{JointHardwareParams{}}, b{JointHardwareParams{}};
  TimePoint now{};
  // Both driven at half duty; 1 ms steps, each followed by the check (SimArm's watch).
  void run(ContactStop& stop, milliseconds how_long) {
    for (auto end = now + how_long; now < end;) {
      now += milliseconds(1);
      a.advance_to(now, nullptr);
      b.advance_to(now, nullptr);
      stop.check();
    }
  }
};

TEST(ContactStop, AJointDrivenIntoTheObstacleStallsThereAndTheOtherGoesOn) {
  TwoJoints j;
  bool open = false;
  // The obstacle: joint a beyond 2000 clicks (while the wall stands).
  ContactStop stop([&](std::span<const double> c) { return !open && c[0] > 2000; }, {&j.a, &j.b});
  j.a.set_drive(128, true);
  j.b.set_drive(128, true);
  j.run(stop, milliseconds(2000));
  EXPECT_LE(j.a.position_clicks(), 2000.5);
  EXPECT_GT(j.a.position_clicks(), 1900);
  EXPECT_TRUE(j.a.at_end_stop());
  EXPECT_GT(j.b.position_clicks(), 10000);  // free: far on
  // The wall goes: a goes on.
  open = true;
  j.run(stop, milliseconds(200));
  EXPECT_GT(j.a.position_clicks(), 2500);
}

TEST(ContactStop, AnArmThatStartsTouchingIsLetMove) {
  TwoJoints j;
  ContactStop stop([](std::span<const double> c) { return c[0] > -1000; }, {&j.a, &j.b});  // touching at 0
  j.a.set_drive(128, true);
  j.run(stop, milliseconds(500));
  EXPECT_GT(j.a.position_clicks(), 2000);
  EXPECT_FALSE(j.a.at_end_stop());
}

}  // namespace
}  // namespace armctl::joint_sim
