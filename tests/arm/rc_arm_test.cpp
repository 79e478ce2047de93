// The Arm API over Robot Commands: the emulated xArm in process, on simulated time.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "arm/arm.hpp"
#include "arm/motion_planning.hpp"
#include "arm/rc_arm_device.hpp"
#include "arm_files.hpp"
#include "portable/joint_bus_codes.hpp"
#include "robot_commands/sim_links.hpp"
#include "scene/scene.hpp"

namespace armctl::arm {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

class RcArm : public ::testing::Test {
 protected:
  robot_commands::testing::EmulatedLink link;
  robot_commands::Client client{link};
  Arm arm{testing::shipped("xarm"), std::make_unique<RcArmDevice>(testing::shipped("xarm"), client)};

  std::vector<std::optional<double>> none() const { return std::vector<std::optional<double>>(6); }
  double seconds() const { return std::chrono::duration<double>(link.clock().now().time_since_epoch()).count(); }
};

TEST_F(RcArm, StartsAtCentreWhichIsZero) {
  auto s = arm.read();
  ASSERT_TRUE(s) << s.error().message;
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_NEAR(s->device[i], 500, 0.5);
    EXPECT_NEAR(s->positions[i], 0, 1e-9);
  }
}

TEST_F(RcArm, MoveJointsArrivesInTheTimeAsked) {
  auto t = none();
  t[1] = 30 * kDeg;   // servo5
  t[2] = -45 * kDeg;  // servo4
  MoveOptions o;
  o.duration = std::chrono::milliseconds(1500);
  const double t0 = seconds();
  ASSERT_TRUE(arm.move_joints(t, o));
  auto s = arm.wait();
  ASSERT_TRUE(s) << s.error().message;
  const double took = seconds() - t0;
  EXPECT_GE(took, 1.45);
  EXPECT_LE(took, 1.5 + 2 * 0.2 + 0.05);  // arrival seen within two polls (200 ms on serial)
  EXPECT_NEAR(s->positions[1], 30 * kDeg, 0.5 * kDeg);  // the wait's tolerance
  EXPECT_NEAR(s->positions[2], -45 * kDeg, 0.5 * kDeg);
  EXPECT_NEAR(s->positions[0], 0, 1e-9);  // untouched
}

// servo6 from -1.7 rad to 1.7 rad (194.8 deg; the arm file allows 180 deg/s): --time 0.1
// arrived in 0.54 s on the board while the HTTP API took 1.46 s. Now every app's duration
// goes through joint_move_duration: stretched to the jerk-limited move at the limits (what
// plan_joint_move, the HTTP API's planner, takes), and the note says so.
TEST_F(RcArm, ADurationShorterThanTheLimitsAllowIsStretchedAsInEveryApp) {
  const ArmModel& model = arm.model();
  const double vmax = model.joints[0].limits.velocity;
  auto t = none();
  t[0] = -1.7;  // servo6
  MoveOptions fastest;
  fastest.speed = 1;
  ASSERT_TRUE(arm.move_joints(t, fastest));
  ASSERT_TRUE(arm.wait());
  double to = 1.7;
  for (const double asked : {0.0, 1e-300, 0.1, 0.5}) {
    const std::vector<double> from = arm.read().value().positions;
    std::vector<double> target = from;
    target[0] = to;
    auto timed = joint_move_duration(model, from, target, asked, "--time x");
    ASSERT_TRUE(timed) << timed.error().message;
    EXPECT_TRUE(timed->stretched);
    EXPECT_GE(timed->seconds, std::abs(to - from[0]) / vmax) << "never faster than the arm file";
    EXPECT_EQ(timed->note.rfind("--time x is too short for joint servo6 to move 194.8", 0), 0u) << timed->note;
    // The HTTP API's planner, asked the same, takes as long.
    JointMove move;
    move.target = target;
    move.speed = 1;
    move.min_duration = asked;
    EXPECT_NEAR(plan_joint_move(model, from, move).value().duration, timed->seconds, 1e-9);
    // The board move (the CLI's and Python's), on simulated time.
    MoveOptions o;
    o.duration = std::chrono::duration_cast<Duration>(std::chrono::duration<double>(asked));
    o.duration_words = "--time x";
    std::string note;
    o.on_note = [&](const std::string& n) { note = n; };
    auto goal = none();
    goal[0] = to;
    const double t0 = seconds();
    ASSERT_TRUE(arm.move_joints(goal, o));
    ASSERT_TRUE(arm.wait());
    const double took = seconds() - t0;
    EXPECT_EQ(note, timed->note);
    EXPECT_GE(took, timed->seconds - 0.05) << asked;
    EXPECT_LE(took, timed->seconds + 2 * 0.2 + 0.05) << asked;  // arrival seen within two polls
    to = -to;
  }
  // Long enough: no note, the duration as asked; negative or past 600 s: refused.
  const std::vector<double> here = arm.read().value().positions;
  std::vector<double> there = here;
  there[0] = 0;
  auto slow = joint_move_duration(model, here, there, 5, "--time 5s");
  ASSERT_TRUE(slow);
  EXPECT_FALSE(slow->stretched);
  EXPECT_EQ(slow->seconds, 5);
  EXPECT_EQ(slow->note, "");
  EXPECT_EQ(joint_move_duration(model, here, there, 601, "--time 601s").error().message,
            "--time 601s: 601 s is too long; allowed 0..600 s (0: as fast as the arm file's limits allow)");
}

