// Host-planned motion on both simulated arms, on simulated time: jerk-limited joint moves
// and Cartesian paths (LIN, blended corners), planned by arm::plan_* and streamed by the
// executor. The tool's real position comes from the simulators' own joints after every
// stream point, so these figures are what the arm did, not what was sent.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <fmt/core.h>

#include "arm/arm.hpp"
#include "arm/bus_arm_device.hpp"
#include "arm/motion_executor.hpp"
#include "arm/motion_planning.hpp"
#include "arm/rc_arm_device.hpp"
#include "arm_files.hpp"
#include "joint_bus/sim_fixture.hpp"
#include "arm_controller/controller_rig.hpp"
#include "robot_commands/sim_links.hpp"

namespace armctl::arm {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

double to_line(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d d = b - a;
  const double f = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (p - (a + f * d)).norm();
}

motion::PathSegment lin_to(const motion::Pose& from, const Eigen::Vector3d& offset, double speed, double zone = 0) {
  motion::PathSegment s;
  s.target = from;
  s.target.position += offset;
  s.speed = speed;
  s.zone = zone;
  return s;
}

class XarmMotion : public ::testing::Test {
 protected:
  robot_commands::testing::EmulatedLink link{9600};
  robot_commands::Client client{link};
  Arm arm{testing::shipped("xarm"), std::make_unique<RcArmDevice>(testing::shipped("xarm"), client)};

