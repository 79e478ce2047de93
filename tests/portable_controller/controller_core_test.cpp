// The arm-controller core against scripted joints (fake_joints.hpp): what each Robot
// Commands request puts on the joint bus, and what goes back upstream.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <vector>

#include "devices/arm_controller/controller_config.hpp"
#include "fake_joints.hpp"
#include "portable_controller/controller_core.hpp"
#include "portable_controller/rc_codes.hpp"
#include "portable_controller/scara_arm.hpp"

namespace armctl::controller::testing {
namespace {

namespace jb = joint_bus;

using Reply = SentFrame;

struct CoreRig {
  CoreRig() {
    core.begin(scara_joints, scara_joint_count, &joints, &upstream, 9600, now);
    core.set_battery_millivolts(23456);
    run_us(200000);  // start-up commands and a first sweep of polls
    joints.log.clear();
  }
  void run_us(std::uint32_t us) { run_core(core, joints, now, us, 100); }
  void request(std::uint8_t command, std::vector<std::uint8_t> data) {
    core.on_frame(command, data.data(), static_cast<std::uint8_t>(data.size()), now);
  }
  // MultiServoMove data: count, time, {servo, position}.
  static std::vector<std::uint8_t> move(std::uint16_t ms, std::vector<std::pair<int, int>> targets) {
    std::vector<std::uint8_t> d{static_cast<std::uint8_t>(targets.size()), static_cast<std::uint8_t>(ms & 0xFF),
                                static_cast<std::uint8_t>(ms >> 8)};
    for (auto [s, p] : targets) {
      d.push_back(static_cast<std::uint8_t>(s));
      d.push_back(static_cast<std::uint8_t>(p & 0xFF));
      d.push_back(static_cast<std::uint8_t>(p >> 8));
    }
    return d;
  }
  std::vector<SentCommand> motion_commands() const {
    std::vector<SentCommand> out;
    for (const auto& c : joints.log)
      if (c.command != jb::cmd_get_position) out.push_back(c);
    return out;
  }