TEST_F(RcArm, MoveToReachesThePoseWithinServoResolution) {
  motion::JointVector q(5);
  q << 20 * kDeg, 25 * kDeg, 40 * kDeg, 30 * kDeg, 10 * kDeg;
  const motion::Pose want = arm.forward(q);
  const motion::Rpy rpy = motion::to_rpy(want.orientation);
  CartesianGoal g;
  g.position = want.position;
  g.pitch = rpy.pitch;
  g.roll = rpy.roll;
  ASSERT_TRUE(arm.move_to(g)) << arm.move_to(g).error().message;
  ASSERT_TRUE(arm.wait());
  auto p = arm.pose();
  ASSERT_TRUE(p);
  // 0.24 deg per servo unit over a reach of about 0.3 m: a few mm at most.
  EXPECT_LT((p->position - want.position).norm(), 0.003);
}

TEST_F(RcArm, RefusedCommandsSendNothing) {
  const std::size_t before = link.sent.size();
  auto t = none();
  t[0] = 130 * kDeg;
  auto r = arm.move_joints(t);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("outside its limits"), std::string::npos) << r.error().message;
  t[0] = std::nan("");
  EXPECT_FALSE(arm.move_joints(t));
  MoveOptions slow;
  slow.speed = 0;
  t[0] = 10 * kDeg;
  EXPECT_FALSE(arm.move_joints(t, slow));
  EXPECT_FALSE(arm.gripper(1.5));
  CartesianGoal far;
  far.position = {1.0, 0, 0.1};
  auto unreachable = arm.move_to(far);
  ASSERT_FALSE(unreachable);
  EXPECT_NE(unreachable.error().message.find("reach"), std::string::npos) << unreachable.error().message;
  // Reads happen (the IK starts from where the arm stands), moves never.
  for (std::size_t i = before; i < link.sent.size(); ++i) EXPECT_NE(link.sent[i].cmd, 3) << "a move was sent";
}

TEST_F(RcArm, WaitNamesTheJointsThatDidNotArrive) {
  auto t = none();
  t[0] = 100 * kDeg;
  MoveOptions o;
  o.duration = std::chrono::milliseconds(2000);
  ASSERT_TRUE(arm.move_joints(t, o));
  WaitOptions w;
  w.timeout = std::chrono::milliseconds(300);
  auto s = arm.wait(w);
  ASSERT_FALSE(s);
  EXPECT_EQ(s.error().kind, ErrorKind::timeout);
  EXPECT_NE(s.error().message.find("servo6 at"), std::string::npos) << s.error().message;
  EXPECT_NE(s.error().message.find("target 100.000 deg"), std::string::npos) << s.error().message;
}

