// The servo mode (arm/run_servo.hpp) on both simulated arms, on simulated time: a twist moves
// the tool along a line, joint velocities and targets, the gripper, commands that stop
// coming, the ends of the joints' ranges, a singularity, a box in the scene, the fence, a
// joint that is held, and bad commands.
#include "arm/run_servo.hpp"
#include "arm/servo_twist.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "arm/arm.hpp"
#include "arm/bus_arm_device.hpp"
#include "arm/rc_arm_device.hpp"
#include "arm_files.hpp"
#include "joint_bus/sim_fixture.hpp"
#include "robot_commands/sim_links.hpp"
#include "scene/collision_world.hpp"
#include "scene/scene.hpp"

namespace armctl::arm {
namespace {

constexpr double kDeg = std::numbers::pi / 180;
using std::chrono::milliseconds;

double seconds(Duration d) { return std::chrono::duration<double>(d).count(); }

ServoCommand twist(Eigen::Vector3d linear_mm_s, ServoFrame frame = ServoFrame::base,
                   Eigen::Vector3d angular_deg_s = Eigen::Vector3d::Zero()) {
  return ServoCommand{ToolTwist{linear_mm_s / 1000, angular_deg_s * kDeg, frame}, std::nullopt};
}

// A script on the servo loop's clock: `command` is sent (renewed at every cycle, as a held
// key or a stick does) from `from` to `until` s after the start; at `end` s the input finishes.
struct Script {
  Script(ServoInput& in, ServoCommand c, double from_s, double until_s, double end_s)
      : input(in), command(std::move(c)), from(from_s), until(until_s), end(end_s) {}
  ServoInput& input;
  ServoCommand command;
  double from, until, end;
  bool renew = true;
  std::optional<TimePoint> start;
  bool sent = false;
  void operator()(TimePoint now) {
    if (!start) start = now;
    const double t = seconds(now - *start);
    if (t >= from && t < until && (renew || !sent)) {
      ASSERT_TRUE(input.send(command));
      sent = true;
    }
    if (t >= end) input.finish();
  }
};

// Every point the loop sends, and how often each slowdown was reported.
struct Trace {
  std::vector<std::vector<double>> points;
  std::vector<ServoStatus> statuses;
  void operator()(const ServoStatus& s) {
    points.push_back(s.positions);
    statuses.push_back(s);
  }
  bool reported(ServoSlowdown why, const std::string& detail_part = "") const {
    for (const auto& s : statuses)
      if (s.slowdown == why && s.detail.find(detail_part) != std::string::npos) return true;
    return false;
  }
};

class XarmServo : public ::testing::Test {
 protected:
  void SetUp() override {
    // A pose in the middle of the workspace.
    std::vector<std::optional<double>> q{0.0, 30 * kDeg, 60 * kDeg, 60 * kDeg, 0.0, std::nullopt};
    auto moved = arm.move_joints(q);
    ASSERT_TRUE(moved) << moved.error().message;
    ASSERT_TRUE(arm.wait());
  }
  robot_commands::testing::EmulatedLink link{115200};
  robot_commands::Client client{link};
  Arm arm{testing::shipped("xarm"), std::make_unique<RcArmDevice>(testing::shipped("xarm"), client)};
  ServoInput input{arm.model()};
  Trace trace;