  void SetUp() override {
    // A bent pose in front of the arm (the path tests start here).
    ASSERT_TRUE(arm.move_joints({0.0, 0.5, 0.9, 0.6, 0.0, std::nullopt}));
    ASSERT_TRUE(arm.wait());
  }
  std::vector<double> here() { return arm.read().value().positions; }
  // The servos' real positions (the emulator's), SI.
  std::vector<double> true_joints() {
    std::vector<double> device;
    for (const auto& j : arm.model().joints)
      device.push_back(link.emulator().servos().commanded_position(std::uint8_t(j.map(Protocol::robot_commands)->id)));
    return arm.model().from_device(Protocol::robot_commands, device);
  }
  Eigen::Vector3d true_tool() { return arm.forward(arm.chain_of(true_joints())).position; }
};

TEST_F(XarmMotion, JointMoveIsJerkLimitedAndEndsTogether) {
  const auto from = here();
  JointMove move;
  move.target = from;
  move.target[0] += 60 * kDeg;
  move.target[2] -= 30 * kDeg;
  move.speed = 0.5;
  auto plan = plan_joint_move(arm.model(), from, move);
  ASSERT_TRUE(plan) << plan.error().message;
  // The plan never asks more than the limits (sampled finely; the generator's own tests
  // check the analytic extrema).
  std::vector<double> p(6), v(6), a(6);
  for (double t = 0; t <= plan->duration; t += 0.002) {
    plan->sample(t, p, v, a);
    for (std::size_t i = 0; i < 6; ++i) {
      const auto& l = arm.model().joints[i].limits;
      EXPECT_LE(std::abs(v[i]), 0.5 * l.velocity * (1 + 1e-9)) << i << " at " << t;
      EXPECT_LE(std::abs(a[i]), l.acceleration * (1 + 1e-9)) << i << " at " << t;
    }
  }
  auto r = execute_motion(arm, *plan);
  ASSERT_TRUE(r) << r.error().message;
  ASSERT_TRUE(arm.wait());
  const auto end = here();
  EXPECT_NEAR(end[0], move.target[0], 0.25 * kDeg);
  EXPECT_NEAR(end[2], move.target[2], 0.25 * kDeg);
}

TEST(JointValuesTarget, LeadingJointsOfTheirKindTheRestStay) {
  const ArmModel scara = testing::shipped("scara");  // Z (a length) first, then angles
  const std::vector<double> from = {0.15, 0.1, 0.2, 0.3, 0.4, 0.5, 0.02};
  auto t = joint_values_target(scara, from, {{0.2, Dimension::length}, {-0.5, Dimension::angle}});
  ASSERT_TRUE(t) << t.error().message;
  EXPECT_EQ(*t, (std::vector<double>{0.2, -0.5, 0.2, 0.3, 0.4, 0.5, 0.02}));
  auto wrong = joint_values_target(scara, from, {{0.2, Dimension::angle}});
  ASSERT_FALSE(wrong);
  EXPECT_EQ(wrong.error().message, "joint Z takes a length, not an angle");
  auto many = joint_values_target(scara, from, std::vector<files::JointValue>(8));
  ASSERT_FALSE(many);
  EXPECT_EQ(many.error().message, "8 joint values given; arm 'scara' has 7 joints");
}

TEST_F(XarmMotion, RefusesAJointMoveOutsideTheLimits) {
  JointMove move;
  move.target = here();
  move.target[0] = 130 * kDeg;
  auto plan = plan_joint_move(arm.model(), here(), move);
  ASSERT_FALSE(plan);
  EXPECT_NE(plan.error().message.find("servo6"), std::string::npos) << plan.error().message;
}

TEST_F(XarmMotion, LinKeepsTheToolOnTheLine) {
  const auto from = here();
  const motion::Pose start = arm.forward(arm.chain_of(from));
  const auto seg = lin_to(start, {0, 0.08, 0}, 0.04);
  auto plan = plan_path(arm.model(), from, std::span(&seg, 1));
  ASSERT_TRUE(plan) << plan.error().message;
  double worst = 0;
  ExecutorOptions o;
  o.on_point = [&](const MotionProgress&) {
    worst = std::max(worst, to_line(true_tool(), start.position, seg.target.position));
  };
  auto r = execute_motion(arm, plan->motion, o);
  ASSERT_TRUE(r) << r.error().message;
  ASSERT_TRUE(arm.wait());
  // Servo units of 0.24 deg at a reach of about 0.2 m: the stream stays within 2 mm.
  EXPECT_LT(worst, 0.002);
  EXPECT_LT((true_tool() - seg.target.position).norm(), 0.002);
  // About 2 s of motion (80 mm at 40 mm/s plus the ramps).
  EXPECT_GT(std::chrono::duration<double>(r->elapsed).count(), 2.0);
  EXPECT_LT(std::chrono::duration<double>(r->elapsed).count(), 3.0);
}

TEST_F(XarmMotion, StopMidLineComesToRestOnTheLine) {
  const auto from = here();
  const motion::Pose start = arm.forward(arm.chain_of(from));
  const auto seg = lin_to(start, {0, 0.08, 0}, 0.04);
  auto plan = plan_path(arm.model(), from, std::span(&seg, 1));
  ASSERT_TRUE(plan) << plan.error().message;
  ExecutorOptions o;
  o.command = [](const MotionProgress& p) { return p.t > 1.0 ? MotionCommand::stop : MotionCommand::none; };
  // The joints' positions as planned at every point's instant: their second differences
  // are the accelerations the stop asks for.
  std::vector<std::pair<double, std::vector<double>>> planned;
  o.on_point = [&](const MotionProgress& p) {
    std::vector<double> q(6), v(6), acc(6);
    plan->motion.sample(p.t, q, v, acc);
    planned.push_back({std::chrono::duration<double>(p.elapsed).count(), q});
  };
  auto r = execute_motion(arm, plan->motion, o);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(r->stopped);
  double worst = 0;  // of |acceleration| / limit, over every joint and point
  for (std::size_t k = 1; k + 1 < planned.size(); ++k) {
    const double h0 = planned[k].first - planned[k - 1].first, h1 = planned[k + 1].first - planned[k].first;
    if (h0 < 1e-3 || h1 < 1e-3) continue;  // the final point goes out at the instant of the last
    for (std::size_t i = 0; i < 5; ++i) {
      const double acc = 2 * ((planned[k + 1].second[i] - planned[k].second[i]) / h1 -
                              (planned[k].second[i] - planned[k - 1].second[i]) / h0) / (h0 + h1);
      worst = std::max(worst, std::abs(acc) / arm.model().joints[i].limits.acceleration);
    }
  }
  RecordProperty("stop_acceleration_of_limit", std::to_string(worst));
  EXPECT_LT(worst, 1.0);  // the stop ramp stays within the joints' acceleration limits
  auto w = arm.wait();
  ASSERT_TRUE(w) << w.error().message;
  const Eigen::Vector3d end = true_tool();
  EXPECT_LT(to_line(end, start.position, seg.target.position), 0.002);
  EXPECT_GT((end - seg.target.position).norm(), 0.02);  // well short of the end
}

TEST_F(XarmMotion, BlendedCornersDoNotStop) {
  const auto from = here();
  const motion::Pose start = arm.forward(arm.chain_of(from));
  std::vector<motion::PathSegment> square;
  motion::Pose corner = start;
  for (Eigen::Vector3d step : {Eigen::Vector3d(0, 0.06, 0), Eigen::Vector3d(-0.05, 0, 0), Eigen::Vector3d(0, -0.06, 0)}) {
    square.push_back(lin_to(corner, step, 0.04, 0.01));
    corner = square.back().target;
  }
  square.back().zone = 0;
  auto plan = plan_path(arm.model(), from, square);
  ASSERT_TRUE(plan) << plan.error().message;
  EXPECT_EQ(plan->path->rests().size(), 1u);  // only the end
  // Along the plan, the tool never stops before the end and passes each inner corner
  // within the zone (10 mm), but not through it (the corner is cut).
  std::vector<double> p(6), v(6), a(6);
  double closest[2] = {1, 1};
  double slowest = 1;
  const Eigen::Vector3d corners[2] = {square[0].target.position, square[1].target.position};
  for (double t = 0.3; t < plan->motion.duration - 0.3; t += 0.005) {
    plan->motion.sample(t, p, v, a);
    const Eigen::Vector3d tool = arm.forward(arm.chain_of(p)).position;
    std::vector<double> ahead(p);
    for (std::size_t i = 0; i < 6; ++i) ahead[i] += v[i] * 1e-3;
    const double speed = (arm.forward(arm.chain_of(ahead)).position - tool).norm() / 1e-3;
    slowest = std::min(slowest, speed);
    for (int c = 0; c < 2; ++c) closest[c] = std::min(closest[c], (tool - corners[c]).norm());
  }
  EXPECT_GT(slowest, 0.01);  // m/s: never at rest between the ends
  for (double d : closest) {
    EXPECT_LT(d, 0.01);
    EXPECT_GT(d, 0.0005);
  }
  auto r = execute_motion(arm, plan->motion);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(r->completed);
}

TEST_F(XarmMotion, PathLeavingTheWorkspaceIsRefusedBeforeAnyByteIsSent) {
  const auto from = here();
  const motion::Pose start = arm.forward(arm.chain_of(from));
  const auto seg = lin_to(start, {0.5, 0, 0}, 0.04);
  const std::size_t before = link.sent.size();
  auto plan = plan_path(arm.model(), from, std::span(&seg, 1));
  ASSERT_FALSE(plan);
  EXPECT_NE(plan.error().message.find("segment 1"), std::string::npos) << plan.error().message;
  EXPECT_EQ(link.sent.size(), before);
}

// x=1e200 mm (move-to --linear) or 1e308 mm (a path file) made the planner read past its
// samples: such targets are refused before the path is built, naming the coordinate, its
// value and the arm's reach; nothing is sent.
TEST_F(XarmMotion, ATargetBeyondAnyReachIsRefusedBeforePlanning) {
  const auto from = here();
  const motion::Pose start = arm.forward(arm.chain_of(from));
  const std::string reach = fmt::format("arm 'xarm' reaches at most {:.0f} mm from its base", arm.model().reach * 1e3);
  const std::size_t before = link.sent.size();
  for (const auto& [x, shown] : std::vector<std::pair<double, std::string>>{{1e197, "1e+200"}, {1e305, "1e+308"},
                                                                           {-1e305, "-1e+308"}}) {
    motion::PathSegment seg = lin_to(start, {0, 0, 0}, 0.04);
    seg.target.position.x() = x;
    auto plan = plan_path(arm.model(), from, std::span(&seg, 1));
    ASSERT_FALSE(plan);
    EXPECT_EQ(plan.error().message, fmt::format("segment 1 (LIN): target: x {} mm is beyond reach: {}", shown, reach));
    ASSERT_NE(motion::path_refusal_of(plan.error()), nullptr);
    EXPECT_EQ(motion::path_refusal_of(plan.error())->segment, 0);
    seg.kind = motion::SegmentKind::circ;
    seg.target.position.x() = start.position.x();
    seg.via = start.position + Eigen::Vector3d(0, 0, x);
    plan = plan_path(arm.model(), from, std::span(&seg, 1));
    ASSERT_FALSE(plan);
    EXPECT_EQ(plan.error().message,
              fmt::format("segment 1 (CIRC): via point: z {} mm is beyond reach: {}", shown, reach));
  }
  EXPECT_EQ(link.sent.size(), before);
  // The same rule for a joint move to a tool pose.
  CartesianGoal goal;
  goal.position = {0.1, 1e197, 0.1};
  EXPECT_EQ(arm.inverse(goal, arm.read().value()).error().message,
            "the tool target: y 1e+200 mm is beyond reach: " + reach);
}

// From the xArm's start pose (every servo centred, straight up), the README's Python lines:
// move_to(150, 50, 120 mm), then a line to (180, 40, 100 mm). The pitch of a position alone
// is the middle of the widest run of pitches that reach (there 15..70 deg), not the nearest
// to the start's -90 deg (then -103 deg, servo5 at its limit, in a run 4 deg wide), from
// which the line left the reach at 20 %. The same line from straight up is refused saying
// to move away with a joint move first.
TEST(XarmFreePitch, APositionAloneTakesRoomyPitchSoTheReadmeLinePlans) {
  robot_commands::testing::EmulatedLink link;
  robot_commands::Client client{link};
  const Arm arm{testing::shipped("xarm"), std::make_unique<RcArmDevice>(testing::shipped("xarm"), client)};
  JointState straight_up;
  straight_up.positions.assign(arm.model().joints.size(), 0.0);
  CartesianGoal goal;
  goal.position = {0.15, 0.05, 0.12};
  auto solutions = arm.inverse(goal, straight_up);
  ASSERT_TRUE(solutions.ok()) << solutions.error().message;
  const motion::JointVector q = solutions->front().joints;
  EXPECT_NEAR(arm.tool_rpy(arm.forward(q), q).pitch / kDeg, 42.5, 1.0);

  std::vector<double> there = straight_up.positions;
  for (int i = 0; i < q.size(); ++i) there[std::size_t(i)] = q[i];
  CartesianMove line;
  line.goal.position = {0.18, 0.04, 0.10};
  line.speed = 0.04;
  const std::vector<CartesianMove> moves{line};
  auto plan = plan_path(arm.model(), there, path_segments(*arm.kinematics(), there, moves));
  ASSERT_TRUE(plan.ok()) << plan.error().message;
  EXPECT_TRUE(plan->checked->slowed.empty());
  EXPECT_LT(plan->motion.duration, 1.5);  // 40 mm at 40 mm/s, and the ramps

  auto refused = plan_path(arm.model(), straight_up.positions, path_segments(*arm.kinematics(), straight_up.positions, moves));
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().message.find("the path starts at a singularity (arm stretched or folded)"),
            std::string::npos)
      << refused.error().message;
  EXPECT_NE(refused.error().message.find("move the arm away from it first with a joint move"), std::string::npos)
      << refused.error().message;
}