  FakeJoints joints;
  RecordingUpstream upstream;
  ControllerCore core;
  std::uint32_t now = 5000;
};

TEST(ControllerCore, StartsByHaltingEveryJointAndSettingZones) {
  FakeJoints joints;
  RecordingUpstream up;
  ControllerCore core;
  std::uint32_t now = 0;
  core.begin(scara_joints, scara_joint_count, &joints, &up, 9600, now);
  for (int i = 0; i < 3000; ++i, now += 100) {
    joints.pump([&](std::uint8_t b) { core.on_bus_byte(b, now); });
    core.poll(now);
  }
  ASSERT_GE(joints.log.size(), 14u);
  for (int j = 1; j <= 7; ++j) {
    EXPECT_EQ(joints.log[j - 1].command, jb::cmd_set_speed) << "after a reset nothing keeps moving";
    EXPECT_EQ(joints.log[j - 1].data, 0);
    EXPECT_EQ(joints.log[6 + j].command, jb::cmd_set_zone);
    EXPECT_EQ(joints.log[6 + j].data, 20);
    EXPECT_TRUE(core.joint_state(j).answering);
    EXPECT_TRUE(core.joint_state(j).read);
  }
  EXPECT_GE(core.stats().sweeps, 1u) << "then it polls positions round robin";
}

TEST(ControllerCore, MapsPositionsToClicksAndBack) {
  CoreRig rig;
  EXPECT_EQ(rig.core.to_clicks(1, 0), -20000);
  EXPECT_EQ(rig.core.to_clicks(1, 1000), 20000);
  EXPECT_EQ(rig.core.to_clicks(4, 600), 2000);
  EXPECT_EQ(rig.core.to_clicks(7, 333), -1670);
  EXPECT_EQ(rig.core.to_position(7, -1670), 333);
  EXPECT_EQ(rig.core.to_position(2, -21000), -25) << "read-backs may leave 0..1000";
  EXPECT_EQ(rig.core.to_clicks(9, 500), 0) << "no joint 9";
}

TEST(ControllerCore, MoveSendsEverySpeedThenEveryDrive) {
  CoreRig rig;
  rig.request(rc_multi_servo_move, CoreRig::move(1000, {{1, 600}, {3, 450}, {7, 0xFF00}}));
  rig.run_us(300000);
  rig.run_us(1000000);
  auto sent = rig.motion_commands();
  ASSERT_GE(sent.size(), 4u);
  EXPECT_EQ(sent[0].command, jb::cmd_set_speed);
  EXPECT_EQ(sent[0].joint, 1);
  EXPECT_EQ(sent[1].command, jb::cmd_set_speed);
  EXPECT_EQ(sent[1].joint, 3);
  EXPECT_EQ(sent[2].command, jb::cmd_drive_to);
  EXPECT_EQ(sent[3].command, jb::cmd_drive_to);
  std::set<std::pair<int, int>> drives{{sent[2].joint, sent[2].data}, {sent[3].joint, sent[3].data}};
  EXPECT_EQ(drives, (std::set<std::pair<int, int>>{{1, 4000}, {3, -2000}}));
  // Then, part-way, each joint whose whole percentage arrives early: one percent slower.
  for (std::size_t i = 4; i < sent.size(); ++i) {
    EXPECT_EQ(sent[i].command, jb::cmd_set_speed);
    EXPECT_TRUE(sent[i].joint == 1 || sent[i].joint == 3) << "joint 7 is left alone (0xFF00)";
    EXPECT_EQ(sent[i].data, rig.core.planned_percent(static_cast<std::uint8_t>(sent[i].joint)) - 1);
  }
  EXPECT_LE(sent.size(), 6u);
  EXPECT_EQ(rig.core.stats().moves, 1);
}

// The acceleration the joint's fixed-point ramp runs for a configured one (Q8 per tick^2).
double ramp_accel(double cps2) { return std::max(1.0, std::floor((cps2 * 32 + 62500) / 125000)) * 1e6 / 256; }

// Seconds a joint at rest takes for `d` clicks at `percent` of (v, a) as the joint ramps.
double ramp_time(double d, int percent, double v, double configured_a) {
  const double a = ramp_accel(configured_a);
  const double speed = v * percent / 100.0;
  if (d * a >= speed * speed) return d / speed + speed / a;
  return 2.0 * std::sqrt(d / a);
}

TEST(ControllerCore, EachJointGetsTheSlowestSpeedThatArrivesInTime) {
  CoreRig rig;
  rig.request(rc_multi_servo_move, CoreRig::move(1500, {{1, 800}, {2, 550}, {4, 100}, {6, 510}}));
  rig.run_us(20000);  // planned once the poll under way has ended
  EXPECT_EQ(rig.core.planned_ms(), 1500u) << "every joint can make it in the time asked";
  const std::uint32_t txn = rig.core.master().transaction_estimate_us();
  const int order[] = {1, 2, 4, 6};
  for (int k = 0; k < 4; ++k) {
    const int j = order[k];
    const JointSetup& s = scara_joints[j - 1];
    const double d = std::abs(rig.core.to_clicks(j, j == 1 ? 800 : j == 2 ? 550 : j == 4 ? 100 : 510));
    // Its drive follows 4 speeds and k drives, and takes effect 3 words after it starts.
    const double available = 1.5 - ((4 + k) * txn + 3 * rig.core.master().word_time_us()) / 1e6;
    const int p = rig.core.planned_percent(j);
    SCOPED_TRACE(::testing::Message() << "joint " << j << " at " << p << " %");
    ASSERT_GE(p, 1);
    ASSERT_LE(p, 100);
    EXPECT_LE(ramp_time(d, p, s.max_speed_cps, s.max_accel_cps2), available + 1e-6);
    if (p > 1) {
      EXPECT_GT(ramp_time(d, p - 1, s.max_speed_cps, s.max_accel_cps2), available);
    }
  }
}

TEST(ControllerCore, MoveWhileTheJointIsUnderWayStartsFromWhereItIsPlannedToBe) {
  // The polls of a moving joint are up to a sweep old (here: at the target at once, no
  // guide at all); a move planned half way through the previous one must start from its
  // half-way point.
  CoreRig moving;
  moving.request(rc_multi_servo_move, CoreRig::move(2000, {{1, 750}}));  // 0 -> 10000 clicks
  moving.run_us(1000000);
  moving.request(rc_multi_servo_move, CoreRig::move(1000, {{1, 750}}));
  moving.run_us(20000);
  CoreRig at_rest;
  at_rest.request(rc_multi_servo_move, CoreRig::move(1000, {{1, 750}}));
  at_rest.run_us(20000);
  EXPECT_LT(moving.core.planned_percent(1) + 10, at_rest.core.planned_percent(1))
      << "about half the distance left: a much lower speed";
  const JointState& s = moving.core.joint_state(1);
  EXPECT_TRUE(s.planned);
  EXPECT_NEAR(s.plan_from, 5000, 600) << "half way along the first move's line";
}

TEST(SetpointMotion, FromRestItIsTheTrapezoid) {
  const float a = ramp_accel(15000);
  const SetpointMotion m{0.0f, 0.0f, 10000.0f, 8000.0f, a};
  const float t = motion_arrival_s(m);
  EXPECT_NEAR(t, shortest_time_s(10000.0f, 8000.0f, a), 1e-4);
  EXPECT_NEAR(motion_at(m, t / 2).x, 5000.0f, 0.5f) << "symmetric";
  EXPECT_NEAR(motion_at(m, t / 2).v, 8000.0f, 0.5f) << "cruising";
  EXPECT_NEAR(motion_at(m, 0.1f).x, a * 0.01f / 2, 0.5f) << "accelerating";
  EXPECT_EQ(motion_at(m, t + 0.1f).x, 10000.0f);
  EXPECT_EQ(motion_at(m, t + 0.1f).v, 0.0f);
}

TEST(SetpointMotion, MovingAwayOrTooFastItBrakesToRestFirstAndComesBack) {
  const float a = ramp_accel(40000);
  // Moving away at 4000 clicks/s: it stops 4000^2 / 2a beyond its start, then turns.
  const SetpointMotion away{0.0f, -4000.0f, 1000.0f, 12000.0f, a};
  const float turn_s = 4000.0f / a;
  EXPECT_NEAR(motion_at(away, turn_s).x, -4000.0f * 4000.0f / (2 * a), 0.5f);
  EXPECT_NEAR(motion_at(away, turn_s).v, 0.0f, 1.0f);
  const float back = 1000.0f + 4000.0f * 4000.0f / (2 * a);
  EXPECT_NEAR(motion_arrival_s(away), turn_s + shortest_time_s(back, 12000.0f, a), 1e-4);
  // Toward a target nearer than its stopping distance: it overshoots and comes back.
  const SetpointMotion fast{0.0f, 8000.0f, 100.0f, 12000.0f, a};
  EXPECT_NEAR(motion_at(fast, 8000.0f / a).x, 8000.0f * 8000.0f / (2 * a), 0.5f);
  EXPECT_EQ(motion_at(fast, 1.0f).x, 100.0f);
  // Speed 0 (GroupStop): it comes to rest where it can, short of its target, and stays.
  const SetpointMotion held{0.0f, 3000.0f, 9000.0f, 0.0f, a};
  EXPECT_NEAR(motion_at(held, 1.0f).x, 3000.0f * 3000.0f / (2 * a), 0.5f);
  EXPECT_LT(motion_arrival_s(held), 0.0f) << "never arrives";
}

TEST(SetpointMotion, TheLimitForAnArrivalArrivesThen) {
  const float a = ramp_accel(15000), top = ramp_speed(8000, 100);
  // Moving toward its target: speeding up, and slowing down to a lower limit.
  for (const float v0 : {0.0f, 1500.0f, 5000.0f, -2000.0f}) {
    for (const float time_s : {1.5f, 2.0f, 4.0f}) {
      SetpointMotion m{200.0f, v0, 6200.0f, top, a};
      const float limit = limit_for_arrival(m, time_s, top);
      SCOPED_TRACE(::testing::Message() << "v0 " << v0 << " time " << time_s << " limit " << limit);
      ASSERT_GT(limit, 0.0f);
      ASSERT_LT(limit, top);
      m.limit = limit;
      EXPECT_NEAR(motion_arrival_s(m), time_s, 2e-3);
    }
  }
  const SetpointMotion far{0.0f, 0.0f, 20000.0f, top, a};
  EXPECT_EQ(limit_for_arrival(far, 1.0f, top), top) << "out of reach: flat out";
}

TEST(ControllerCore, MoveWhileAJointStillMovesDrivesItFirstFromItsRamp) {
  // Joint 1 at full cruise half way through a move: the next move's drive goes out first
  // (a speed change first would push it on toward the old target), then its speed, chosen
  // from where its ramp is and how fast it goes.
  CoreRig rig;
  rig.joints.ramps_from(scara_joints, scara_joint_count, rig.now);
  rig.request(rc_multi_servo_move, CoreRig::move(2000, {{1, 750}}));  // 0 -> 10000 clicks
  rig.run_us(1000000);
  const int first_percent = rig.core.planned_percent(1);
  rig.joints.log.clear();
  rig.request(rc_multi_servo_move, CoreRig::move(1000, {{1, 800}}));  // 12000 clicks
  rig.run_us(50000);
  auto sent = rig.motion_commands();
  ASSERT_GE(sent.size(), 1u);
  EXPECT_EQ(sent[0].command, jb::cmd_drive_to);
  EXPECT_EQ(sent[0].data, 12000);
  // 1 s in, it is about half way (5000 clicks) at its cruise speed: 7000 clicks in a second
  // from there needs a little more than the first move's speed, not the start from rest.
  const int p = rig.core.planned_percent(1);
  EXPECT_GT(p, first_percent) << "farther, sooner";
  EXPECT_LT(p, 80) << "not the 100 % a start from rest would need";
  ASSERT_EQ(sent.size(), 2u);
  EXPECT_EQ(sent[1].command, jb::cmd_set_speed);
  EXPECT_EQ(sent[1].data, p);
  EXPECT_NEAR(rig.core.joint_state(1).plan_from, 5000, 300);
  // Its ramp, replayed by the fake joint, arrives when the plan says.
  const std::uint32_t planned_end = rig.core.joint_state(1).plan_end_us;
  std::uint32_t arrived = 0;
  for (int ms = 0; ms < 1500 && arrived == 0; ++ms) {
    rig.run_us(1000);
    if (rig.joints.position[1] == 12000) arrived = rig.now;
  }
  ASSERT_NE(arrived, 0u);
  EXPECT_NEAR(static_cast<std::int32_t>(arrived - planned_end) / 1000.0, 0.0, 40.0) << "ms from the planned end";
}

TEST(ControllerCore, StreamedMovesSendOnlyWhatChanges) {
  // A joint resting on its target is not sent anything by a move that names the same
  // target.
  CoreRig rig;
  rig.joints.ramps_from(scara_joints, scara_joint_count, rig.now);
  rig.request(rc_multi_servo_move, CoreRig::move(500, {{1, 520}, {2, 500}, {3, 480}}));
  rig.run_us(1000000);  // all at rest on their targets (joint 2: where it was)
  rig.joints.log.clear();
  rig.request(rc_multi_servo_move, CoreRig::move(500, {{1, 520}, {2, 500}, {3, 480}}));
  rig.run_us(100000);
  EXPECT_TRUE(rig.motion_commands().empty()) << "nothing changes";
  rig.request(rc_multi_servo_move, CoreRig::move(2000, {{1, 620}, {2, 500}}));
  rig.run_us(500000);
  rig.joints.log.clear();
  rig.request(rc_multi_servo_move, CoreRig::move(1500, {{1, 640}, {2, 500}}));
  rig.run_us(50000);
  const auto sent = rig.motion_commands();
  ASSERT_GE(sent.size(), 1u);
  for (const auto& c : sent) EXPECT_EQ(c.joint, 1) << "joint 2 rests on its target";
  EXPECT_EQ(sent[0].command, jb::cmd_drive_to);
}

TEST(ControllerCore, MoveTooFastForAJointIsStretchedToItsReach) {
  CoreRig rig;
  rig.request(rc_multi_servo_move, CoreRig::move(100, {{2, 1000}}));  // 20000 clicks in 0.1 s
  rig.run_us(20000);
  // SHOULDER: 8000 clicks/s, 15000 clicks/s^2 (15,625 as its ramp holds it) ->
  // 20000/8000 + 8000/15625 = 3.012 s.
  const auto& m = rig.core.master();
  EXPECT_NEAR(rig.core.planned_ms(), 3012 + (m.transaction_estimate_us() + 3 * m.word_time_us()) / 1000.0, 2);
  EXPECT_EQ(rig.core.planned_percent(2), 100);
}

TEST(ControllerCore, SlowJointStartsAtOnceAndSlowsByOnePercentPartWay) {
  // SHOULDER 0 -> 1000 clicks in 3 s needs about 4.2 % of 8000 clicks/s: 5 % alone would
  // arrive 0.5 s early. It is not held back for that long: its drive goes out behind the
  // speed, and a set_speed of 4 % follows once it cruises.
  CoreRig rig;
  rig.request(rc_multi_servo_move, CoreRig::move(3000, {{2, 525}}));
  rig.run_us(100000);
  auto sent = rig.motion_commands();
  ASSERT_EQ(sent.size(), 2u) << "speed and drive within 100 ms";
  EXPECT_EQ(sent[0].command, jb::cmd_set_speed);
  const int percent = sent[0].data;
  EXPECT_EQ(sent[1].command, jb::cmd_drive_to);
  EXPECT_EQ(sent[1].data, 1000);
  EXPECT_GT(ramp_time(1000, percent - 1, 8000, 15000), 3.0) << "one percent slower alone would be late";
  rig.run_us(3000000);
  sent = rig.motion_commands();
  ASSERT_EQ(sent.size(), 3u);
  EXPECT_EQ(sent[2].command, jb::cmd_set_speed);
  EXPECT_EQ(sent[2].data, percent - 1);
}

TEST(ControllerCore, IgnoresMalformedAndOutOfRangeMovesWhole) {
  CoreRig rig;
  const auto before = rig.core.stats().ignored_frames;
  rig.request(rc_multi_servo_move, CoreRig::move(1000, {{1, 600}, {9, 500}}));   // no joint 9
  rig.request(rc_multi_servo_move, CoreRig::move(1000, {{1, 600}, {2, 1001}}));  // > 1000
  rig.request(rc_multi_servo_move, CoreRig::move(1000, {{2, 600}, {1, 100}}));   // below Z's soft min
  rig.request(rc_multi_servo_move, CoreRig::move(30001, {{1, 600}}));            // > 30 s
  rig.request(rc_multi_servo_move, CoreRig::move(1000, {{1, 600}, {1, 700}}));   // twice the same
  auto short_frame = CoreRig::move(1000, {{1, 600}});
  short_frame.pop_back();
  rig.request(rc_multi_servo_move, short_frame);
  rig.run_us(300000);
  EXPECT_TRUE(rig.motion_commands().empty());
  EXPECT_EQ(rig.core.stats().ignored_frames, before + 6);
}

TEST(ControllerCore, MoveNamingAJointThatStoppedAnsweringIsRefused) {
  CoreRig rig;
  rig.joints.dead[3] = true;
  rig.run_us(400000);  // a sweep finds it silent
  EXPECT_FALSE(rig.core.joint_state(3).answering);
  EXPECT_EQ(rig.core.joint_state(3).last_fault, jb::status_no_answer);
  rig.request(rc_multi_servo_move, CoreRig::move(1000, {{2, 600}, {3, 600}}));
  rig.run_us(300000);
  EXPECT_TRUE(rig.motion_commands().empty());
  EXPECT_EQ(rig.core.stats().refused_moves, 1);
  EXPECT_GT(rig.core.joint_state(2).reads, 0) << "the others are still polled";
}

TEST(ControllerCore, PositionReadAnswersFromThePolls) {
  CoreRig rig;
  rig.joints.position[2] = 4000;
  rig.joints.position[7] = -5000;
  rig.run_us(200000);
  rig.request(rc_servo_position_read, {2, 2, 7});
  ASSERT_EQ(rig.upstream.frames.size(), 1u);
  const Reply& r = rig.upstream.frames[0];
  EXPECT_EQ(r.command, rc_servo_position_read);
  EXPECT_EQ(r.data, (std::vector<std::uint8_t>{2, 2, 0x58, 0x02, 7, 0, 0}));  // 600, 0
  rig.request(rc_servo_position_read, {2, 2, 8});  // no joint 8: ignored
  EXPECT_EQ(rig.upstream.frames.size(), 1u);
}

TEST(ControllerCore, ServoOffTurnsLoopsOffAndTheNextMoveOn) {
  CoreRig rig;
  rig.request(rc_multi_servo_off, {2, 4, 5});
  rig.run_us(100000);
  auto sent = rig.motion_commands();
  ASSERT_EQ(sent.size(), 2u);
  EXPECT_EQ(sent[0].command, jb::cmd_set_pid_state);
  EXPECT_EQ(sent[0].data, 0);
  EXPECT_EQ(sent[1].joint, 5);
  rig.joints.log.clear();
  rig.request(rc_multi_servo_move, CoreRig::move(500, {{4, 600}}));
  rig.run_us(200000);
  sent = rig.motion_commands();
  ASSERT_EQ(sent.size(), 3u);
  EXPECT_EQ(sent[0].command, jb::cmd_set_pid_state);
  EXPECT_EQ(sent[0].data, 1);
  EXPECT_EQ(sent[2].command, jb::cmd_drive_to);
}

TEST(ControllerCore, GroupStopHaltsEveryJointAndNotifies) {
  CoreRig rig;
  rig.request(rc_multi_servo_move, CoreRig::move(3000, {{1, 900}, {2, 900}}));
  rig.request(rc_group_stop, {});  // before the move's commands went out: they never do
  rig.run_us(300000);
  auto sent = rig.motion_commands();
  ASSERT_EQ(sent.size(), 7u);
  for (const auto& c : sent) {
    EXPECT_EQ(c.command, jb::cmd_set_speed);
    EXPECT_EQ(c.data, 0);
  }
  ASSERT_EQ(rig.upstream.frames.size(), 1u);
  EXPECT_EQ(rig.upstream.frames[0].command, rc_group_stop);
  EXPECT_TRUE(rig.upstream.frames[0].data.empty());
}

TEST(ControllerCore, BatteryAndUnknownCommands) {
  CoreRig rig;
  rig.request(rc_get_battery_voltage, {});
  ASSERT_EQ(rig.upstream.frames.size(), 1u);
  EXPECT_EQ(rig.upstream.frames[0].data, (std::vector<std::uint8_t>{0xA0, 0x5B}));
  rig.request(99, {});
  rig.request(rc_get_battery_voltage, {1});
  EXPECT_EQ(rig.upstream.frames.size(), 1u);
}

TEST(ControllerCore, OffsetShiftsTargetsAndIsReadBack) {
  CoreRig rig;
  rig.request(rc_servo_offset_adjust, {2, 25, 0});
  rig.request(rc_servo_offset_adjust, {3, 0x82, 0xFF});  // -126: out of range, ignored
  rig.request(rc_servo_offset_read, {2, 2, 3});
  ASSERT_EQ(rig.upstream.frames.size(), 1u);
  EXPECT_EQ(rig.upstream.frames[0].command, rc_servo_offset_read);
  EXPECT_EQ(rig.upstream.frames[0].data, (std::vector<std::uint8_t>{2, 2, 25, 3, 0}));
  rig.request(rc_multi_servo_move, CoreRig::move(500, {{2, 500}}));
  rig.run_us(300000);
  const auto drives = rig.joints.commands_of(jb::cmd_drive_to);
  ASSERT_EQ(drives.size(), 1u);
  EXPECT_EQ(drives[0].data, 1000) << "map(500 + 25)";
}

TEST(ControllerCore, MotorModeJogsTowardTheSoftLimitAndServoModeEndsIt) {
  CoreRig rig;
  rig.request(rc_servo_speed, {3, 1, 0x39, 0xFE});  // motor, -455
  rig.run_us(100000);
  auto sent = rig.motion_commands();
  ASSERT_EQ(sent.size(), 2u);
  EXPECT_EQ(sent[0].command, jb::cmd_set_speed);
  EXPECT_EQ(sent[0].data, 46);
  EXPECT_EQ(sent[1].command, jb::cmd_drive_to);
  EXPECT_EQ(sent[1].data, -20000) << "toward joint 3's soft minimum";
  EXPECT_TRUE(rig.core.joint_state(3).jogging);
  rig.joints.log.clear();
  rig.request(rc_servo_speed, {3, 0, 0, 0});
  rig.run_us(100000);
  sent = rig.motion_commands();
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].command, jb::cmd_set_speed);
  EXPECT_EQ(sent[0].data, 0);
  rig.request(rc_servo_speed, {3, 1, 0xE9, 0x03});  // 1001: out of range
  rig.request(rc_servo_speed, {3, 2, 0, 0});        // mode 2
  rig.run_us(100000);
  EXPECT_EQ(rig.motion_commands().size(), 1u);
}

