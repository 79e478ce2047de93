// wait_until_reached / wait_until_at against the simulated arm on simulated time: they wait
// until the joints are there (not a fixed time), report a dead joint with the master's
// error while still waiting for the others, and name position and target on a timeout.
#include <gtest/gtest.h>

#include <cstdlib>

#include "devices/joint_bus/arrival.hpp"
#include "sim_fixture.hpp"

namespace armctl::test {
namespace {

using namespace std::chrono_literals;
using joint_bus::BusMaster;
using joint_bus::JointTarget;
using joint_sim::FaultPlan;

class ArrivalOnSim : public ::testing::Test {
 protected:
  void drive(BusMaster& m, int joint, std::int16_t target) {
    ASSERT_TRUE(m.set_pid_state(joint, true));
    ASSERT_TRUE(m.set_zone(joint, 7));
    ASSERT_TRUE(m.drive_to(joint, target));
  }
  int position(int joint) { return arm->joint(joint).controller().position(); }

  std::unique_ptr<joint_sim::SimArm> arm = make_arm(115200);
};

TEST_F(ArrivalOnSim, WaitsUntilEveryJointIsInItsZone) {
  BusMaster m(arm->link());
  drive(m, 1, 3000);
  drive(m, 2, -1500);
  const TimePoint start = m.clock().now();
  const int joints[] = {1, 2};
  const auto arrivals = joint_bus::wait_until_reached(m, joints, start + 10s);
  ASSERT_EQ(arrivals.size(), 2u);
  EXPECT_TRUE(joint_bus::all_arrived(arrivals));
  for (const auto& a : arrivals) EXPECT_FALSE(a.error.has_value()) << a.error->message;
  EXPECT_LE(std::abs(position(1) - 3000), 7);
  EXPECT_LE(std::abs(position(2) + 1500), 7);
  // It took the joints' travel time, not the whole 10 s, and ran on simulated time.
  EXPECT_GT(arrivals[0].after, 100ms);
  EXPECT_LT(m.clock().now() - start, 5s);
  EXPECT_GE(arrivals[1].after, arrivals[0].after) << "the longer move arrives later";
}

TEST_F(ArrivalOnSim, WaitsUntilEachPositionIsWithinTheTolerance) {
  BusMaster m(arm->link());
  drive(m, 3, 2500);
  const JointTarget targets[] = {{3, 2500}};
  const auto arrivals = joint_bus::wait_until_at(m, targets, 3, m.clock().now() + 10s);
  ASSERT_EQ(arrivals.size(), 1u);
  ASSERT_TRUE(arrivals[0].arrived) << arrivals[0].error->message;
  ASSERT_TRUE(arrivals[0].position);
  EXPECT_LE(std::abs(*arrivals[0].position - 2500), 3);
  EXPECT_EQ(arrivals[0].target, 2500);
}

TEST_F(ArrivalOnSim, ADeadJointFailsWithTheMastersErrorAndTheOthersAreStillWaitedFor) {
  BusMaster m(arm->link());
  drive(m, 4, 2000);
  arm->set_fault_plan(FaultPlan{}.dead_joint(5));
  const int joints[] = {4, 5};
  const auto arrivals = joint_bus::wait_until_reached(m, joints, m.clock().now() + 10s);
  ASSERT_EQ(arrivals.size(), 2u);
  EXPECT_TRUE(arrivals[0].arrived);
  EXPECT_FALSE(arrivals[1].arrived);
  ASSERT_TRUE(arrivals[1].error);
  const auto* f = joint_bus::joint_failure(*arrivals[1].error);
  ASSERT_NE(f, nullptr) << arrivals[1].error->message;
  EXPECT_EQ(f->code(), 990);
  EXPECT_EQ(f->joint, 5);
  EXPECT_FALSE(joint_bus::all_arrived(arrivals));
}

TEST_F(ArrivalOnSim, ATimeoutNamesPositionAndTarget) {
  BusMaster m(arm->link());
  drive(m, 1, 20000);
  const TimePoint start = m.clock().now();
  const int joints[] = {1};
  const auto arrivals = joint_bus::wait_until_reached(m, joints, start + 200ms);
  ASSERT_EQ(arrivals.size(), 1u);
  EXPECT_FALSE(arrivals[0].arrived);
  ASSERT_TRUE(arrivals[0].error);
  EXPECT_EQ(arrivals[0].error->kind, ErrorKind::timeout);
  EXPECT_EQ(arrivals[0].target, 20000);
  ASSERT_TRUE(arrivals[0].position);
  EXPECT_GT(*arrivals[0].position, 0);
  EXPECT_LT(*arrivals[0].position, 20000);
  const std::string& message = arrivals[0].error->message;
  EXPECT_NE(message.find("joint 1: not in its zone within 0.2 s"), std::string::npos) << message;
  EXPECT_NE(message.find("target 20000"), std::string::npos) << message;
  EXPECT_GE(m.clock().now() - start, 200ms);
  EXPECT_LT(m.clock().now() - start, 300ms);
}

TEST_F(ArrivalOnSim, ANegativeToleranceIsRefusedBeforeAnyTransaction) {
  BusMaster m(arm->link());
  const JointTarget targets[] = {{1, 0}};
  const auto arrivals = joint_bus::wait_until_at(m, targets, -1, m.clock().now() + 1s);
  ASSERT_EQ(arrivals.size(), 1u);
  EXPECT_EQ(arrivals[0].error->kind, ErrorKind::invalid_argument);
  EXPECT_EQ(m.counters().transactions, 0u);
}

}  // namespace
}  // namespace armctl::test