// The reach is an upper bound of where the tool can be, and not a loose one.
TEST(ArmReach, BoundsTheToolOfBothArms) {
  for (const char* name : {"xarm", "scara"}) {
    const ArmModel m = testing::shipped(name);
    double farthest = 0;
    std::uint64_t state = 12345;
    auto uniform = [&] {  // a fixed LCG: the same joints every run
      state = state * 6364136223846793005ull + 1442695040888963407ull;
      return double(state >> 11) / double(1ull << 53);
    };
    for (int k = 0; k < 20000; ++k) {
      motion::JointVector q(m.chain_joints());
      for (int i = 0; i < q.size(); ++i) {
        const JointLimits& l = m.joints[std::size_t(i)].limits;
        q[i] = l.lower + (l.upper - l.lower) * uniform();
      }
      const motion::Pose flange = m.kinematics->forward(q);
      farthest = std::max(farthest, (flange.position + flange.orientation * m.tool.position).norm());
    }
    EXPECT_LE(farthest, m.reach) << name;
    EXPECT_GT(farthest, 0.7 * m.reach) << name << ": reach " << m.reach << " m, farthest seen " << farthest << " m";
  }
}

class ScaraMotion : public ::testing::Test {
 protected:
  std::unique_ptr<joint_sim::SimArm> sim = test::make_arm(115200);
  joint_bus::BusMaster master{sim->link()};
  Arm arm{testing::shipped("scara"),
          std::make_unique<BusArmDevice>(testing::shipped("scara"), master, sim->link(), "simulated SCARA")};