TEST(ScaraJoints, MatchTheArmControllerConfig) {
  const auto config = arm_controller::load_controller_config(arm_controller::default_controller_config_path());
  ASSERT_EQ(config.joints.size(), scara_joint_count);
  EXPECT_EQ(config.supply_millivolts, scara_supply_millivolts);
  for (std::size_t i = 0; i < scara_joint_count; ++i) {
    const auto& c = config.joints[i];
    const JointSetup& s = scara_joints[i];
    SCOPED_TRACE(c.name);
    EXPECT_EQ(s.number, c.number);
    EXPECT_EQ(s.clicks_at_0, c.map.to_clicks(0));
    EXPECT_EQ(s.clicks_at_1000, c.map.to_clicks(1000));
    EXPECT_EQ(s.soft_min, c.soft_min);
    EXPECT_EQ(s.soft_max, c.soft_max);
    EXPECT_EQ(s.max_speed_cps, c.max_speed_cps);
    EXPECT_EQ(s.max_accel_cps2, c.max_accel_cps2);
    EXPECT_EQ(s.zone, c.zone_clicks);
  }
}

TEST(ControllerCore, StreamedMovesReachEveryJointInTurn) {
  // A point every 27 ms (a 7-joint MultiServoMove at 9600 baud) while a move's 14 commands
  // take ~150 ms of bus: each joint's queued speed and drive take the newest values and
  // keep their place, so every joint is driven, toward its newest target.
  CoreRig rig;
  rig.joints.drives_move = false;
  for (int i = 0; i < 20; ++i) {
    const int p = 500 + 5 * (i + 1);
    rig.request(rc_multi_servo_move, CoreRig::move(27, {{1, p}, {2, p}, {3, p}, {4, p}, {5, p}, {6, p}, {7, p}}));
    rig.run_us(27000);
  }
  rig.run_us(300000);
  std::set<int> driven;
  for (const auto& c : rig.joints.commands_of(jb::cmd_drive_to)) driven.insert(c.joint);
  EXPECT_EQ(driven.size(), 7u) << "every joint got drives, not only the first in bus order";
  for (int j = 1; j <= 7; ++j) {
    int last = 0;
    for (const auto& c : rig.joints.commands_of(jb::cmd_drive_to))
      if (c.joint == j) last = c.data;
    EXPECT_EQ(last, rig.core.to_clicks(j, 600)) << "joint " << j << ": its last drive is the newest target";
  }
}

