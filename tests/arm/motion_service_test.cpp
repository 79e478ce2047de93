// The one motion service: the arm's kinematics value (arm/arm_kinematics.hpp), the planner
// (arm/plan_moves.hpp) and the runner (arm/run_motion.hpp), on the emulated xArm board and
// on simulated time.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <thread>

#include "arm/arm.hpp"
#include "arm/plan_moves.hpp"
#include "arm/rc_arm_device.hpp"
#include "arm/run_motion.hpp"
#include "arm_files.hpp"
#include "motion/move_limits.hpp"
#include "robot_commands/sim_links.hpp"

namespace armctl::arm {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

std::vector<std::optional<double>> only(std::size_t joints, std::size_t joint, double value) {
  std::vector<std::optional<double>> t(joints);
  t[joint] = value;
  return t;
}

TEST(ArmKinematics, ChecksTheDevicesRangeAsWellAsTheJointLimits) {
  ArmModel wide = testing::shipped("xarm");
  // Limits wider than what the board's 0..1000 carries for servo6 (240 deg over 1000 units).
  wide.joints[0].limits.lower = -3.0;
  wide.joints[0].limits.upper = 3.0;
  const ArmKinematics offline(wide);
  const ArmKinematics on_board(wide, Protocol::robot_commands);
  const auto beyond = only(wide.joints.size(), 0, 2.5);
  EXPECT_TRUE(offline.check_targets(beyond).ok());
  const Status refused = on_board.check_targets(beyond);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().kind, ErrorKind::invalid_argument);
  EXPECT_NE(refused.error().message.find("joint servo6: 143.239 deg maps to device position"), std::string::npos)
      << refused.error().message;
  EXPECT_NE(refused.error().message.find("outside what robot_commands carries (0..1000)"), std::string::npos)
      << refused.error().message;
  // Inside both: accepted; outside the joint limits: the limits' message first.
  EXPECT_TRUE(on_board.check_targets(only(wide.joints.size(), 0, 0.5)).ok());
  EXPECT_NE(on_board.check_targets(only(wide.joints.size(), 0, 4.0)).error().message.find("outside its limits"),
            std::string::npos);
}

TEST(ArmKinematics, IsOneValueThreadsShareWhileTheArmMoves) {
  robot_commands::testing::EmulatedLink link{9600};
  robot_commands::Client client{link};
  Arm arm{testing::shipped("xarm"), std::make_unique<RcArmDevice>(testing::shipped("xarm"), client)};
  const std::shared_ptr<const ArmKinematics> kin = arm.kinematics();
  const std::vector<double> here = arm.read().value().positions;
  CartesianGoal goal;
  goal.position = {0.18, 0.05, 0.12};
  const auto expected = kin->nearest_joints(goal, here);
  ASSERT_TRUE(expected.ok()) << expected.error().message;
  // Four threads solve the same goal at once; each gets the same answer.
  std::vector<std::vector<double>> got(4);
  std::vector<std::thread> threads;
  for (auto& g : got)
    threads.emplace_back([&, out = &g] { *out = kin->nearest_joints(goal, here).value(); });
  for (auto& t : threads) t.join();
  for (const auto& g : got) EXPECT_EQ(g, *expected);
  // The Arm's own calls are the kinematics'.
  EXPECT_EQ(arm.inverse(goal, arm.read().value())->front().joints, kin->inverse(goal, here)->front().joints);
}

TEST(ArmKinematics, KeepsTheFamilysRulesBehindIt) {
  const ArmKinematics xarm(testing::shipped("xarm"));
  const ArmKinematics scara(testing::shipped("scara"));
  EXPECT_TRUE(xarm.yaw_follows_position());
  EXPECT_FALSE(scara.yaw_follows_position());
  const motion::Rpy current{0.1, 0.2, 0.3};
  // The yaw is kept on the SCARA; on the xArm it follows the position.
  const CartesianGoal s = scara.keeping_orientation({0.3, 0.1, 0.1}, current);
  ASSERT_TRUE(s.yaw.has_value());
  EXPECT_DOUBLE_EQ(*s.yaw, 0.3);
  const CartesianGoal x = xarm.keeping_orientation({0.1, 0.1, 0.1}, current);
  EXPECT_FALSE(x.yaw.has_value());
  EXPECT_NEAR(xarm.goal_rpy(x, current).yaw, std::atan2(0.1, 0.1), 1e-12);
  EXPECT_EQ(motion::parse_elbow("up"), motion::Elbow::up);
  EXPECT_EQ(motion::parse_elbow("left"), motion::Elbow::left);
  EXPECT_FALSE(motion::parse_elbow("UP").has_value());
}