  void SetUp() override {
    ASSERT_TRUE(arm.move_joints({0.15, 0.3, -0.8, 0.0, 0.0, 0.0, std::nullopt}));
    ASSERT_TRUE(arm.wait());
  }
  std::vector<double> here() { return arm.read().value().positions; }
  Eigen::Vector3d true_tool() {
    std::vector<double> device;
    for (const auto& j : arm.model().joints) device.push_back(sim->joint(j.map(Protocol::joint_bus)->id).controller().position());
    return arm.forward(arm.chain_of(arm.model().from_device(Protocol::joint_bus, device))).position;
  }
};

TEST_F(ScaraMotion, LinKeepsTheToolOnTheLine) {
  const auto from = here();
  const motion::Pose start = arm.forward(arm.chain_of(from));
  const auto seg = lin_to(start, {0, 0.1, 0}, 0.1);
  auto plan = plan_path(arm.model(), from, std::span(&seg, 1));
  ASSERT_TRUE(plan) << plan.error().message;
  double worst = 0;
  ExecutorOptions o;
  o.on_point = [&](const MotionProgress&) {
    worst = std::max(worst, to_line(true_tool(), start.position, seg.target.position));
  };
  auto r = execute_motion(arm, plan->motion, o);
  ASSERT_TRUE(r) << r.error().message;
  ASSERT_TRUE(arm.wait());
  EXPECT_LT(worst, 0.003);
  EXPECT_LT((true_tool() - seg.target.position).norm(), 0.001);
}