TEST(ControllerCore, StreamedMovesKeepEveryJointOnTheStream) {
  // A line streamed as the motion executor streams it through RcArmDevice at 9600 baud: a
  // point of all seven joints every 27 ms, each to be reached in 27 ms. The joints run their
  // own setpoint ramps (fake_joints.hpp). Each moving joint must keep up with the line and
  // never stand still on the way (bench_mega_streaming's stall: the joints were planned
  // from where the last plan's straight line put them, at rest, while they lagged behind).
  CoreRig rig;
  rig.joints.ramps_from(scara_joints, scara_joint_count, rig.now);
  const double rate[8] = {0, 0, 3000, -4000, 1500, 0, 200, 0};  // clicks/s along the line
  const double period = 0.027;
  const int points = 40;
  double worst_lag[8] = {};
  int last_moved_ms[8] = {}, longest_still_ms[8] = {};
  std::int16_t last_at[8] = {};
  for (int j = 1; j <= 7; ++j) last_at[j] = rig.joints.position[j];
  auto position_of = [&](int j, double clicks) {
    const JointSetup& s = scara_joints[j - 1];
    return static_cast<int>(std::lround(1000.0 * (clicks - s.clicks_at_0) / (s.clicks_at_1000 - s.clicks_at_0)));
  };
  int ms = 0;
  for (int i = 1; i <= points + 40; ++i) {
    if (i <= points) {
      std::vector<std::pair<int, int>> targets;
      for (int j = 1; j <= 7; ++j) targets.push_back({j, position_of(j, rate[j] * period * i)});
      rig.request(rc_multi_servo_move, CoreRig::move(27, targets));
    }
    for (int k = 0; k < 27; ++k, ++ms) {
      rig.run_us(1000);
      const double t = std::min(ms / 1000.0, period * points);
      for (int j : {2, 3, 4, 6}) {
        if (ms > 200 && i <= points) worst_lag[j] = std::max(worst_lag[j], std::abs(rate[j] * t - rig.joints.position[j]));
        if (std::abs(rig.joints.position[j] - last_at[j]) >= 5) {
          last_at[j] = rig.joints.position[j];
          last_moved_ms[j] = ms;
        }
        if (ms > 200 && i <= points) longest_still_ms[j] = std::max(longest_still_ms[j], ms - last_moved_ms[j]);
      }
    }
  }
  for (int j : {2, 3, 4, 6}) {
    SCOPED_TRACE(::testing::Message() << "joint " << j);
    std::printf("joint %d: worst lag behind the line %.0f clicks (%.0f ms of it), longest still %d ms, ends at %d (line %.0f)\n",
                j, worst_lag[j], 1000 * worst_lag[j] / std::abs(rate[j]), longest_still_ms[j], rig.joints.position[j],
                rate[j] * period * points);
    // (Joint 6 moves a Robot Commands unit, 20 clicks, every 100 ms: it rests between.)
    if (j != 6) {
      EXPECT_LT(longest_still_ms[j], 30) << "it never stands still on the way";
    }
    EXPECT_LT(worst_lag[j], 0.2 * std::abs(rate[j])) << "less than 200 ms behind the line";
    EXPECT_NEAR(rig.joints.position[j], rate[j] * period * points, 30) << "at the end of the line";
  }
  for (int j : {1, 5, 7}) EXPECT_EQ(rig.joints.position[j], 0) << "joint " << j << " stays";
  EXPECT_EQ(rig.core.stats().stalls, 0) << "no healthy joint is taken for a stalled one";
  EXPECT_EQ(rig.core.stats().following_lost, 0);
}