TEST_F(RcArm, TorqueOffAndGripper) {
  ASSERT_TRUE(arm.set_torque(false));
  // The off frame(s), MultiServoOff, then the read-back that confirms the board handled
  // them, ServoPositionRead (Client::servos_off, docs/usb-hid.md).
  ASSERT_GE(link.sent.size(), 2u);
  EXPECT_EQ(link.sent[link.sent.size() - 2].cmd, 20);
  EXPECT_EQ(link.sent.back().cmd, 21);
  ASSERT_TRUE(arm.gripper(1.0));
  auto s = arm.wait();
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_NEAR(s->positions[5], 48 * kDeg, 0.5 * kDeg);
}

TEST_F(RcArm, StopHoldsWhereTheServosAre) {
  auto t = none();
  t[0] = 90 * kDeg;
  MoveOptions o;
  o.duration = std::chrono::milliseconds(3000);
  ASSERT_TRUE(arm.move_joints(t, o));
  EXPECT_TRUE(arm.device().idle(std::chrono::milliseconds(1000)));
  ASSERT_TRUE(arm.stop());
  const double at_stop = arm.read()->positions[0];
  EXPECT_TRUE(arm.device().idle(std::chrono::milliseconds(2000)));
  EXPECT_NEAR(arm.read()->positions[0], at_stop, 0.5 * kDeg);
  EXPECT_LT(at_stop, 60 * kDeg);
}

// A servo holding an offset reads back its shaft, commanded + offset (robot-commands.json,
// "BusServoInfoRead reply"); the device reads it in the commanded frame, so the arm neither
// misreads the joint nor moves it when asked to hold: a stop once commanded every servo to
// its read-back, turning one with offset 40 by 40 more units (9.6 deg).
TEST_F(RcArm, AServosOffsetIsLeftOutOfItsReadingsSoHoldingDoesNotTurnIt) {
  xarm::XarmServos& servos = link.emulator().servos();
  ASSERT_TRUE(client.adjust_offset(4, 40));  // servo4 is joint 2
  ASSERT_TRUE(arm.device().idle(std::chrono::seconds(1)));
  const double shaft = servos.true_position(4);
  EXPECT_NEAR(shaft, 540, 1) << "the offset turns the shaft";
  auto read = arm.read();
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_NEAR(read->device[2], 500, 0.5);
  EXPECT_NEAR(read->positions[2], 0, 0.3 * kDeg);
  ASSERT_TRUE(arm.stop());
  ASSERT_TRUE(arm.device().idle(std::chrono::seconds(1)));
  EXPECT_NEAR(servos.true_position(4), shaft, 1) << "holding where it reads must not turn it";

  // Moved, it arrives (the closed-loop wait reads it where it was sent) with the shaft the
  // offset further along.
  auto t = none();
  t[2] = 20 * kDeg;
  ASSERT_TRUE(arm.move_joints(t));
  auto s = arm.wait();
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_NEAR(s->positions[2], 20 * kDeg, 0.5 * kDeg);
  const double commanded = s->device[2];
  EXPECT_NEAR(servos.true_position(4), commanded + 40, 1);

  // The offset is read once; a new one (adjusted through this client) is read again.
  auto offset_reads = [&] {
    return std::count_if(link.sent.begin(), link.sent.end(), [](const rc::Frame& f) { return f.cmd == 23; });
  };
  EXPECT_EQ(offset_reads(), 1);
  ASSERT_TRUE(client.adjust_offset(4, -20));
  ASSERT_TRUE(arm.device().idle(std::chrono::seconds(1)));
  auto after = arm.read();
  ASSERT_TRUE(after) << after.error().message;
  EXPECT_EQ(offset_reads(), 2);
  EXPECT_NEAR(after->device[2], commanded, 0.5) << "still where it was commanded";
  EXPECT_NEAR(servos.true_position(4), commanded - 20, 1);
}

