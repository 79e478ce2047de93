// The Mega controller firmware on an emulated ATmega2560 driving seven emulated joint
// controllers (mega_rig.hpp): the Robot Commands SDK against it, command by command, with
// the joints' true positions (their emulated encoders) as the judge.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <vector>

#include <fmt/core.h>

#include "devices/robot_commands/arrival.hpp"
#include "mega_rig.hpp"
#include "portable/joint_bus_codes.hpp"

namespace armctl::hil {
namespace {

using namespace std::chrono_literals;
using robot_commands::ServoTarget;


double ms_between(TimePoint a, TimePoint b) { return std::chrono::duration<double, std::milli>(b - a).count(); }

// Runs the rig until `until`, recording per joint the last instant it was outside its
// zone (20 clicks) around its target: its arrival.
std::map<int, TimePoint> watch_arrivals(MegaRig& rig, const std::map<int, int>& targets, TimePoint until) {
  std::map<int, TimePoint> last_outside;
  for (const auto& [j, t] : targets) last_outside[j] = rig.now();
  while (rig.now() < until) {
    rig.mega.advance(2ms);
    for (const auto& [j, t] : targets)
      if (std::abs(rig.clicks(j) - t) > 20) last_outside[j] = rig.now();
  }
  return last_outside;
}

TEST(MegaController, AnswersBatteryAndPositionsAfterPowerUp) {
  MegaRig rig;
  auto mv = rig.client->battery_millivolts();
  ASSERT_TRUE(mv.ok()) << mv.error().message;
  EXPECT_EQ(*mv, 24000) << "the stated fixed supply (docs/mega-controller.md)";
  auto positions = rig.client->read_all_positions();
  ASSERT_TRUE(positions.ok()) << positions.error().message;
  ASSERT_EQ(positions->size(), 7u);
  for (const auto& p : *positions) EXPECT_EQ(p.position, 500) << "joint " << int(p.servo) << " starts at 0 clicks";
}

TEST(MegaController, BatteryIsMeasuredOnA0ThroughTheDivider) {
  // The BATTERY=a0 image: A0 = supply x 10/57 (47k over 10k), against AVcc = 5 V.
  MegaRig rig(9600, {}, joint_avr::mega_firmware_elf_battery());
  for (const int supply_mv : {24000, 12000, 26500}) {
    const int pin_mv = supply_mv * 10 / 57;
    rig.mega.mega().set_adc_millivolts(0, std::uint32_t(pin_mv));
    rig.mega.advance(20ms);  // a reading every ~1.7 ms
    auto mv = rig.client->battery_millivolts();
    ASSERT_TRUE(mv.ok()) << mv.error().message;
    // The ADC's step is 27.8 mV of supply (28,500 / 1024); the pin voltage above is rounded down.
    EXPECT_NEAR(int(*mv), supply_mv, 60) << "supply " << supply_mv;
  }
  // Above the divider's full scale (28.5 V): the ADC saturates.
  rig.mega.mega().set_adc_millivolts(0, 5000);
  rig.mega.advance(20ms);
  auto top = rig.client->battery_millivolts();
  ASSERT_TRUE(top.ok());
  EXPECT_NEAR(int(*top), 28472, 30) << "1023 of 1024 steps of 28,500 mV";
  // The move path is unchanged in this image.
  ASSERT_TRUE(rig.client->move({{1, 520}}, 300).ok());
  rig.mega.advance(800ms);
  EXPECT_NEAR(rig.clicks(1), clicks_for(1, 520), 20);
}

TEST(MegaController, SynchronizedMoveArrivesTogetherAndReadsBack) {
  MegaRig rig;
  const std::vector<ServoTarget> move{{1, 600}, {2, 450}, {3, 540}, {5, 600}, {7, 300}};
  std::map<int, int> targets;
  for (const auto& t : move) targets[t.servo] = clicks_for(t.servo, *t.position);
  const TimePoint start = rig.now();
  ASSERT_TRUE(rig.client->move(move, 1500).ok());
  auto arrivals = watch_arrivals(rig, targets, start + 2500ms);
  double earliest = 1e9, latest = -1e9;
  for (const auto& [j, at] : arrivals) {
    const double ms = ms_between(start, at);
    earliest = std::min(earliest, ms);
    latest = std::max(latest, ms);
    EXPECT_NEAR(ms, 1500, 150) << fmt::format("joint {} arrived at {:.0f} ms of 1500", j, ms);
    EXPECT_LE(std::abs(rig.clicks(j) - targets[j]), 20) << "joint " << j;
  }
  std::printf("Mega controller, 9600 baud, 1500 ms move: joints in their zones %.0f .. %.0f ms\n", earliest, latest);
  auto read = rig.client->read_positions({1, 2, 3, 4, 5, 6, 7});
  ASSERT_TRUE(read.ok()) << read.error().message;
  for (const auto& p : *read) {
    const int expected = targets.count(p.servo) ? [&] {
      for (const auto& t : move)
        if (t.servo == p.servo) return int(*t.position);
      return 500;
    }() : 500;
    EXPECT_NEAR(p.position, expected, 1) << "joint " << int(p.servo);
  }
}

// Stated tolerance for a synchronized move's arrival (as the Linux arm controller states
// it, docs/arm-controller.md): every joint in its zone within max(75 ms, 5 % of the move's
// time) of the instant asked for, or of the joints' reach when that is later.
double arrival_tolerance_ms(double move_ms) { return std::max(75.0, 0.05 * move_ms); }

TEST(MegaController, SynchronizedMoveArrivesWithinItsTime) {
  for (const std::uint32_t baud : {9600u, 115200u}) {
    SCOPED_TRACE(::testing::Message() << baud << " baud");
    MegaRig rig(baud);
    const std::vector<ServoTarget> move{{1, 600}, {3, 450}, {6, 620}};
    std::map<int, int> targets;
    for (const auto& t : move) targets[t.servo] = clicks_for(t.servo, *t.position);
    const TimePoint start = rig.now();
    ASSERT_TRUE(rig.client->move(move, 800).ok());
    for (const auto& [j, at] : watch_arrivals(rig, targets, start + 1500ms)) {
      EXPECT_NEAR(ms_between(start, at), 800, arrival_tolerance_ms(800)) << "joint " << j;
      EXPECT_LE(std::abs(rig.clicks(j) - targets[j]), 20) << "joint " << j;
    }
  }
}

// Found by hand: `armctl xarm ... move 1=600 --time 500 --wait` on the emulated Mega
// failed. Joint 1 (Z: 12,000 clicks/s, 40,000 clicks/s^2) cannot cover 4,000 clicks in
// 500 ms: its reach is 2 x sqrt(4000 / 39062) = 640 ms (the joint's acceleration as its
// fixed-point ramp holds it), so the move is stretched to that, as an xArm stretches a
// move to its servos' speed limit; then it must arrive within the tolerance, and the CLI's
// closed-loop wait (reads from 500 ms on, 1000 ms more) must find it there.
TEST(MegaController, MoveOutOfReachArrivesAsSoonAsTheJointCan) {
  const std::vector<ServoTarget> move{{1, 600}};
  const double reach_ms = 2000.0 * std::sqrt(4000.0 / 39062.0);
  {
    MegaRig rig;
    const TimePoint start = rig.now();
    ASSERT_TRUE(rig.client->move(move, 500).ok());
    const auto arrivals = watch_arrivals(rig, {{1, clicks_for(1, 600)}}, start + 1500ms);
    EXPECT_NEAR(ms_between(start, arrivals.at(1)), reach_ms, arrival_tolerance_ms(reach_ms));
    EXPECT_LE(std::abs(rig.clicks(1) - clicks_for(1, 600)), 20);
  }
  MegaRig rig;
  const TimePoint start = rig.now();
  ASSERT_TRUE(rig.client->move(move, 500).ok());
  robot_commands::ArrivalOptions options;
  options.not_before = start + 500ms;
  const auto report = robot_commands::wait_until_arrived(*rig.client, move, start + 1500ms, options);
  ASSERT_TRUE(report.ok()) << report.error().message;
  EXPECT_TRUE(report->all_arrived()) << "servo 1 at " << report->servos[0].position;
}

TEST(MegaController, GroupStopHaltsEveryJointShortOfItsTarget) {
  MegaRig rig;
  ASSERT_TRUE(rig.client->move({{2, 900}, {3, 100}}, 3000).ok());
  rig.mega.advance(1000ms);
  ASSERT_TRUE(rig.client->stop_group().ok());
  rig.mega.advance(600ms);
  const int two = rig.clicks(2), three = rig.clicks(3);
  rig.mega.advance(1000ms);
  EXPECT_NEAR(rig.clicks(2), two, 20) << "joint 2 at rest after the stop";
  EXPECT_NEAR(rig.clicks(3), three, 20);
  EXPECT_LT(two, clicks_for(2, 900) - 2000) << "stopped well short of the target";
  EXPECT_GT(two, 500) << "it had started";
}

TEST(MegaController, ServoOffTurnsTheLoopOffAndTheNextMoveTurnsItOn) {
  MegaRig rig;
  ASSERT_TRUE(rig.client->servos_off({4}).ok());
  rig.mega.advance(300ms);
  EXPECT_FALSE(rig.mega.arm().joint(4).chip().bridge_inputs().enable) << "H-bridge of joint 4 off";
  EXPECT_TRUE(rig.mega.arm().joint(3).chip().bridge_inputs().enable);
  ASSERT_TRUE(rig.client->move({{4, 700}}, 800).ok());
  rig.mega.advance(1500ms);
  EXPECT_TRUE(rig.mega.arm().joint(4).chip().bridge_inputs().enable);
  EXPECT_NEAR(rig.clicks(4), clicks_for(4, 700), 20);
}

TEST(MegaController, MotorModeJogsAndServoModeStops) {
  MegaRig rig;
  ASSERT_TRUE(rig.client->adjust_offset(6, -40).ok());
  auto offsets = rig.client->read_offsets({6});
  ASSERT_TRUE(offsets.ok()) << offsets.error().message;
  ASSERT_EQ(offsets->size(), 1u);
  EXPECT_EQ((*offsets)[0].offset, -40);
  ASSERT_TRUE(rig.client->set_mode(2, robot_commands::ServoMode::motor, 500).ok());
  rig.mega.advance(800ms);
  ASSERT_TRUE(rig.client->set_mode(2, robot_commands::ServoMode::servo, 0).ok());
  rig.mega.advance(800ms);
  const int stopped = rig.clicks(2);
  rig.mega.advance(500ms);
  EXPECT_GT(stopped, 1000) << "joint 2 jogged up at half its top speed";
  EXPECT_NEAR(rig.clicks(2), stopped, 20) << "and rests after servo mode";
}

TEST(MegaController, TornUpstreamFrameMovesNothing) {
  MegaRig rig;
  // A host dies mid-frame (a move of servo 1 begun), the next one reads positions.
  rig.link.send_bytes({0x55, 0x55, 0x08, 0x03, 0x01});
  rig.mega.advance(300ms);
  rig.link.send_bytes({0x55, 0x55, 0x04, 0x15, 0x01, 0x04});  // would complete "servo 4 -> 0x5515..."
  rig.mega.advance(100ms);
  auto read = rig.client->read_positions({4});
  ASSERT_TRUE(read.ok()) << read.error().message;
  rig.mega.advance(1000ms);
  for (int j = 1; j <= 7; ++j) EXPECT_NEAR(rig.clicks(j), 0, 20) << "joint " << j << " must not move";
}

TEST(MegaController, RefusesBadRequestsWhole) {
  MegaRig rig;
  // Joint 9 does not exist; 1001 is out of range; joint 1's soft minimum is -15000
  // (position 125): each frame is ignored whole, including its valid entries.
  rig.link.send_bytes({0x55, 0x55, 0x0B, 0x03, 0x02, 0xE8, 0x03, 0x02, 0x58, 0x02, 0x09, 0xF4, 0x01});
  rig.link.send_bytes({0x55, 0x55, 0x08, 0x03, 0x01, 0xE8, 0x03, 0x03, 0xE9, 0x03});
  rig.link.send_bytes({0x55, 0x55, 0x0B, 0x03, 0x02, 0xE8, 0x03, 0x02, 0x58, 0x02, 0x01, 0x64, 0x00});
  rig.mega.advance(1500ms);
  for (int j = 1; j <= 7; ++j) EXPECT_NEAR(rig.clicks(j), 0, 20) << "joint " << j;
  // Still answering afterwards.
  EXPECT_TRUE(rig.client->battery_millivolts().ok());
}

TEST(MegaController, MoveNamingADeadJointIsRefusedWhole) {
  MegaRig rig;
  rig.mega.arm().joint(5).set_held_in_reset(true);  // killed: it never answers again
  rig.mega.advance(500ms);                          // the polls find out
  ASSERT_TRUE(rig.client->move({{2, 700}, {5, 700}}, 800).ok());
  rig.mega.advance(1200ms);
  EXPECT_NEAR(rig.clicks(2), 0, 20) << "no joint of a refused move moves";
  // The others still work. (The SHOULDER's 8,000 clicks take at least 8000/8000 +
  // 8000/15625 = 1.51 s: the move is stretched to that, so look at 2 s, not at 1.2 s.)
  ASSERT_TRUE(rig.client->move({{2, 700}}, 800).ok());
  rig.mega.advance(2000ms);
  EXPECT_NEAR(rig.clicks(2), clicks_for(2, 700), 20);
}

TEST(MegaController, JointKilledMidMoveLeavesTheOthersRunning) {
  MegaRig rig;
  ASSERT_TRUE(rig.client->move({{1, 700}, {3, 700}}, 1000).ok());
  rig.mega.advance(300ms);
  rig.mega.arm().joint(3).set_held_in_reset(true);
  rig.mega.advance(1200ms);
  EXPECT_NEAR(rig.clicks(1), clicks_for(1, 700), 20) << "joint 1 completes its move";
  auto read = rig.client->read_positions({1, 2});
  ASSERT_TRUE(read.ok()) << "the controller keeps answering: " << read.error().message;
}

// The armctl extension CMD 40 (docs/mega-controller.md "Joint faults") through the SDK.
std::optional<rc::JointFaultReport> read_joint_faults(MegaRig& rig, int servo) {
  auto r = rig.client->read_joint_faults(std::uint8_t(servo));
  EXPECT_TRUE(r.ok()) << r.error().message;
  if (!r.ok() || !*r) return std::nullopt;
  return **r;
}

TEST(MegaController, JointThatRunsAwayMidMoveStopsItsMoveAndHasItsFaultsRead) {
  // Joint 3's motor leads are swapped: driven up, it runs down, raises a runaway fault and
  // stops itself (bridge braked, then off). The Mega finds it behind its setpoint ramp
  // within the first moments, stops the move (joint 2 rests short of its target), reads
  // its 7 diagnostic words until the runaway shows, and answers them upstream.
  MegaRig rig(115200, {3});
  ASSERT_TRUE(rig.client->move({{2, 700}, {3, 700}}, 1500).ok());
  rig.mega.advance(2500ms);
  EXPECT_LT(rig.clicks(3), -64) << "it ran the wrong way";
  EXPECT_LT(rig.clicks(2), clicks_for(2, 700) - 2000) << "joint 2's move was stopped";
  EXPECT_GT(rig.clicks(2), 20) << "joint 2 had started";
  const auto j3 = read_joint_faults(rig, 3);
  ASSERT_TRUE(j3.has_value());
  EXPECT_EQ(j3->servo, 3);
  EXPECT_FALSE(j3->following);
  EXPECT_TRUE(j3->words_read);
  EXPECT_TRUE(j3->answering) << "it still answers its polls";
  EXPECT_TRUE(j3->behind_ramp);
  EXPECT_EQ(j3->following_lost, 1);
  EXPECT_EQ(j3->words[0], joint_bus::fault_runaway) << "read again until the joint's own fault showed";
  EXPECT_EQ(j3->words[4] & 1, 1) << "reset cause: power-on";
  EXPECT_EQ(j3->words[3], 0) << "no UART errors";
  const auto j2 = read_joint_faults(rig, 2);
  ASSERT_TRUE(j2.has_value());
  EXPECT_TRUE(j2->answering && j2->following && !j2->words_read && !j2->behind_ramp);
  EXPECT_EQ(j2->following_lost, 0);
  // A new move for the faulted joint: refused by the joint (940), still reported; the
  // other joint moves.
  ASSERT_TRUE(rig.client->move({{2, 600}, {3, 600}}, 1000).ok());
  rig.mega.advance(1500ms);
  EXPECT_NEAR(rig.clicks(2), clicks_for(2, 600), 20);
  const auto again = read_joint_faults(rig, 3);
  ASSERT_TRUE(again.has_value());
  EXPECT_EQ(again->words[0], joint_bus::fault_runaway);
  EXPECT_EQ(again->last_failure, 940) << "the refused drive";
}

TEST(MegaController, StreamedMovesOnAHealthyArmReadNoFaults) {
  // Moves streamed every 150 ms, reversing: a joint still moving when the next move is
  // planned is never taken for one that stopped following.
  MegaRig rig(115200);
  for (int i = 0; i < 12; ++i) {
    const int p = i % 2 == 0 ? 650 : 400;
    ASSERT_TRUE(rig.client->move({{1, p}, {2, 1000 - p}, {3, p}}, 400).ok());
    rig.mega.advance(150ms);
  }
  rig.mega.advance(1500ms);
  for (int j = 1; j <= 3; ++j) {
    const auto r = read_joint_faults(rig, j);
    ASSERT_TRUE(r.has_value());
    EXPECT_TRUE(r->answering && r->following && !r->words_read && !r->behind_ramp) << "joint " << j;
    EXPECT_EQ(r->following_lost, 0) << "joint " << j;
  }
}

TEST(MegaController, JointBlockedMidMoveIsFoundBehindItsRampAndItsMoveStopped) {
  // Joint 3 meets an obstacle 400 ms into a 2 s move: the Mega finds it behind its setpoint
  // ramp while the move is under way (not when it ends), stops the move (joint 2 comes to
  // rest short of its target) and answers JointFaultRead.
  MegaRig rig;
  ASSERT_TRUE(rig.client->move({{2, 700}, {3, 700}}, 2000).ok());
  const TimePoint start = rig.now();
  rig.mega.advance(400ms);
  const int blocked_at = rig.clicks(3);
  ASSERT_GT(blocked_at, 300) << "joint 3 was on its way";
  rig.mega.arm().joint(3).set_obstacle({blocked_at - 1, blocked_at + 1});
  std::optional<rc::JointFaultReport> found;
  while (!found && rig.now() < start + 2000ms) {
    rig.mega.advance(50ms);
    const auto r = read_joint_faults(rig, 3);
    if (r && r->behind_ramp) found = r;
  }
  ASSERT_TRUE(found.has_value()) << "never found behind its ramp";
  const double found_ms = ms_between(start, rig.now());
  std::printf("joint 3 blocked at 400 ms of a 2000 ms move: found behind its ramp by %.0f ms\n", found_ms);
  EXPECT_LT(found_ms, 1000) << "mid-move";
  EXPECT_FALSE(found->following);
  EXPECT_TRUE(found->answering);
  EXPECT_EQ(found->following_lost, 1);
  rig.mega.advance(1000ms);
  const int two = rig.clicks(2);
  rig.mega.advance(500ms);
  EXPECT_NEAR(rig.clicks(2), two, 20) << "joint 2 at rest: the move was stopped";
  EXPECT_LT(two, clicks_for(2, 700) - 1000) << "short of its target";
  EXPECT_NEAR(rig.clicks(3), blocked_at, 2);
  const auto later = read_joint_faults(rig, 3);
  ASSERT_TRUE(later.has_value());
  EXPECT_TRUE(later->words_read) << "its diagnostic words were read";
  // Freed, the next move works (and clears the finding).
  rig.mega.arm().joint(3).set_obstacle({-30000, 30000});
  ASSERT_TRUE(rig.client->move({{3, 600}}, 1000).ok());
  rig.mega.advance(1500ms);
  EXPECT_NEAR(rig.clicks(3), clicks_for(3, 600), 20);
  const auto cleared = read_joint_faults(rig, 3);
  ASSERT_TRUE(cleared.has_value());
  EXPECT_FALSE(cleared->behind_ramp);
}

class MegaStream : public ::testing::TestWithParam<std::uint32_t> {};

TEST_P(MegaStream, AJointBlockedMidStreamIsFoundWhileTheStreamRuns) {
  // A line streamed as a host streams one: a point every 30 ms, each to be reached in 30 ms,
  // joints 2 and 3 moving steadily. Joint 3 meets an obstacle 0.6 s in. Its moves are all
  // planned while it moves (no ramp from rest to check): the Mega compares its polls with
  // its model's setpoint when the next point is planned, finds it within the stream, and
  // stops every move (joint 2 comes to rest) instead of letting the others run on without it.
  MegaRig rig(GetParam());
  const TimePoint start = rig.now();
  std::optional<int> blocked_at;
  std::optional<double> found_ms;
  const int points = 100;  // 3 s
  for (int i = 1; i <= points && !found_ms; ++i) {
    const int p = 500 + 4 * i;  // 500 -> 900
    ASSERT_TRUE(rig.client->move({{2, p}, {3, p}}, 30).ok());
    rig.mega.advance(30ms);
    if (!blocked_at && rig.now() >= start + 600ms) {
      blocked_at = rig.clicks(3);
      rig.mega.arm().joint(3).set_obstacle({*blocked_at - 1, *blocked_at + 1});
    }
    if (blocked_at && i % 5 == 0) {
      const auto r = read_joint_faults(rig, 3);
      if (r && r->behind_ramp) found_ms = ms_between(start, rig.now());
    }
  }
  ASSERT_TRUE(blocked_at.has_value());
  ASSERT_TRUE(found_ms.has_value()) << "never found while the stream ran";
  std::printf("%u baud: joint 3 blocked at 600 ms of a 3000 ms stream: found by %.0f ms\n", GetParam(), *found_ms);
  EXPECT_LT(*found_ms, 1500) << "within the stream, well before its end";
  rig.mega.advance(500ms);
  const int two = rig.clicks(2);
  rig.mega.advance(500ms);
  EXPECT_NEAR(rig.clicks(2), two, 20) << "joint 2 at rest: every move was stopped";
  EXPECT_LT(two, clicks_for(2, 900) - 1000) << "short of where the stream went";
  const auto later = read_joint_faults(rig, 3);
  ASSERT_TRUE(later.has_value());
  EXPECT_FALSE(later->following);
  EXPECT_TRUE(later->words_read) << "its diagnostic words were read";
}

INSTANTIATE_TEST_SUITE_P(Baud, MegaStream, ::testing::Values(9600u, 115200u));

TEST(MegaController, ResetMidMoveHaltsTheJoints) {
  MegaRig rig;
  ASSERT_TRUE(rig.client->move({{2, 950}}, 3000).ok());
  rig.mega.advance(1200ms);
  rig.mega.reset_mega();  // e.g. the watchdog, or the USB port opened (DTR)
  rig.mega.advance(1000ms);  // 100 ms start-up, set_speed 0, then at most 0.5 s of braking
  const int held = rig.clicks(2);
  rig.mega.advance(1000ms);
  EXPECT_NEAR(rig.clicks(2), held, 20) << "joint 2 at rest after the controller's reset";
  EXPECT_LT(held, clicks_for(2, 950) - 2000);
  EXPECT_TRUE(rig.client->battery_millivolts().ok()) << "answers again after the reset";
}

TEST(MegaController, GroupDownloadedSurvivesAResetAndPlays) {
  MegaRig rig(115200);
  const std::vector<robot_commands::GroupAction> actions{
      {400, {{1, 520}, {2, 480}, {7, 550}}},
      {500, {{1, 560}, {2, 450}, {7, 600}}},
  };
  const auto downloaded = rig.client->download_group(3, actions);
  ASSERT_TRUE(downloaded.ok()) << downloaded.error().message;
  rig.mega.reset_mega();  // the EEPROM keeps the group
  rig.mega.advance(400ms);
  ASSERT_TRUE(rig.client->run_group(3, 1).ok());
  auto started = rig.client->wait_event(rig.now() + 500ms);
  ASSERT_TRUE(started.ok()) << started.error().message;
  EXPECT_EQ(started->kind, robot_commands::GroupEventKind::started);
  auto finished = rig.client->wait_event(rig.now() + 3000ms);
  ASSERT_TRUE(finished.ok()) << finished.error().message;
  EXPECT_EQ(finished->kind, robot_commands::GroupEventKind::finished);
  EXPECT_EQ(finished->group, 3);
  rig.mega.advance(300ms);
  EXPECT_NEAR(rig.clicks(1), clicks_for(1, 560), 20);
  EXPECT_NEAR(rig.clicks(2), clicks_for(2, 450), 20);
  EXPECT_NEAR(rig.clicks(7), clicks_for(7, 600), 20);
}

TEST(MegaController, GroupThatDoesNotFitTheEepromIsRefusedAndErasedGroupsDoNotRun) {
  MegaRig rig(115200);
  // 1020 one-joint actions need 5100 bytes; the EEPROM holds 3964 bytes of groups.
  std::vector<robot_commands::GroupAction> big(1020, robot_commands::GroupAction{100, {{1, 500}}});
  const auto refused = rig.client->download_group(4, big);
  EXPECT_FALSE(refused.ok()) << "refused at sub 2 with no reply, as anything inconsistent";
  ASSERT_TRUE(rig.client->download_group(5, {{300, {{3, 540}}}}).ok());
  ASSERT_TRUE(rig.client->erase_group(5).ok());
  ASSERT_TRUE(rig.client->run_group(5, 1).ok());
  auto events = rig.client->pump_events(rig.now() + 1000ms);
  ASSERT_TRUE(events.ok()) << events.error().message;
  EXPECT_EQ(*events, 0u) << "an erased group does not start";
  EXPECT_NEAR(rig.clicks(3), 0, 20);
}

TEST(MegaController, SynchronizedMoveAt115200) {
  MegaRig rig(115200);
  const std::vector<ServoTarget> move{{1, 400}, {2, 560}, {4, 300}, {6, 650}};
  std::map<int, int> targets;
  for (const auto& t : move) targets[t.servo] = clicks_for(t.servo, *t.position);
  const TimePoint start = rig.now();
  ASSERT_TRUE(rig.client->move(move, 1000).ok());
  auto arrivals = watch_arrivals(rig, targets, start + 1800ms);
  for (const auto& [j, at] : arrivals) {
    EXPECT_NEAR(ms_between(start, at), 1000, 100) << "joint " << j;
    EXPECT_LE(std::abs(rig.clicks(j) - targets[j]), 20) << "joint " << j;
  }
}

}  // namespace
}  // namespace armctl::hil