class Service : public ::testing::Test {
 protected:
  robot_commands::testing::EmulatedLink link{9600};
  robot_commands::Client client{link};
  Arm arm{testing::shipped("xarm"), std::make_unique<RcArmDevice>(testing::shipped("xarm"), client)};
  std::vector<double> here() { return arm.read().value().positions; }
  const ArmKinematics& kin() { return *arm.kinematics(); }
};

TEST_F(Service, PlansPtpAndARunOfLinesAsPieces) {
  const std::vector<double> from = here();
  PtpMove ptp;
  CartesianGoal start;
  start.position = {0.18, 0.0, 0.12};
  ptp.target = start;
  CartesianMove a, b;
  a.goal.position = {0.18, 0.05, 0.12};
  a.zone = 0.01;
  b.goal.position = {0.15, 0.05, 0.12};
  const std::vector<Move> moves{{ptp, "ptp"}, {a, "lin a"}, {b, "lin b"}, {WaitMove{0.5}, "wait"}, {MessageMove{"hi"}}};
  auto plan = plan_moves(kin(), from, moves);
  ASSERT_TRUE(plan.ok()) << plan.error().message;
  ASSERT_EQ(plan->pieces.size(), 4u);  // PTP, the blended LIN run, the wait, the message
  EXPECT_EQ(plan->pieces[0].kind, PieceKind::motion);
  EXPECT_EQ(plan->pieces[1].first_move, 1u);
  EXPECT_EQ(plan->pieces[1].last_move, 2u);
  EXPECT_EQ(plan->pieces[1].label, "lin a .. lin b");
  EXPECT_TRUE(plan->pieces[1].path != nullptr);
  EXPECT_EQ(plan->pieces[2].kind, PieceKind::wait);
  EXPECT_EQ(plan->pieces[3].kind, PieceKind::message);
  EXPECT_EQ(plan->pieces[3].text, "hi");
  EXPECT_EQ(plan->moves, 3u);
  double total = 0;
  for (const auto& p : plan->pieces) total += p.duration();
  EXPECT_DOUBLE_EQ(plan->duration, total);
  EXPECT_NEAR((kin().pose_at(plan->end()).position - b.goal.position).norm(), 0, 1e-6);
  // The speed override stretches the motions, not the wait.
  EXPECT_NEAR(run_duration(*plan, 0.5), 2 * (plan->duration - 0.5) + 0.5, 1e-9);
}

TEST_F(Service, ARefusalNamesItsMovesAndKeepsTheCause) {
  PtpMove ok;
  ok.target = only(here().size(), 0, 10 * kDeg);
  CartesianMove far, near;
  far.goal.position = {2.0, 0, 0.1};
  near.goal.position = {0.15, 0, 0.1};
  const std::vector<Move> moves{{ok}, {near}, {far}};
  MoveRefusal refused;
  auto plan = plan_moves(kin(), here(), moves, {}, &refused);
  ASSERT_FALSE(plan.ok());
  EXPECT_EQ(plan.error().kind, ErrorKind::invalid_argument);
  EXPECT_EQ(refused.first_move, 1u);  // the run of lines
  EXPECT_EQ(refused.last_move, 2u);
  EXPECT_EQ(plan.error().message.rfind("segment 2 (LIN): target: x 2000 mm is beyond reach", 0), 0u)
      << plan.error().message;
  // A PTP outside the limits: that move alone.
  PtpMove outside;
  outside.target = only(here().size(), 0, 3.0);
  const std::vector<Move> one{{ok}, {outside}};
  ASSERT_FALSE(plan_moves(kin(), here(), one, {}, &refused).ok());
  EXPECT_EQ(refused.first_move, 1u);
  EXPECT_EQ(refused.last_move, 1u);
}

TEST_F(Service, OneDurationRuleForStreamedAndBoardMoves) {
  const std::vector<double> from = here();
  PtpMove fast;
  fast.target = only(from.size(), 0, 1.7);
  fast.duration = 0.1;
  fast.duration_words = "duration 0.1 s";
  PlanOptions board;
  board.ptp = PtpRun::board;
  auto streamed = plan_moves(kin(), from, std::vector<Move>{{fast}});
  auto sent = plan_moves(kin(), from, std::vector<Move>{{fast}}, board);
  ASSERT_TRUE(streamed.ok() && sent.ok());
  const auto rule = joint_move_duration(kin().model(), from, streamed->end(), 0.1, "duration 0.1 s");
  ASSERT_TRUE(rule.ok());
  EXPECT_NEAR(streamed->duration, rule->seconds, 1e-3);
  EXPECT_NEAR(sent->duration, rule->seconds, 1e-9);
  EXPECT_EQ(sent->pieces[0].kind, PieceKind::board_move);
  EXPECT_EQ(streamed->notes(), rule->note);
  EXPECT_EQ(sent->notes(), rule->note);
  EXPECT_NE(rule->note.find("duration 0.1 s is too short for joint servo6"), std::string::npos) << rule->note;
}