  Eigen::Vector3d tool_mm() { return arm.pose().value().position * 1000; }
  // A fence whose +y face is at `y_mm`, reaching far every other way.
  void fence_at_y(double y_mm) {
    auto sc = scene::parse_scene(fmt::format(R"({{"fence": {{"min": [-800, -800, -100], "max": [800, {:.1f}, 800]}}}})", y_mm),
                                 "test scene");
    ASSERT_TRUE(sc) << sc.error().message;
    ASSERT_TRUE(arm.set_scene(*sc));
  }
  Result<ServoReport> run(Script script, ServoOptions o = {}) {
    o.before_cycle = std::ref(script);
    o.on_cycle = std::ref(trace);
    return run_servo(arm, input, o);
  }
};

TEST_F(XarmServo, ATwistMovesTheToolAlongALineAndStopsWhenTheInputEnds) {
  const Eigen::Vector3d before = tool_mm();
  auto r = run(Script(input, twist({-30, 0, 0}), 0, 1.0, 1.0));
  ASSERT_TRUE(r) << r.error().message;
  ASSERT_TRUE(arm.wait());
  const Eigen::Vector3d moved = tool_mm() - before;
  // 30 mm/s for 1 s, the jerk-limited stop adding about as much as the start takes.
  EXPECT_NEAR(moved.x(), -30, 3);
  EXPECT_LT(std::abs(moved.y()), 1.0);
  EXPECT_LT(std::abs(moved.z()), 1.0);
  EXPECT_GT(r->commands, 30u);
  EXPECT_GE(r->reads, 4u);
  EXPECT_LT(r->largest_following_error, 2 * kDeg);
  // Every point sent lies within the joints' limits, and steps no further than the velocity
  // limits allow in one period.
  const auto& model = arm.model();
  const double dt = seconds(r->period);
  for (std::size_t k = 1; k < trace.points.size(); ++k)
    for (std::size_t i = 0; i < trace.points[k].size(); ++i) {
      EXPECT_TRUE(model.joints[i].limits.contains(trace.points[k][i], 1e-9));
      ASSERT_LE(std::abs(trace.points[k][i] - trace.points[k - 1][i]), model.joints[i].limits.velocity * dt * 1.000001);
    }
}

// The xArm's line is full duplex: a read-back's request goes out after one cycle's point and
// its reply is taken after the next one's, so a cycle with a read-back lasts one point and
// the request (not the whole read), and no reply is left over.
TEST_F(XarmServo, AReadBackHoldsTheLineOnlyForItsRequest) {
  std::vector<TimePoint> cycles;
  Script script(input, twist({0, 20, 0}), 0, 0.5, 0.5);
  ServoOptions o;
  o.executor.read_interval = milliseconds(20);
  o.before_cycle = [&](TimePoint now) {
    cycles.push_back(now);
    script(now);
  };
  o.on_cycle = std::ref(trace);
  const std::size_t stale_before = client.stats().stale_replies;
  auto r = run_servo(arm, input, o);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_GE(r->reads, 20u);
  EXPECT_LT(r->largest_following_error, 2 * kDeg);
  auto& device = arm.device();
  const Duration request = *device.read_request_time();
  const Duration whole_read = device.stream_period(true) - device.stream_period(false);
  ASSERT_LT(request + milliseconds(1), whole_read);  // what the test tells apart
  Duration longest{0};
  for (std::size_t k = 1; k < cycles.size(); ++k) longest = std::max(longest, cycles[k] - cycles[k - 1]);
  EXPECT_GT(longest, r->period);  // the cycles with a request
  EXPECT_LE(longest, r->period + request + std::chrono::microseconds(10));
  EXPECT_FALSE(client.position_request_pending());
  EXPECT_EQ(client.stats().stale_replies, stale_before);
}

TEST_F(XarmServo, ATwistInTheToolFrameFollowsTheToolsAxes) {
  const Eigen::Vector3d before = tool_mm();
  const Eigen::Vector3d tool_z = arm.pose().value().orientation * Eigen::Vector3d::UnitZ();
  auto r = run(Script(input, twist({0, 0, 15}, ServoFrame::tool), 0, 1.0, 1.0));
  ASSERT_TRUE(r) << r.error().message;
  ASSERT_TRUE(arm.wait());
  EXPECT_FALSE(trace.reported(ServoSlowdown::joint_limit));
  const Eigen::Vector3d moved = tool_mm() - before;
  EXPECT_NEAR(moved.dot(tool_z), 15, 1.5);
  EXPECT_LT((moved - moved.dot(tool_z) * tool_z).norm(), 1.5);
}

TEST_F(XarmServo, CommandsThatStopComingBringTheArmToRestAfterTheTimeout) {
  const Eigen::Vector3d before = tool_mm();
  Script once(input, twist({0, 50, 0}), 0, 1.0, 2.0);
  once.renew = false;  // sent once, never renewed: a dead host
  auto r = run(once);
  ASSERT_TRUE(r) << r.error().message;
  ASSERT_TRUE(arm.wait());
  // 200 ms of motion at most (with the start), and the stop after it.
  const double moved = (tool_mm() - before).norm();
  EXPECT_GT(moved, 2);
  EXPECT_LT(moved, 50 * 0.3);
  EXPECT_GT(r->slowed[std::size_t(ServoSlowdown::command_timeout)], 0u);
  EXPECT_TRUE(trace.statuses.back().at_rest);
}

TEST_F(XarmServo, AJointDrivenToTheEndOfItsRangeStopsThereAndReportsIt) {
  std::vector<double> v(std::size_t(arm.model().joint_count()), 0.0);
  v[0] = 2.0;  // the base, at its velocity limit toward its upper end
  auto r = run(Script(input, ServoCommand{JointVelocities{v}, std::nullopt}, 0, 6, 6));
  ASSERT_TRUE(r) << r.error().message;
  const double upper = arm.model().joints[0].limits.upper;
  for (const auto& p : trace.points) ASSERT_LE(p[0], upper + 1e-9);
  EXPECT_NEAR(trace.points.back()[0], upper, 0.5 * kDeg);
  EXPECT_TRUE(trace.reported(ServoSlowdown::joint_limit, arm.model().joints[0].name));
  ASSERT_TRUE(arm.wait());
}

TEST_F(XarmServo, AJointTargetAndThePoseTargetAreReachedAndHeld) {
  CartesianGoal goal;
  goal.position = Eigen::Vector3d(0.16, 0.08, 0.1);
  auto r = run(Script(input, ServoCommand{PoseTarget{goal}, 1.0}, 0, 3, 3));
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_FALSE(trace.reported(ServoSlowdown::unreachable));
  ASSERT_TRUE(arm.wait());
  EXPECT_LT((tool_mm() - Eigen::Vector3d(160, 80, 100)).norm(), 1.5);
  // The gripper went to its target (closed) with the pose.
  const int g = arm.model().gripper->joint;
  EXPECT_NEAR(arm.read().value().positions[std::size_t(g)], arm.model().gripper->at(1.0), 1 * kDeg);
}

TEST_F(XarmServo, AnUnreachablePoseTargetHoldsTheArmAndSaysWhy) {
  CartesianGoal goal;
  goal.position = Eigen::Vector3d(0.9, 0, 0.1);
  const auto before = arm.read().value().positions;
  auto r = run(Script(input, ServoCommand{PoseTarget{goal}, std::nullopt}, 0, 0.5, 0.5));
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(trace.reported(ServoSlowdown::unreachable, "beyond reach"));
  const auto after = arm.read().value().positions;
  for (std::size_t i = 0; i < before.size(); ++i) EXPECT_NEAR(after[i], before[i], 0.5 * kDeg);
}

TEST_F(XarmServo, TowardTheStretchedArmItSlowsDownInsteadOfSpeedingTheJointsUp) {
  // Straight out along x until the arm is stretched: the twist is slowed near the
  // singularity, no joint goes beyond its limits, nothing falls behind.
  auto r = run(Script(input, twist({150, 0, 0}), 0, 4, 4));
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(trace.reported(ServoSlowdown::singularity));
  EXPECT_LT(r->largest_following_error, 3 * kDeg);
  ASSERT_TRUE(arm.wait());
}

TEST_F(XarmServo, ABoxInTheSceneSlowsTheToolDownAndStopsItBeforeContact) {
  // A box 30 mm in front of the tool's path along +y.
  const Eigen::Vector3d at = tool_mm();
  auto sc = scene::parse_scene(fmt::format(R"({{"objects": [{{"name": "feeder", "box": [80, 40, 200],
      "at": [{:.1f}, {:.1f}, 100]}}]}})",
                                           at.x(), at.y() + 70),
                               "test scene");
  ASSERT_TRUE(sc) << sc.error().message;
  ASSERT_TRUE(arm.set_scene(*sc));
  auto r = run(Script(input, twist({0, 40, 0}), 0, 3, 3));
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(trace.reported(ServoSlowdown::collision, "feeder"));
  const auto world = arm.kinematics()->collisions();
  for (const auto& p : trace.points) ASSERT_FALSE(world->collides(p));
  ASSERT_TRUE(arm.wait());
  const double moved = tool_mm().y() - at.y();
  EXPECT_GT(moved, 5);
  EXPECT_LT(moved, 70);
}