// ------------------------------------------------------------------ joint faults

std::vector<int> diagnostic_indexes(const FakeJoints& joints, int joint) {
  std::vector<int> out;
  for (const auto& c : joints.commands_of(jb::cmd_read_diagnostic))
    if (c.joint == joint) out.push_back(c.data);
  return out;
}

TEST(ControllerCoreFaults, AJointThatRefusesItsDriveHasItsFaultWordsReadAndReported) {
  CoreRig rig;
  rig.joints.refuses_drives[3] = true;  // a joint holding a fault answers drives with 940
  const std::int16_t words[7] = {jb::fault_runaway, 0, 3, 0, 1, 2, 0};
  std::copy(words, words + 7, rig.joints.diagnostics[3]);
  rig.request(rc_multi_servo_move, CoreRig::move(1000, {{2, 600}, {3, 600}}));
  rig.run_us(300000);
  EXPECT_EQ(diagnostic_indexes(rig.joints, 3), (std::vector<int>{0, 1, 2, 3, 4, 5, 6}));
  EXPECT_TRUE(diagnostic_indexes(rig.joints, 2).empty()) << "joint 2 follows its plan";
  const JointState& s = rig.core.joint_state(3);
  EXPECT_FALSE(s.following);
  EXPECT_TRUE(s.diagnostics_read);
  for (int k = 0; k < 7; ++k) EXPECT_EQ(s.diagnostics[k], words[k]) << k;
  EXPECT_EQ(s.following_lost, 1);
  EXPECT_EQ(rig.core.stats().following_lost, 1);
  EXPECT_EQ(rig.core.stats().fault_reads, 1);
  EXPECT_EQ(rig.core.stats().runaway_faults, 1);
  EXPECT_EQ(rig.core.stats().following_error_faults, 0);
  EXPECT_TRUE(rig.core.joint_state(2).following);

  // Upstream: the armctl extension CMD 40 answers a joint's fault state.
  rig.upstream.frames.clear();
  rig.request(rc_joint_fault_read, {3});
  ASSERT_EQ(rig.upstream.frames.size(), 1u);
  const Reply& r = rig.upstream.frames[0];
  EXPECT_EQ(r.command, rc_joint_fault_read);
  ASSERT_EQ(r.data.size(), 20u);
  EXPECT_EQ(r.data[0], 3);
  EXPECT_EQ(r.data[1], 1 | 4) << "answering (it answered its polls since), not following, words read";
  EXPECT_EQ(r.data[2] | (r.data[3] << 8), 940) << "the last bus failure: the refused drive";
  EXPECT_EQ(r.data[4] | (r.data[5] << 8), 1) << "stopped following once";
  for (int k = 0; k < 7; ++k) EXPECT_EQ(r.data[6 + 2 * k] | (r.data[7 + 2 * k] << 8), words[k]) << k;
  // Not a configured joint, or a malformed request: ignored.
  rig.upstream.frames.clear();
  rig.request(rc_joint_fault_read, {9});
  rig.request(rc_joint_fault_read, {3, 4});
  EXPECT_TRUE(rig.upstream.frames.empty());
  // Its faults are known: not read again.
  rig.run_us(1000000);
  EXPECT_EQ(diagnostic_indexes(rig.joints, 3).size(), 7u);
}