// A calibration confirmed (Arm::use_model): the arm drives with the new model at once, the
// scene and reduced mode kept, and a reference to the model given out before still reads the
// old one. A model of other joints or IDs is refused and changes nothing.
TEST_F(RcArm, UseModelDrivesWithTheNewModelKeepingTheSceneAndOldReferences) {
  ASSERT_TRUE(arm.set_scene(scene::parse_scene(R"({"objects": [{"name": "box", "box": [50, 50, 50], "at": [200, 0, 25]}],
                                                  "reduced": {"tool_speed": 20}})",
                                               "scene")
                                .value()));
  ASSERT_TRUE(arm.set_reduced_mode(true));
  const ArmModel& before = arm.model();
  ArmModel shifted = before;
  DeviceMap& servo4 = shifted.joints[2].devices.find(Protocol::robot_commands.name())->second;
  const double per_unit = servo4.device_per_unit();
  servo4.device_a += 10 * kDeg * per_unit;  // the zero 10 deg further along the servo
  servo4.device_b += 10 * kDeg * per_unit;
  ASSERT_TRUE(arm.use_model(shifted));
  EXPECT_NEAR(arm.read()->positions[2], -10 * kDeg, 0.3 * kDeg);
  EXPECT_NEAR(before.from_device(Protocol::robot_commands, arm.read()->device)[2], 0, 0.3 * kDeg);  // still the old
  EXPECT_EQ(arm.scene().objects.size(), 1u);
  ASSERT_TRUE(arm.kinematics()->reduced());
  // Plans are made with the new model too (the kinematics with the scene).
  EXPECT_EQ(arm.kinematics()->model().joints[2].devices.find(Protocol::robot_commands.name())->second.device_a,
            servo4.device_a);
  auto t = none();
  t[2] = 0.0;
  ASSERT_TRUE(arm.move_joints(t));
  auto s = arm.wait();
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_NEAR(s->device[2], 500 + 10 * kDeg * per_unit, 1.0);  // the new zero, on the servo

  ArmModel other = arm.model();
  other.joints[1].devices.find(Protocol::robot_commands.name())->second.id = 9;
  const Status refused = arm.use_model(other);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("ID 9"), std::string::npos) << refused.error().message;
  other = arm.model();
  other.joints.pop_back();
  EXPECT_FALSE(arm.use_model(other));
  EXPECT_NEAR(arm.read()->positions[2], 0, 0.5 * kDeg);  // the model used before the refusals
}

// An xArm ignores JointFaultRead (CMD 40, an armctl extension): health() is the battery
// alone, the first call waits one extension_timeout for nothing, later calls never ask.
TEST_F(RcArm, HealthOnABoardWithoutJointFaultsIsTheBatteryAndAsksOnlyOnce) {
  const double t0 = seconds();
  const DeviceHealth first = arm.device().health();
  ASSERT_TRUE(first.battery_volts.has_value());
  EXPECT_TRUE(first.faults.empty());
  const double took = seconds() - t0;
  EXPECT_NEAR(took, 0.25, 0.01) << "one extension_timeout (250 ms), no error";
  auto asked = [&] {
    return std::count_if(link.sent.begin(), link.sent.end(), [](const rc::Frame& f) { return f.cmd == 40; });
  };
  EXPECT_EQ(asked(), 1);
  const double t1 = seconds();
  const DeviceHealth second = arm.device().health();
  EXPECT_TRUE(second.battery_volts.has_value());
  EXPECT_EQ(asked(), 1) << "known not to answer: not asked again";
  EXPECT_LT(seconds() - t1, 0.01);
}

TEST(RcJointFaults, EachStateIsOneLineAndAHealthyServoNone) {
  rc::JointFaultReport r;
  r.servo = 3;
  r.answering = true;
  r.following = true;
  EXPECT_FALSE(describe_joint_faults(r).has_value());
  r.following = false;
  EXPECT_EQ(describe_joint_faults(r), "servo 3: not following its move");
  r.words_read = true;
  r.words[0] = joint_bus::fault_runaway;
  EXPECT_EQ(describe_joint_faults(r), "servo 3: runaway (bridge off until clear-faults)");
  r = rc::JointFaultReport{};
  r.servo = 5;
  r.last_failure = 990;
  r.following = true;
  EXPECT_EQ(describe_joint_faults(r), "servo 5: not answering (last bus failure 990)");
  r.answering = true;
  r.following = false;
  r.behind_ramp = true;
  EXPECT_EQ(describe_joint_faults(r), "servo 5: fell behind its move's ramp (the move was stopped)");
  r.words_read = true;
  r.words[0] = joint_bus::fault_following_error;
  EXPECT_EQ(describe_joint_faults(r),
            "servo 5: following error (bridge off until clear-faults), fell behind its move's ramp (the move was "
            "stopped)");
}

}  // namespace
}  // namespace armctl::arm
