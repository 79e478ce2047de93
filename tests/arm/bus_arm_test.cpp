// The Arm API on the joint bus: the simulated SCARA arm (portable joint controllers, motors,
// the bus with wire timing) in process, on simulated time.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "arm/arm.hpp"
#include "arm/bus_arm_device.hpp"
#include "arm_files.hpp"
#include "joint_bus/sim_fixture.hpp"

namespace armctl::arm {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

class BusArm : public ::testing::Test {
 protected:
  std::unique_ptr<joint_sim::SimArm> sim = test::make_arm();
  joint_bus::BusMaster master{sim->link()};
  Arm arm{testing::shipped("scara"),
          std::make_unique<BusArmDevice>(testing::shipped("scara"), master, sim->link(), "simulated SCARA")};

  std::vector<std::optional<double>> none() const { return std::vector<std::optional<double>>(7); }
  double seconds() const { return std::chrono::duration<double>(sim->now().time_since_epoch()).count(); }
  // Z's zero is the bottom of its travel, 15000 clicks below the simulated joint's start.
  void to_start() {
    auto t = none();
    t[0] = 0.15;
    ASSERT_TRUE(arm.move_joints(t));
    ASSERT_TRUE(arm.wait());
  }
};

TEST_F(BusArm, ReadsClicksAsSi) {
  auto s = arm.read();
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_NEAR(s->positions[0], 0.15, 1e-9);  // clicks 0 = 150 mm (Z travel 0..300 mm)
  for (std::size_t i = 1; i < 7; ++i) EXPECT_NEAR(s->positions[i], i == 6 ? 0.02 : 0.0, 1e-9) << i;
}

TEST_F(BusArm, JointsArriveTogetherInTheTimeAsked) {
  auto t = none();
  t[1] = 40 * kDeg;   // SHOULDER: the slow heavy joint
  t[2] = -20 * kDeg;  // UAE
  t[0] = 0.2;         // Z
  MoveOptions o;
  o.duration = std::chrono::milliseconds(2500);
  const double t0 = seconds();
  ASSERT_TRUE(arm.move_joints(t, o));
  auto s = arm.wait();
  ASSERT_TRUE(s) << s.error().message;
  const double took = seconds() - t0;
  EXPECT_GE(took, 2.2);
  EXPECT_LE(took, 2.9);
  EXPECT_NEAR(s->positions[1], 40 * kDeg, 0.5 * kDeg);
  EXPECT_NEAR(s->positions[2], -20 * kDeg, 0.5 * kDeg);
  EXPECT_NEAR(s->positions[0], 0.2, 0.001);
}

TEST_F(BusArm, MoveToReachesTheToolPose) {
  motion::JointVector q(6);
  q << 0.12, 30 * kDeg, 50 * kDeg, -20 * kDeg, 35 * kDeg, 15 * kDeg;
  const motion::Pose want = arm.forward(q);
  const motion::Rpy r = motion::to_rpy(want.orientation);
  CartesianGoal g;
  g.position = want.position;
  g.roll = r.roll;
  g.pitch = r.pitch;
  g.yaw = r.yaw;
  auto moved = arm.move_to(g);
  ASSERT_TRUE(moved) << moved.error().message;
  ASSERT_TRUE(arm.wait());
  EXPECT_TRUE(arm.device().idle(std::chrono::milliseconds(500)));  // the position loops settle
  auto p = arm.pose();
  ASSERT_TRUE(p);
  EXPECT_LT((p->position - want.position).norm(), 0.002) << (p->position - want.position).transpose();
}

TEST_F(BusArm, StopBrakesAndHolds) {
  auto t = none();
  t[2] = 120 * kDeg;
  MoveOptions o;
  o.duration = std::chrono::seconds(4);
  ASSERT_TRUE(arm.move_joints(t, o));
  EXPECT_TRUE(arm.device().idle(std::chrono::milliseconds(1500)));
  ASSERT_TRUE(arm.stop());
  EXPECT_TRUE(arm.device().idle(std::chrono::milliseconds(1000)));
  const double held = arm.read()->positions[2];
  EXPECT_TRUE(arm.device().idle(std::chrono::milliseconds(1000)));
  EXPECT_NEAR(arm.read()->positions[2], held, 0.2 * kDeg);
  EXPECT_LT(held, 100 * kDeg);
  EXPECT_GT(held, 10 * kDeg);
}

TEST_F(BusArm, WaitTakesAToleranceForEachJoint) {
  // SHOULDER held back by an obstacle short of its target: the default tolerance waits in
  // vain; a tolerance of its own that it meets ends the wait.
  auto& hw = sim->joint(2).hardware();
  const auto at = static_cast<std::int32_t>(hw.position_clicks());
  hw.set_end_stops({at - 5, at + 5});
  auto t = none();
  t[1] = 3 * kDeg;
  ASSERT_TRUE(arm.move_joints(t));
  WaitOptions w;
  w.timeout = std::chrono::seconds(3);
  auto late = arm.wait(w);
  ASSERT_FALSE(late);
  EXPECT_NE(late.error().message.find("SHOULDER"), std::string::npos) << late.error().message;
  w.joint_tolerance.assign(7, 0.0);
  w.joint_tolerance[1] = 5 * kDeg;
  auto there = arm.wait(w);
  EXPECT_TRUE(there) << there.error().message;
}

TEST_F(BusArm, TorqueOffTurnsThePositionLoopsOff) {
  ASSERT_TRUE(arm.set_torque(false));
  for (int j = 1; j <= 7; ++j) EXPECT_FALSE(sim->joint(j).controller().loop_enabled()) << j;
  ASSERT_TRUE(arm.set_torque(true));
  for (int j = 1; j <= 7; ++j) EXPECT_TRUE(sim->joint(j).controller().loop_enabled()) << j;
}

TEST_F(BusArm, ADeadJointFailsTheCommandNamingIt) {
  joint_sim::FaultPlan plan;
  plan.dead_joint(3);
  sim->set_fault_plan(plan);
  auto s = arm.read();
  ASSERT_FALSE(s);
  EXPECT_EQ(s.error().kind, ErrorKind::timeout);
  EXPECT_NE(s.error().message.find("3"), std::string::npos) << s.error().message;
}

// A link whose far end went away (a simulated arm's socket closed): every read throws, as
// sim_link_client does.
class ClosedLink : public transport::JointBusLink {
 public:
  explicit ClosedLink(transport::JointBusLink& inner) : inner_(inner) {}
  int joint_count() const override { return inner_.joint_count(); }
  void set_select(int joint, bool high) override { inner_.set_select(joint, high); }
  void write(std::span<const std::uint8_t> bytes) override { inner_.write(bytes); }
  void flush() override { inner_.flush(); }
  std::optional<std::uint8_t> read_byte(TimePoint) override {
    throw ArmctlError(ErrorKind::io, "simulated arm at /tmp/x closed the connection");
  }
  std::size_t drain() override { return 0; }
  const Clock& clock() const override { return inner_.clock(); }
  std::uint32_t baud() const override { return inner_.baud(); }

 private:
  transport::JointBusLink& inner_;
};

TEST(BusArmDevice, ALinkThatFailsWhileIdleIsAnErrorNotAnException) {
  auto sim = test::make_arm();
  ClosedLink link(sim->link());
  joint_bus::BusMaster master{link};
  BusArmDevice device(testing::shipped("scara"), master, link, "simulated SCARA");
  Status s = Ok{};
  EXPECT_NO_THROW(s = device.idle(std::chrono::milliseconds(20)));
  ASSERT_FALSE(s);
  EXPECT_EQ(s.error().kind, ErrorKind::io);
  EXPECT_NE(s.error().message.find("closed the connection"), std::string::npos) << s.error().message;
}

}  // namespace
}  // namespace armctl::arm