TEST(ControllerCoreFaults, JointFaultClearClearsTheJointAndAnswersWithItsStatus) {
  CoreRig rig;
  rig.joints.refuses_drives[3] = true;
  rig.joints.diagnostics[3][jb::diagnostic_faults] = jb::fault_runaway;
  rig.request(rc_multi_servo_move, CoreRig::move(1000, {{3, 600}}));
  rig.run_us(300000);
  ASSERT_FALSE(rig.core.joint_state(3).following);
  ASSERT_EQ(rig.core.joint_state(3).diagnostics[jb::diagnostic_faults], jb::fault_runaway);

  // CMD 41: clear_faults goes to the joint, and its STATUS comes back once it answered.
  rig.upstream.frames.clear();
  rig.joints.log.clear();
  rig.request(rc_joint_fault_clear, {3});
  EXPECT_TRUE(rig.upstream.frames.empty()) << "no answer before the joint's";
  rig.run_us(50000);
  ASSERT_EQ(rig.joints.commands_of(jb::cmd_clear_faults).size(), 1u);
  EXPECT_EQ(rig.joints.commands_of(jb::cmd_clear_faults)[0].joint, 3);
  ASSERT_EQ(rig.upstream.frames.size(), 1u);
  EXPECT_EQ(rig.upstream.frames[0].command, rc_joint_fault_clear);
  EXPECT_EQ(rig.upstream.frames[0].data, (std::vector<std::uint8_t>{3, 510 & 0xFF, 510 >> 8}));
  const JointState& s = rig.core.joint_state(3);
  EXPECT_TRUE(s.following);
  EXPECT_FALSE(s.diagnostics_read);
  EXPECT_EQ(s.diagnostics[jb::diagnostic_faults], 0);
  rig.upstream.frames.clear();
  rig.request(rc_joint_fault_read, {3});
  ASSERT_EQ(rig.upstream.frames.size(), 1u);
  EXPECT_EQ(rig.upstream.frames[0].data[1], 1 | 2) << "answering and following, no fault words held";
  // It drives again.
  rig.request(rc_multi_servo_move, CoreRig::move(500, {{3, 650}}));
  rig.run_us(800000);
  EXPECT_EQ(rig.joints.position[3], rig.core.to_clicks(3, 650));
  EXPECT_TRUE(rig.core.joint_state(3).following);

  // A joint that does not answer: its STATUS is the master's 990, and nothing is cleared.
  rig.joints.dead[5] = true;
  rig.upstream.frames.clear();
  rig.request(rc_joint_fault_clear, {5});
  rig.run_us(100000);
  ASSERT_EQ(rig.upstream.frames.size(), 1u);
  EXPECT_EQ(rig.upstream.frames[0].data, (std::vector<std::uint8_t>{5, 990 & 0xFF, 990 >> 8}));
  EXPECT_FALSE(rig.core.joint_state(5).answering);
  // Not a configured joint, or a malformed request: ignored, nothing sent.
  rig.upstream.frames.clear();
  rig.joints.log.clear();
  rig.request(rc_joint_fault_clear, {9});
  rig.request(rc_joint_fault_clear, {3, 4});
  rig.request(rc_joint_fault_clear, {});
  rig.run_us(50000);
  EXPECT_TRUE(rig.upstream.frames.empty());
  EXPECT_TRUE(rig.joints.commands_of(jb::cmd_clear_faults).empty());
}

