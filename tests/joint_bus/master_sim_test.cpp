// The master against the simulated arm (portable JointController + motor model on the
// simulated bus with wire timing): every command and status path, every injected fault,
// retries and verify-after-write.
#include <gtest/gtest.h>

#include "devices/joint_bus/bus_master.hpp"
#include "portable/joint_bus_codes.hpp"
#include "sim_fixture.hpp"

namespace armctl::test {
namespace {

using joint_bus::BusMaster;
using joint_bus::FailureKind;
using joint_bus::MasterOptions;
using joint_sim::FaultPlan;
using joint_sim::Wire;

class MasterOnSim : public ::testing::Test {
 protected:
  std::unique_ptr<joint_sim::SimArm> arm = make_arm();
  const joint_bus::JointController& joint(int j) { return arm->joint(j).controller(); }
};

TEST_F(MasterOnSim, EveryCommandSucceedsAndChangesWhatItShould) {
  BusMaster m(arm->link());
  for (int j = 1; j <= 7; ++j) {
    ASSERT_EQ(m.ping(j, -12345).value(), -12345);
    ASSERT_EQ(m.get_joint_number(j).value(), j);
    ASSERT_TRUE(m.set_pid_state(j, true).ok());
    EXPECT_TRUE(joint(j).loop_enabled());
    ASSERT_TRUE(m.set_speed(j, 80).ok());
    EXPECT_EQ(joint(j).speed_percent(), 80);
    ASSERT_TRUE(m.set_zone(j, 7).ok());
    EXPECT_EQ(joint(j).zone(), 7);
    ASSERT_TRUE(m.drive_to(j, 400).ok());
    EXPECT_EQ(joint(j).target(), 400);
    ASSERT_TRUE(m.drive_dist(j, -100).ok());
    EXPECT_EQ(joint(j).target(), 300);
    EXPECT_EQ(m.get_target(j).value(), 300);
  }
  arm->advance(std::chrono::seconds(2));
  for (int j = 1; j <= 7; ++j) {
    EXPECT_TRUE(m.check_target_reached(j).value()) << j;
    const auto p = m.get_position(j).value();
    EXPECT_EQ(p, joint(j).position());
    EXPECT_LE(std::abs(p - 300), 7);
    ASSERT_TRUE(m.drive_dist_max(j, 50).ok());
    EXPECT_EQ(joint(j).target(), p + 50);
    ASSERT_TRUE(m.home(j).ok());
    EXPECT_EQ(joint(j).target(), 0);
    EXPECT_LE(std::abs(joint(j).position()), 3);  // position := 0, then motor momentum
  }
  EXPECT_EQ(m.counters().failures, 0u);
}

TEST_F(MasterOnSim, UnknownCommandIs930AndNothingChanges) {
  BusMaster m(arm->link());
  auto r = m.transact(3, 99, std::nullopt);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(joint_bus::joint_failure(r.error())->code(), 930);
  EXPECT_EQ(joint_bus::joint_failure(r.error())->status_word, 930);
  EXPECT_TRUE(m.ping(3, 1).ok());  // the bus is still in step
}

TEST_F(MasterOnSim, BadDataIs940AndStateUnchanged) {
  BusMaster m(arm->link());
  ASSERT_TRUE(m.set_speed(1, 40).ok());
  auto r = m.set_speed(1, 150);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(joint_bus::joint_failure(r.error())->code(), 940);
  EXPECT_EQ(joint(1).speed_percent(), 40);
  EXPECT_EQ(joint_bus::joint_failure(m.set_zone(1, -1).error())->code(), 940);
  EXPECT_EQ(joint_bus::joint_failure(m.transact(2, joint_bus::cmd_set_pid_state, 5).error())->code(), 940);
}

// master_side vector: "drive_dist of +1 on a target of 32767".
TEST_F(MasterOnSim, DriveDistPastInt16Is940AndTargetStays) {
  BusMaster m(arm->link());
  ASSERT_TRUE(m.drive_to(4, 32767).ok());
  auto r = m.drive_dist(4, 1);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(joint_bus::joint_failure(r.error())->code(), 940);
  EXPECT_EQ(joint(4).target(), 32767);
}

// master_side vector: "no READY within the timeout": 990 for that joint; the others answered.
TEST_F(MasterOnSim, DeadJointIs990AndNeverBlanksTheOthers) {
  arm->set_fault_plan(FaultPlan{}.dead_joint(5));
  BusMaster m(arm->link());
  const TimePoint start = arm->now();
  auto all = m.for_each_joint<std::int16_t>([&](int j) { return m.get_joint_number(j); });
  ASSERT_EQ(all.size(), 7u);
  for (const auto& o : all) {
    if (o.joint == 5) {
      ASSERT_FALSE(o.result.ok());
      EXPECT_EQ(joint_bus::joint_failure(o.result.error())->code(), 990);
      EXPECT_EQ(joint_bus::joint_failure(o.result.error())->stage, joint_bus::Stage::ready);
    } else {
      ASSERT_TRUE(o.result.ok()) << o.joint << ": " << o.result.error().message;
      EXPECT_EQ(o.result.value(), o.joint);
    }
  }
  // Bounded: 6 transactions of 8 bytes plus one timeout and one quiet period.
  EXPECT_LT(arm->now() - start, std::chrono::milliseconds(200));
}

// master_side vector: READY from another number -> 910, select dropped, no COMMAND sent.
TEST_F(MasterOnSim, WrongNumberIs910AndNoCommandReachesTheJoint) {
  arm->set_fault_plan(FaultPlan{}.wrong_number(3, 5));
  BusMaster m(arm->link());
  const auto sent_before = arm->bus().stats().bytes_to_joints;
  auto r = m.drive_to(3, 1000);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(joint_bus::joint_failure(r.error())->code(), 910);
  EXPECT_FALSE(joint_bus::joint_failure(r.error())->command_sent);
  EXPECT_EQ(arm->bus().stats().bytes_to_joints, sent_before);
  EXPECT_FALSE(arm->bus().select(3));
  EXPECT_EQ(joint(3).target(), 0);
  EXPECT_TRUE(m.ping(2, 7).ok());
}

// Each injected fault on the master's RX makes a transaction fail; never a made-up success.
struct FaultCase {
  const char* name;
  std::function<void(FaultPlan&)> plan;
  FailureKind kind;
};

TEST_F(MasterOnSim, EveryInjectedFaultIsReportedNotSwallowed) {
  // Bytes to the master for get_position: READY 0-1, RESPONSE 2-3, STATUS 4-5.
  const std::vector<FaultCase> cases = {
      {"drop READY", [](FaultPlan& p) { p.drop_byte(Wire::to_master, 0); }, FailureKind::no_answer},
      {"drop RESPONSE", [](FaultPlan& p) { p.drop_byte(Wire::to_master, 3); }, FailureKind::no_answer},
      {"drop STATUS", [](FaultPlan& p) { p.drop_byte(Wire::to_master, 5); }, FailureKind::no_answer},
      {"flip READY", [](FaultPlan& p) { p.flip_bits(Wire::to_master, 0, 0x10); }, FailureKind::wrong_joint},
      {"flip STATUS", [](FaultPlan& p) { p.flip_bits(Wire::to_master, 4, 0x01); }, FailureKind::bad_status},
      {"flip COMMAND", [](FaultPlan& p) { p.flip_bits(Wire::to_joints, 0, 0x01); }, FailureKind::bad_status},
      {"delay READY", [](FaultPlan& p) { p.delay_byte(Wire::to_master, 0, std::chrono::milliseconds(100)); },
       FailureKind::no_answer},
      {"delay STATUS", [](FaultPlan& p) { p.delay_byte(Wire::to_master, 5, std::chrono::milliseconds(100)); },
       FailureKind::no_answer},
      {"dead joint", [](FaultPlan& p) { p.dead_joint(2); }, FailureKind::no_answer},
      {"wrong number", [](FaultPlan& p) { p.wrong_number(2, 6); }, FailureKind::wrong_joint},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    auto a = make_arm();
    FaultPlan plan;
    c.plan(plan);
    a->set_fault_plan(plan);
    BusMaster m(a->link());
    auto r = m.get_position(2);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(joint_bus::joint_failure(r.error())->kind, c.kind) << r.error().message;
    // The next transaction works: stale bytes were drained, the joint recovered.
    a->bus().clear_faults();
    a->advance(std::chrono::milliseconds(200));
    auto again = m.get_position(2);
    EXPECT_TRUE(again.ok()) << again.error().message;
  }
}

TEST_F(MasterOnSim, GarbageBeforeReadyIsDrainedOrRefused) {
  BusMaster m(arm->link());
  // Noise that arrived before the transaction: drained, the transaction succeeds.
  arm->set_fault_plan(FaultPlan{}.garbage(arm->now() + std::chrono::milliseconds(1), {0x55, 0xAA, 0x01}));
  arm->advance(std::chrono::milliseconds(10));
  ASSERT_TRUE(m.get_target(1).ok());
  EXPECT_EQ(m.counters().drained_bytes, 3u);
  // Noise in the middle of READY: never a success.
  auto a = make_arm();
  a->set_fault_plan(FaultPlan{}.garbage(a->now() + std::chrono::microseconds(100), {0x07}));
  BusMaster m2(a->link());
  auto r = m2.get_target(1);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(joint_bus::joint_failure(r.error())->kind, FailureKind::wrong_joint);
}

TEST_F(MasterOnSim, RetriesRecoverSafeCommands) {
  arm->set_fault_plan(FaultPlan{}.drop_byte(Wire::to_master, 3));  // the first RESPONSE
  MasterOptions o;
  o.retries = 2;
  BusMaster m(arm->link(), o);
  auto r = m.get_joint_number(6);
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r.value(), 6);
  EXPECT_EQ(m.counters().retries, 1u);
}

TEST_F(MasterOnSim, RelativeMoveIsRetriedOnlyIfTheCommandWasNeverSent) {
  MasterOptions o;
  o.retries = 3;
  {  // READY lost: the COMMAND never went out, so trying again is safe.
    arm->set_fault_plan(FaultPlan{}.drop_byte(Wire::to_master, 0));
    BusMaster m(arm->link(), o);
    ASSERT_TRUE(m.drive_dist(2, 100).ok());
    EXPECT_EQ(m.counters().retries, 1u);
    EXPECT_EQ(joint(2).target(), 100);
  }
  {  // STATUS lost: the joint moved its target once; it must not be told again.
    arm->set_fault_plan(FaultPlan{}.drop_byte(Wire::to_master, 3));
    BusMaster m(arm->link(), o);
    const auto sent_before = arm->bus().stats().bytes_to_joints;
    auto r = m.drive_dist(2, 100);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(joint_bus::joint_failure(r.error())->code(), 990);
    EXPECT_TRUE(joint_bus::joint_failure(r.error())->command_sent);
    EXPECT_EQ(m.counters().retries, 0u);
    EXPECT_EQ(arm->bus().stats().bytes_to_joints - sent_before, 4u);  // one COMMAND + DATA
    EXPECT_EQ(joint(2).target(), 200);
  }
  {  // Same for drive_dist_max.
    arm->set_fault_plan(FaultPlan{}.drop_byte(Wire::to_master, 2));
    BusMaster m(arm->link(), o);
    auto r = m.drive_dist_max(2, 10);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(m.counters().retries, 0u);
  }
  {  // Absolute moves may be repeated after any lost answer.
    arm->set_fault_plan(FaultPlan{}.drop_byte(Wire::to_master, 3));
    BusMaster m(arm->link(), o);
    ASSERT_TRUE(m.drive_to(2, -700).ok());
    EXPECT_EQ(m.counters().retries, 1u);
    EXPECT_EQ(joint(2).target(), -700);
  }
}

TEST_F(MasterOnSim, VerifyAfterWriteCatchesACorruptedTargetAndNeverFixesItWithAMove) {
  MasterOptions o;
  o.verify = true;
  o.retries = 3;
  BusMaster m(arm->link(), o);
  ASSERT_TRUE(m.drive_to(1, 1000).ok());
  ASSERT_TRUE(m.drive_dist(1, 24).ok());
  EXPECT_EQ(joint(1).target(), 1024);
  ASSERT_TRUE(m.drive_dist_max(1, 5).ok());

  // drive_dist with verify: get_target (to_joints bytes 0-1), then drive_dist: COMMAND 2-3,
  // DATA 4-5. A flipped DATA bit gives the joint a distance of 100 ^ 0x04 = 96.
  auto a = make_arm();
  a->set_fault_plan(FaultPlan{}.flip_bits(Wire::to_joints, 4, 0x04));
  BusMaster mv(a->link(), o);
  const auto sent_before = a->bus().stats().bytes_to_joints;
  auto r = mv.drive_dist(3, 100);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(joint_bus::joint_failure(r.error())->kind, FailureKind::verify_mismatch);
  EXPECT_EQ(a->joint(3).controller().target(), 96);
  // get_target, drive_dist, get_target: no second drive_dist went out.
  EXPECT_EQ(a->bus().stats().bytes_to_joints - sent_before, 2u + 4u + 2u);
  EXPECT_EQ(mv.counters().retries, 0u);
}

TEST_F(MasterOnSim, DriveAllSendsEveryJointItsValueBeforeVerifying) {
  MasterOptions o;
  o.verify = true;
  BusMaster m(arm->link(), o);
  arm->set_fault_plan(FaultPlan{}.dead_joint(4));
  const std::vector<std::int16_t> values{100, 200, 300, 400, 500, 600, 700};
  auto out = m.drive_all(joint_bus::Drive::to, values);
  ASSERT_EQ(out.size(), 7u);
  for (const auto& o2 : out) {
    if (o2.joint == 4) {
      EXPECT_EQ(joint_bus::joint_failure(o2.result.error())->code(), 990);
      EXPECT_EQ(joint(4).target(), 0);
    } else {
      EXPECT_TRUE(o2.result.ok()) << o2.result.error().message;
      EXPECT_EQ(joint(o2.joint).target(), values[static_cast<std::size_t>(o2.joint - 1)]);
    }
  }
}

TEST_F(MasterOnSim, TimeoutsFollowTheBaud) {
  joint_bus::BusTiming t;
  EXPECT_EQ(t.word_timeout(9600), wire_time(2, 9600) * 4 + std::chrono::milliseconds(2));
  EXPECT_LT(t.word_timeout(115200), t.word_timeout(9600));
  for (std::uint32_t baud : {9600u, 115200u}) {
    auto a = make_arm(baud);
    a->set_fault_plan(FaultPlan{}.dead_joint(1));
    BusMaster m(a->link());
    const TimePoint start = a->now();
    ASSERT_FALSE(m.home(1).ok());
    // A READY timeout, then one quiet period.
    EXPECT_EQ(a->now() - start, 2 * t.word_timeout(baud));
  }
}

}  // namespace
}  // namespace armctl::test