TEST_F(XarmServo, TheFenceSlowsTheToolDownAndStopsItInside) {
  // The fence's face 40 mm along +y from the tool: the tool slows toward it and comes to rest
  // inside, never beyond (docs/scene.md "Fence and reduced mode").
  const Eigen::Vector3d at = tool_mm();
  fence_at_y(at.y() + 40);
  auto r = run(Script(input, twist({0, 40, 0}), 0, 3, 3));
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(trace.reported(ServoSlowdown::collision, "the fence"));
  const auto k = arm.kinematics();
  for (const auto& p : trace.points) ASSERT_LE(k->pose_at(p).position.y() * 1000, at.y() + 40);
  ASSERT_TRUE(arm.wait());
  const double moved = tool_mm().y() - at.y();
  EXPECT_GT(moved, 20);
  EXPECT_LT(moved, 40.5);
}

// The fence switched on with the tool 10 mm beyond its +y face: a twist further out is held
// where the arm stands (it never goes further beyond), a twist back in moves the tool in.
TEST_F(XarmServo, StartedBeyondTheFenceItComesBackButGoesNoFurther) {
  const Eigen::Vector3d at = tool_mm();
  fence_at_y(at.y() - 10);
  auto out = run(Script(input, twist({0, 30, 0}), 0, 1, 1));
  ASSERT_TRUE(out) << out.error().message;
  EXPECT_TRUE(trace.reported(ServoSlowdown::collision, "further beyond"));
  const auto k = arm.kinematics();
  for (const auto& p : trace.points) ASSERT_LE(k->pose_at(p).position.y() * 1000, at.y() + 0.01);
  ServoInput back_input{arm.model()};
  trace = {};
  ServoOptions o;
  Script back(back_input, twist({0, -30, 0}), 0, 1, 1);
  o.before_cycle = std::ref(back);
  o.on_cycle = std::ref(trace);
  auto in = run_servo(arm, back_input, o);
  ASSERT_TRUE(in) << in.error().message;
  ASSERT_TRUE(arm.wait());
  EXPECT_LT(tool_mm().y(), at.y() - 15);  // back inside the fence
}