TEST(ControllerCoreFaults, ClearingAJointMidMoveStopsItsMoveAndGroupStopKeepsTheClear) {
  CoreRig rig;
  rig.joints.ramps_from(scara_joints, scara_joint_count, rig.now);  // a long move under way
  rig.request(rc_multi_servo_move, CoreRig::move(2000, {{1, 700}, {2, 700}}));
  rig.run_us(300000);
  ASSERT_TRUE(rig.core.joint_state(1).planned);
  rig.joints.log.clear();
  rig.upstream.frames.clear();
  // A cleared joint holds where it is: the move would go on without it, so it stops whole,
  // and a GroupStop that comes before the clear went out does not drop it.
  rig.request(rc_joint_fault_clear, {1});
  rig.request(rc_group_stop, {});
  rig.run_us(100000);
  EXPECT_FALSE(rig.core.joint_state(1).planned);
  EXPECT_FALSE(rig.core.joint_state(2).planned);
  EXPECT_EQ(rig.joints.commands_of(jb::cmd_clear_faults).size(), 1u);
  for (const auto& c : rig.joints.commands_of(jb::cmd_set_speed)) EXPECT_EQ(c.data, 0) << c.joint;
  EXPECT_TRUE(rig.joints.commands_of(jb::cmd_drive_to).empty());
  int clears = 0;
  for (const auto& f : rig.upstream.frames) clears += f.command == rc_joint_fault_clear;
  EXPECT_EQ(clears, 1);
}

TEST(ControllerCoreFaults, AJointThatRunsTheWrongWayIsReadAgainUntilItsFaultShows) {
  CoreRig rig;
  rig.joints.drives_move = false;
  rig.request(rc_multi_servo_move, CoreRig::move(2000, {{3, 750}}));  // 0 -> 10000 clicks
  rig.run_us(100000);
  rig.joints.position[3] = -2000;  // runs away the other way, its fault not raised yet
  rig.run_us(100000);
  EXPECT_EQ(diagnostic_indexes(rig.joints, 3).size(), 7u);
  EXPECT_FALSE(rig.core.joint_state(3).following);
  EXPECT_EQ(rig.core.joint_state(3).diagnostics[0], 0);
  rig.joints.diagnostics[3][0] = jb::fault_runaway;  // the joint raises it
  rig.run_us(300000);
  EXPECT_EQ(diagnostic_indexes(rig.joints, 3).size(), 14u) << "read again after 250 ms";
  EXPECT_EQ(rig.core.joint_state(3).diagnostics[0], jb::fault_runaway);
  EXPECT_EQ(rig.core.stats().runaway_faults, 1);
  rig.run_us(1000000);
  EXPECT_EQ(diagnostic_indexes(rig.joints, 3).size(), 14u) << "the fault is known: no more reads";
  EXPECT_EQ(rig.core.stats().following_lost, 1) << "counted once";
}

TEST(ControllerCoreFaults, AJointThatStallsIsFoundMidMoveAndItsMoveIsStopped) {
  CoreRig rig;
  rig.joints.stuck[1] = true;  // blocked at 0; joint 2 moves
  rig.request(rc_multi_servo_move, CoreRig::move(1000, {{1, 600}, {2, 600}}));  // 4000 clicks each
  // Joint 1's ramp (39,062 clicks/s^2) is 500 clicks on after ~0.16 s plus a poll.
  rig.run_us(150000);
  EXPECT_FALSE(rig.core.joint_state(1).behind_ramp) << "not yet 500 clicks behind its ramp";
  rig.run_us(250000);
  const JointState& s = rig.core.joint_state(1);
  EXPECT_TRUE(s.behind_ramp) << "found 0.4 s into a 1 s move, not when it ends";
  EXPECT_FALSE(s.following);
  EXPECT_FALSE(s.planned) << "its move is stopped";
  EXPECT_FALSE(rig.core.joint_state(2).planned) << "the whole move";
  EXPECT_EQ(rig.core.stats().stalls, 1);
  EXPECT_EQ(diagnostic_indexes(rig.joints, 1), (std::vector<int>{0, 1, 2, 3, 4, 5, 6}));
  // Safe state: set_speed 0 to both joints of the move, after their drives.
  auto speeds = rig.joints.commands_of(jb::cmd_set_speed);
  ASSERT_GE(speeds.size(), 4u);
  EXPECT_EQ(speeds[speeds.size() - 2].data, 0);
  EXPECT_EQ(speeds[speeds.size() - 1].data, 0);
  EXPECT_EQ(rig.joints.commands_of(jb::cmd_drive_to).size(), 2u);
  rig.upstream.frames.clear();
  rig.request(rc_joint_fault_read, {1});
  ASSERT_EQ(rig.upstream.frames.size(), 1u);
  EXPECT_EQ(rig.upstream.frames[0].data[1], 1 | 4 | 8) << "answering, words read, behind its ramp";
  // Counted once; with no fault of its own showing, its words are read again every 250 ms
  // for a second after the stop (a runaway shows 100-150 ms after it begins), then no more.
  rig.run_us(1000000);
  EXPECT_EQ(rig.core.stats().stalls, 1);
  EXPECT_EQ(diagnostic_indexes(rig.joints, 1).size(), 28u);
  rig.run_us(1000000);
  EXPECT_EQ(diagnostic_indexes(rig.joints, 1).size(), 28u);
  // A new move naming it clears the finding.
  rig.joints.stuck[1] = false;
  rig.request(rc_multi_servo_move, CoreRig::move(1000, {{1, 600}}));
  rig.run_us(100000);
  EXPECT_FALSE(rig.core.joint_state(1).behind_ramp);
}