TEST_F(Service, LeadsALineInFromTheSingularStraightUpStart) {
  // The xArm starts straight up (every servo centred): a line cannot start there.
  CartesianMove line;
  line.goal.position = {0.15, 0.05, 0.12};
  const std::vector<Move> moves{{line, "line 1 (LIN)"}};
  PlanOptions no_lead_in;
  no_lead_in.lead_in = false;
  ASSERT_FALSE(plan_moves(kin(), here(), moves, no_lead_in).ok());
  auto plan = plan_moves(kin(), here(), moves);
  ASSERT_TRUE(plan.ok()) << plan.error().message;
  ASSERT_EQ(plan->pieces.size(), 2u);
  EXPECT_EQ(plan->pieces[0].label, "line 1 (LIN): joint move off the singular start, 30 mm along the line");
  EXPECT_EQ(plan->moves, 1u);
  EXPECT_NEAR((kin().pose_at(plan->end()).position - line.goal.position).norm(), 0, 1e-6);
}

TEST_F(Service, RunsAPlanToTheEndAndWaitsForArrival) {
  PtpMove ptp;
  CartesianGoal goal;
  goal.position = {0.18, 0.0, 0.12};
  ptp.target = goal;
  CartesianMove line;
  line.goal.position = {0.18, 0.04, 0.12};
  const std::vector<Move> moves{{ptp, "ptp"}, {line, "lin"}};
  const Plan plan = plan_moves(kin(), here(), moves).value();
  std::vector<RunEventKind> events;
  RunHooks hooks;
  hooks.on_event = [&](const RunEvent& e) {
    if (e.kind != RunEventKind::progress) events.push_back(e.kind);
  };
  auto report = run_motion(arm, plan, hooks);
  ASSERT_TRUE(report.ok()) << report.error().message;
  EXPECT_TRUE(report->completed);
  EXPECT_FALSE(report->stopped);
  EXPECT_EQ(report->pieces, 2u);
  ASSERT_TRUE(report->arrived.has_value());
  EXPECT_LT((kin().pose_at(report->arrived->positions).position - line.goal.position).norm(), 0.003);
  EXPECT_EQ(events, (std::vector<RunEventKind>{RunEventKind::piece_started, RunEventKind::piece_done,
                                               RunEventKind::piece_started, RunEventKind::piece_done}));
}

TEST_F(Service, AStopEndsTheRunAtRestWithoutAnError) {
  PtpMove ptp;
  ptp.target = only(here().size(), 0, 60 * kDeg);
  const std::vector<Move> moves{{ptp}, {WaitMove{1.0}}};
  const Plan plan = plan_moves(kin(), here(), moves).value();
  const TimePoint began = arm.clock().now();
  RunHooks hooks;
  hooks.command = [&] {
    return arm.clock().now() - began > plan.pieces[0].motion.duration / 2 * std::chrono::seconds(1)
               ? MotionCommand::stop
               : MotionCommand::none;
  };
  auto report = run_motion(arm, plan, hooks);
  ASSERT_TRUE(report.ok()) << report.error().message;
  EXPECT_TRUE(report->stopped);
  EXPECT_FALSE(report->completed);
  EXPECT_EQ(report->pieces, 0u);
  EXPECT_GT(here()[0], 5 * kDeg);
  EXPECT_LT(here()[0], 58 * kDeg);
}

TEST_F(Service, RunsABoardMoveAndWaitsForIt) {
  PtpMove ptp;
  ptp.target = only(here().size(), 0, 30 * kDeg);
  ptp.speed = 0.5;
  PlanOptions board;
  board.ptp = PtpRun::board;
  const Plan plan = plan_moves(kin(), here(), std::vector<Move>{{ptp}}, board).value();
  ASSERT_EQ(plan.pieces[0].kind, PieceKind::board_move);
  // The board's time is that of the same move streamed: a PTP takes as long however it is sent.
  const Plan streamed = plan_moves(kin(), here(), std::vector<Move>{{ptp}}).value();
  ASSERT_EQ(streamed.pieces[0].kind, PieceKind::motion);
  EXPECT_NEAR(plan.duration, streamed.duration, 1e-9);
  EXPECT_GT(plan.duration, 0.1);
  auto report = run_motion(arm, plan);
  ASSERT_TRUE(report.ok()) << report.error().message;
  EXPECT_TRUE(report->completed);
  ASSERT_TRUE(report->arrived.has_value());
  EXPECT_NEAR(report->arrived->positions[0], 30 * kDeg, 0.01);
}

}  // namespace
}  // namespace armctl::arm