// The tool point's fastest speed between consecutive points sent (mm/s).
double fastest_tool_speed(const ArmKinematics& k, const Trace& trace) {
  double fastest = 0;
  for (std::size_t c = 1; c < trace.points.size(); ++c) {
    const double dt = seconds(trace.statuses[c].elapsed - trace.statuses[c - 1].elapsed);
    const double d = (k.pose_at(trace.points[c]).position - k.pose_at(trace.points[c - 1]).position).norm();
    if (dt > 0) fastest = std::max(fastest, d / dt * 1000);
  }
  return fastest;
}

TEST_F(XarmServo, InReducedModeJointAndPoseTargetsKeepTheToolUnderItsSpeedCap) {
  // The same far joint target first without the cap (the tool goes much faster than 20 mm/s,
  // so the check below can fail), then with it; then a pose target with it. Every target is
  // still reached (docs/scene.md "Fence and reduced mode").
  std::vector<std::optional<double>> far{60 * kDeg, 10 * kDeg, 80 * kDeg, 40 * kDeg, std::nullopt, std::nullopt};
  // Each run on an input of its own (a finished input stays finished).
  const auto run_for = [&](ServoCommand command, double seconds_to_run) {
    trace = {};
    ServoInput fresh{arm.model()};
    Script script(fresh, std::move(command), 0, seconds_to_run, seconds_to_run);
    ServoOptions o;
    o.before_cycle = std::ref(script);
    o.on_cycle = std::ref(trace);
    return run_servo(arm, fresh, o);
  };
  const auto there = [&](double seconds_to_run) {
    return run_for(ServoCommand{JointTargets{far}, std::nullopt}, seconds_to_run);
  };
  ASSERT_TRUE(there(4));
  const auto k = arm.kinematics();
  EXPECT_GT(fastest_tool_speed(*k, trace), 60);
  ASSERT_TRUE(arm.move_joints({0.0, 30 * kDeg, 60 * kDeg, 60 * kDeg, 0.0, std::nullopt}));
  ASSERT_TRUE(arm.wait());

  ASSERT_TRUE(arm.set_scene(scene::parse_scene(R"({"reduced": {"tool_speed": 20}})", "scene").value()));
  auto r = there(20);
  ASSERT_TRUE(r) << r.error().message;
  const auto reduced = arm.kinematics();
  const double capped = fastest_tool_speed(*reduced, trace);
  double arrived = NAN;
  for (const auto& st : trace.statuses) {
    bool there_now = true;
    for (std::size_t i = 0; i < 4; ++i) there_now = there_now && std::abs(st.positions[i] - *far[i]) < 0.5 * kDeg;
    if (there_now) {
      arrived = seconds(st.elapsed);
      break;
    }
  }
  std::printf("joint target: the tool at most %.1f mm/s under the 20 mm/s cap, there in %.1f s\n", capped, arrived);
  EXPECT_LE(capped, 20.0);
  EXPECT_TRUE(trace.reported(ServoSlowdown::joint_limit, "reduced mode's 20.0 mm/s"));
  ASSERT_TRUE(arm.wait());
  const auto at = arm.read().value().positions;
  for (std::size_t i = 0; i < 4; ++i) EXPECT_NEAR(at[i], *far[i], 0.5 * kDeg) << "joint " << i;

  CartesianGoal goal;
  goal.position = Eigen::Vector3d(0.16, 0.08, 0.1);
  auto p = run_for(ServoCommand{PoseTarget{goal}, std::nullopt}, 20);
  ASSERT_TRUE(p) << p.error().message;
  EXPECT_LE(fastest_tool_speed(*reduced, trace), 20.0);
  ASSERT_TRUE(arm.wait());
  EXPECT_LT((tool_mm() - Eigen::Vector3d(160, 80, 100)).norm(), 1.5);
}