TEST(ControllerCoreFaults, AJointThatKeepsUpWithItsRampIsNotStalled) {
  // A joint that follows its ramp (here: always 400 clicks behind the fastest it could be)
  // is never taken for a stalled one.
  CoreRig rig;
  rig.joints.drives_move = false;
  rig.request(rc_multi_servo_move, CoreRig::move(1000, {{3, 700}}));  // 0 -> 8000 clicks
  for (int ms = 0; ms < 1600; ms += 10) {
    const double t = ms / 1000.0;
    // 8000 clicks in 1 s from the request: d/v + v/a = 1 s gives v = 11,228 clicks/s (the
    // plan starts the drive a little later, so it runs a little faster).
    const double a = 39062, v = 11228, reach = v / a;
    double x = t < reach ? a * t * t / 2 : v * v / (2 * a) + v * (t - reach);
    x = std::min(8000.0, x) - 400;
    rig.joints.position[3] = static_cast<std::int16_t>(std::max(0.0, x));
    rig.run_us(10000);
  }
  EXPECT_EQ(rig.core.stats().stalls, 0);
  EXPECT_TRUE(rig.core.joint_state(3).following);
}

TEST(ControllerCoreFaults, AJointThatStallsInAStreamIsFoundMidStreamAndEveryMoveStops) {
  // The same streamed line (a point every 27 ms at 9600 baud); joint 3 is blocked 0.27 s in.
  // Its moves are planned while it moves (no ramp from rest to check): its polls are
  // compared with its model's setpoint when the next point folds it, so it is found while
  // the stream still runs, and every joint of the stream is stopped.
  CoreRig rig;
  rig.joints.ramps_from(scara_joints, scara_joint_count, rig.now);
  const double rate[8] = {0, 0, 3000, -4000, 1500, 0, 0, 0};
  const double period = 0.027;
  const int points = 60;
  auto position_of = [&](int j, double clicks) {
    const JointSetup& s = scara_joints[j - 1];
    return static_cast<int>(std::lround(1000.0 * (clicks - s.clicks_at_0) / (s.clicks_at_1000 - s.clicks_at_0)));
  };
  int stuck_ms = -1, found_ms = -1, ms = 0;
  for (int i = 1; i <= points; ++i) {
    if (i == 10) {
      rig.joints.stuck[3] = true;
      stuck_ms = ms;
    }
    std::vector<std::pair<int, int>> targets;
    for (int j = 1; j <= 7; ++j) targets.push_back({j, position_of(j, rate[j] * period * i)});
    rig.request(rc_multi_servo_move, CoreRig::move(27, targets));
    for (int k = 0; k < 27; ++k, ++ms) {
      rig.run_us(1000);
      if (found_ms < 0 && rig.core.stats().stalls > 0) found_ms = ms;
    }
    if (found_ms >= 0) break;  // a host stops streaming when its arm stops following
  }
  ASSERT_GE(found_ms, 0) << "found before the stream ended";
  std::printf("stalled joint found %d ms after it stuck (stream of %d ms)\n", found_ms - stuck_ms,
              int(period * points * 1000));
  EXPECT_LT(found_ms - stuck_ms, 800);
  const JointState& s = rig.core.joint_state(3);
  EXPECT_TRUE(s.behind_ramp);
  EXPECT_FALSE(s.following);
  EXPECT_EQ(rig.core.stats().stalls, 1);
  rig.run_us(300000);
  for (int j : {2, 3, 4}) EXPECT_FALSE(rig.core.joint_state(j).planned) << "joint " << j << "'s move stopped";
  EXPECT_EQ(diagnostic_indexes(rig.joints, 3).size() % 7, 0u);
  EXPECT_GE(diagnostic_indexes(rig.joints, 3).size(), 7u) << "its words were read";
  // Brought to rest where they are: nothing moves on.
  const std::int16_t at2 = rig.joints.position[2], at4 = rig.joints.position[4];
  rig.run_us(500000);
  EXPECT_EQ(rig.joints.position[2], at2);
  EXPECT_EQ(rig.joints.position[4], at4);
}

TEST(ControllerCoreFaults, AJointPlannedWhileMovingIsCheckedWhenItsMoveEnds) {
  // A move planned while the joint still moves has no ramp from rest to compare with: a
  // joint that stops short is found when the move ends.
  CoreRig rig;
  rig.request(rc_multi_servo_move, CoreRig::move(2000, {{1, 750}}));  // 0 -> 10000 clicks
  rig.run_us(500000);
  rig.request(rc_multi_servo_move, CoreRig::move(1000, {{1, 700}}));  // planned while moving
  rig.run_us(20000);
  rig.joints.drives_move = false;
  rig.joints.position[1] = 5000;  // stopped short of 8000
  rig.run_us(1200000);
  EXPECT_TRUE(diagnostic_indexes(rig.joints, 1).empty()) << "between start and target during the move";
  EXPECT_EQ(rig.core.stats().stalls, 0);
  rig.run_us(600000);
  EXPECT_GE(diagnostic_indexes(rig.joints, 1).size(), 7u) << "off its target 0.5 s after the planned end";
  EXPECT_FALSE(rig.core.joint_state(1).following);
  // Back on its target (moved by hand, or cleared and driven): following again.
  rig.joints.position[1] = 8000;
  rig.run_us(200000);
  EXPECT_TRUE(rig.core.joint_state(1).following);
}

TEST(ControllerCoreFaults, HealthyMovesNeverReadFaults) {
  // (These scripted joints jump to their target at once; streamed moves are checked on
  // emulated silicon, tests/hil/mega_controller_test.cpp.)
  CoreRig rig;
  rig.request(rc_multi_servo_move, CoreRig::move(1500, {{1, 300}, {2, 700}, {3, 700}}));
  rig.run_us(2000000);
  rig.request(rc_multi_servo_move, CoreRig::move(800, {{1, 600}, {2, 400}}));
  rig.run_us(2000000);
  EXPECT_TRUE(rig.joints.commands_of(jb::cmd_read_diagnostic).empty());
  EXPECT_EQ(rig.core.stats().following_lost, 0);
}

}  // namespace
}  // namespace armctl::controller::testing