TEST_F(ScaraMotion, StopMidLineComesToRestOnTheLine) {
  const auto from = here();
  const motion::Pose start = arm.forward(arm.chain_of(from));
  const auto seg = lin_to(start, {0, 0.1, 0}, 0.1);
  auto plan = plan_path(arm.model(), from, std::span(&seg, 1));
  ASSERT_TRUE(plan) << plan.error().message;
  ExecutorOptions o;
  o.command = [](const MotionProgress& p) { return p.t > 0.5 ? MotionCommand::stop : MotionCommand::none; };
  auto r = execute_motion(arm, plan->motion, o);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(r->stopped);
  ASSERT_TRUE(arm.wait());
  const Eigen::Vector3d end = true_tool();
  EXPECT_LT(to_line(end, start.position, seg.target.position), 0.003);
  EXPECT_GT((end - seg.target.position).norm(), 0.02);
}

}  // namespace
}  // namespace armctl::arm

namespace armctl::arm {
namespace {

// The SCARA through armctl's arm controller: the stream is MultiServoMoves of the
// controller's 0..1000 units per joint (1.42 deg each on SHOULDER), which the controller
// turns into synchronized joint moves from a moving start.
TEST(ControllerMotion, LinThroughTheArmControllerStaysWithinItsResolution) {
  arm_controller::testing::Rig rig;
  const ArmModel model = testing::shipped("scara");
  Arm arm{model, std::make_unique<RcArmDevice>(model, *rig.client)};
  ASSERT_TRUE(arm.move_joints({0.15, 0.3, -0.8, 0.0, 0.0, 0.0, std::nullopt}));
  { auto w = arm.wait(); ASSERT_TRUE(w) << w.error().message; }
  auto true_tool = [&] {
    std::vector<double> device;
    for (const auto& j : model.joints) device.push_back(rig.clicks(j.map(Protocol::joint_bus)->id));
    return arm.forward(arm.chain_of(model.from_device(Protocol::joint_bus, device))).position;
  };
  const auto from = arm.read().value().positions;
  const motion::Pose start = arm.forward(arm.chain_of(from));
  const auto seg = lin_to(start, {0, 0.1, 0}, 0.05);
  auto plan = plan_path(model, from, std::span(&seg, 1));
  ASSERT_TRUE(plan) << plan.error().message;
  double worst = 0;
  ExecutorOptions o;
  o.on_point = [&](const MotionProgress&) {
    worst = std::max(worst, to_line(true_tool(), start.position, seg.target.position));
  };
  auto r = execute_motion(arm, plan->motion, o);
  ASSERT_TRUE(r) << r.error().message;
  auto w = arm.wait();
  ASSERT_TRUE(w) << w.error().message;
  // Twice the quantization limit (half a controller unit on every joint, mid-path).
  std::vector<double> middle = from;
  const motion::JointVector& mid = plan->checked->joints[plan->checked->joints.size() / 2];
  for (int i = 0; i < mid.size(); ++i) middle[std::size_t(i)] = mid[i];
  const double limit = 2 * tool_quantization(model, Protocol::robot_commands, middle);
  std::printf("through the arm controller: %zu points every %.1f ms, largest distance from the line %.2f mm, end "
              "%.2f mm, twice the quantization limit %.2f mm\n",
              r->points, std::chrono::duration<double, std::milli>(r->period).count(), worst * 1e3,
              (true_tool() - seg.target.position).norm() * 1e3, limit * 1e3);
  EXPECT_LT(worst, limit);
  EXPECT_LT((true_tool() - seg.target.position).norm(), limit);
}

}  // namespace
}  // namespace armctl::arm