TEST_F(XarmServo, BadCommandsAreRefusedAndTheLastOneStays) {
  ServoCommand nan = twist({NAN, 0, 0});
  auto e = input.send(nan);
  ASSERT_FALSE(e);
  EXPECT_NE(e.error().message.find("finite"), std::string::npos);
  EXPECT_FALSE(input.send(ServoCommand{JointVelocities{{1, 2}}, std::nullopt}));
  auto g = input.send(ServoCommand{ToolTwist{}, 1.5});
  ASSERT_FALSE(g);
  EXPECT_NE(g.error().message.find("0 (open) to 1 (closed)"), std::string::npos);
  EXPECT_EQ(input.take(0).sequence, 0u);
  ServoOptions o;
  o.speed = 0;
  input.finish();
  EXPECT_FALSE(run_servo(arm, input, o));
}

// The tool point's Jacobian against finite differences of the forward kinematics, both arms.
TEST(ServoTwist, TheToolJacobianIsTheDerivativeOfTheToolPose) {
  for (const char* name : {"xarm", "scara"}) {
    const ArmKinematics k(testing::shipped(name));
    motion::JointVector q(k.model().chain_joints());
    for (int i = 0; i < q.size(); ++i) q[i] = 0.3 + 0.1 * i;
    const motion::Jacobian j = tool_jacobian(k, q);
    const motion::Pose p0 = k.forward(q);
    for (int c = 0; c < q.size(); ++c) {
      motion::JointVector dq = q;
      dq[c] += 1e-7;
      const motion::Pose p1 = k.forward(dq);
      const Eigen::Vector3d v = (p1.position - p0.position) / 1e-7;
      const Eigen::AngleAxisd w(p1.orientation * p0.orientation.inverse());
      const Eigen::Vector3d omega = w.axis() * w.angle() / 1e-7;
      for (int r = 0; r < 3; ++r) {
        EXPECT_NEAR(j(r, c), v[r], 1e-5) << name << " column " << c << " row " << r;
        EXPECT_NEAR(j(r + 3, c), omega[r], 1e-5) << name << " column " << c << " row " << r + 3;
      }
    }
  }
}

// The simulated SCARA on its joint bus, as it starts: stretched out along x.
class SimulatedScara : public ::testing::Test {
 protected:
  std::unique_ptr<joint_sim::SimArm> sim = test::make_arm(115200);
  joint_bus::BusMaster master{sim->link()};
  Arm arm{testing::shipped("scara"),
          std::make_unique<BusArmDevice>(testing::shipped("scara"), master, sim->link(), "simulated SCARA")};
  ServoInput input{arm.model()};
  Trace trace;
  Result<ServoReport> run(Script script, ServoOptions o = {}) {
    o.before_cycle = std::ref(script);
    o.on_cycle = std::ref(trace);
    return run_servo(arm, input, o);
  }
  Eigen::Vector3d tool_mm() { return arm.pose().value().position * 1000; }
};

class ScaraServo : public SimulatedScara {
 protected:
  // The simulated arm starts stretched out (a singularity): first to a bent elbow, through
  // the servo mode's joint targets.
  void SetUp() override {
    std::vector<std::optional<double>> bent(std::size_t(arm.model().joint_count()));
    bent[0] = 0.15;       // Z
    bent[2] = 60 * kDeg;  // UAE
    ServoInput first(arm.model());
    ServoOptions o;
    o.before_cycle = [&](TimePoint) {
      // Renewed every cycle (targets are a stream too) until the arm rests there.
      if (trace.statuses.size() > 5 && trace.statuses.back().at_rest) first.finish();
      else ASSERT_TRUE(first.send(ServoCommand{JointTargets{bent}, std::nullopt}));
    };
    o.on_cycle = std::ref(trace);
    auto r = run_servo(arm, first, o);
    ASSERT_TRUE(r) << r.error().message;
    ASSERT_TRUE(arm.wait());
    const auto at = arm.read().value().positions;
    EXPECT_NEAR(at[0], 0.15, 0.5e-3);
    EXPECT_NEAR(at[2], 60 * kDeg, 0.5 * kDeg);
    trace = {};
  }
};

// The simulated SCARA starts stretched out along x: the tool cannot move outward there, and
// the status says so instead of nothing moving for no reason.
TEST_F(SimulatedScara, ATwistOutwardAtFullStretchIsReportedAsASingularity) {
  const Eigen::Vector3d before = arm.pose().value().position;
  const Eigen::Vector3d outward = Eigen::Vector3d(before.x(), before.y(), 0).normalized();
  auto r = run(Script(input, twist(outward * 20), 0, 0.5, 0.5));
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(trace.reported(ServoSlowdown::singularity, "cannot move that way"));
  EXPECT_LT((arm.pose().value().position - before).dot(outward), 0.001);
}

TEST_F(ScaraServo, ATwistMovesTheToolAlongALineAtItsOrientation) {
  const Eigen::Vector3d before = tool_mm();
  const auto rpy_before = motion::to_rpy(arm.pose().value().orientation);
  auto r = run(Script(input, twist({0, 30, -20}), 0, 1.0, 1.0));
  ASSERT_TRUE(r) << r.error().message;
  ASSERT_TRUE(arm.wait());
  const Eigen::Vector3d moved = tool_mm() - before;
  EXPECT_NEAR(moved.y(), 30, 3);
  EXPECT_NEAR(moved.z(), -20, 2);
  EXPECT_LT(std::abs(moved.x()), 1.5);
  const auto rpy_after = motion::to_rpy(arm.pose().value().orientation);
  EXPECT_NEAR(rpy_after.yaw, rpy_before.yaw, 1 * kDeg);
  EXPECT_LT(r->largest_following_error, 3 * kDeg);
}

TEST_F(ScaraServo, AJointHeldByAnObstacleHaltsTheArmWithAFollowingError) {
  auto& hw = sim->joint(2).hardware();
  const auto at = static_cast<std::int32_t>(hw.position_clicks());
  hw.set_end_stops({at - 5, at + 5});
  std::vector<double> v(std::size_t(arm.model().joint_count()), 0.0);
  v[1] = 0.5;  // SHOULDER (joint-bus joint 2)
  auto r = run(Script(input, ServoCommand{JointVelocities{v}, std::nullopt}, 0, 3, 3));
  ASSERT_FALSE(r);
  const auto* f = following_error_of(r.error());
  ASSERT_NE(f, nullptr) << r.error().message;
  EXPECT_EQ(f->joint, 1);
}

// The SCARA's device, passed through, counting its reads: whole, and one joint at a time.
class CountedReads final : public ArmDevice {
 public:
  explicit CountedReads(std::unique_ptr<ArmDevice> inner) : inner_(std::move(inner)) {}
  Protocol protocol() const override { return inner_->protocol(); }
  std::string description() const override { return inner_->description(); }
  const Clock& clock() const override { return inner_->clock(); }
  Duration poll_interval() const override { return inner_->poll_interval(); }
  Result<std::vector<double>> read_positions() override {
    ++whole;
    return inner_->read_positions();
  }
  std::optional<Duration> joint_read_time() const override { return inner_->joint_read_time(); }
  Result<double> read_joint(int joint) override {
    ++joints;
    return inner_->read_joint(joint);
  }
  Status move(const std::vector<std::optional<double>>& t, Duration d) override { return inner_->move(t, d); }
  Status stop() override { return inner_->stop(); }
  Status set_torque(bool on) override { return inner_->set_torque(on); }
  Status release(int joint) override { return inner_->release(joint); }
  Duration stream_period(bool with_read) const override { return inner_->stream_period(with_read); }
  Duration stream_latency() const override { return inner_->stream_latency(); }
  Status stream(const std::vector<double>& q, const std::vector<double>& v, Duration in) override {
    return inner_->stream(q, v, in);
  }
  Status idle(Duration d) override { return inner_->idle(d); }
  int whole = 0, joints = 0;

 private:
  std::unique_ptr<ArmDevice> inner_;
};

// The joint bus is half duplex, and each joint is read in a transaction of its own: the
// servo mode reads the arm back one joint after each point, so that no point waits behind a
// read of all seven; every seventh joint read completes a reading that is checked.
TEST_F(SimulatedScara, AReadBackTakesOneJointAfterEachPoint) {
  auto counted = std::make_unique<CountedReads>(
      std::make_unique<BusArmDevice>(testing::shipped("scara"), master, sim->link(), "simulated SCARA"));
  CountedReads& device = *counted;
  Arm scara(testing::shipped("scara"), std::move(counted));
  ServoInput in{scara.model()};
  std::vector<double> v(std::size_t(scara.model().joint_count()), 0.0);
  v[0] = -0.02;  // Z down, 20 mm/s
  v[2] = 0.3;    // UAE
  Script script(in, ServoCommand{JointVelocities{v}, std::nullopt}, 0, 0.6, 0.6);
  int most_in_a_cycle = 0, at_cycle = 0, whole_at_start = -1;
  std::size_t readings = 0;
  ServoOptions o;
  o.before_cycle = [&](TimePoint now) {
    if (whole_at_start < 0) whole_at_start = device.whole;  // after the start's read
    most_in_a_cycle = std::max(most_in_a_cycle, device.joints - at_cycle);
    at_cycle = device.joints;
    script(now);
  };
  o.executor.on_read = [&](const JointState& s) {
    ++readings;
    EXPECT_EQ(s.positions.size(), v.size());
  };
  auto r = run_servo(scara, in, o);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_EQ(device.whole, whole_at_start) << "no read of every joint at once while servoing";
  EXPECT_EQ(most_in_a_cycle, 1);
  EXPECT_GE(r->reads, 3u);
  EXPECT_EQ(readings, r->reads);
  EXPECT_GE(device.joints, int(r->reads) * 7);
  EXPECT_LT(device.joints, int(r->reads + 1) * 7);
  EXPECT_LT(r->largest_following_error, 3 * kDeg);
}

// Stall protection in the servo mode: a joint held by something no scene knows, driven
// slowly enough that it never falls 5 degrees behind, is stopped and released after 0.5 s of
// standing still, and the error names it.
TEST_F(ScaraServo, ASlowlyDrivenJointHeldByAnObstacleIsFoundStalledAndReleased) {
  auto& hw = sim->joint(2).hardware();
  const auto at = static_cast<std::int32_t>(hw.position_clicks());
  hw.set_end_stops({at - 5, at + 5});
  std::vector<double> v(std::size_t(arm.model().joint_count()), 0.0);
  v[1] = 0.05;  // SHOULDER (joint-bus joint 2), 3 degrees a second
  auto r = run(Script(input, ServoCommand{JointVelocities{v}, std::nullopt}, 0, 5, 5));
  ASSERT_FALSE(r);
  const auto* stall = stall_of(r.error());
  ASSERT_NE(stall, nullptr) << r.error().message;
  EXPECT_EQ(stall->joint, 1);
  EXPECT_GE(stall->seconds, 0.5);
}

}  // namespace
}  // namespace armctl::arm
