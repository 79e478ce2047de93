#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "fake_joints.hpp"

namespace armctl::controller::testing {
namespace {

namespace jb = joint_bus;

struct MasterRig {
  MasterRig() { master.begin(&joints, 9600); }
  BusResult run(std::uint8_t joint, std::int16_t command, std::int16_t data = 0) {
    EXPECT_TRUE(master.start(joint, command, data, now));
    BusResult r{};
    for (int i = 0; i < 100000 && !master.take_result(&r); ++i) {
      joints.pump([&](std::uint8_t b) { master.on_rx_byte(b, now); });
      now += 100;
      master.poll(now);
    }
    return r;
  }
  FakeJoints joints;
  BusMaster master;
  std::uint32_t now = 1000;
};

TEST(BusMaster, GetPositionReturnsTheResponseWithItsStatus) {
  MasterRig rig;
  rig.joints.position[3] = -1234;
  BusResult r = rig.run(3, jb::cmd_get_position);
  EXPECT_TRUE(r.ok);
  EXPECT_EQ(r.status, 160);
  EXPECT_EQ(r.response, -1234);
  ASSERT_EQ(rig.joints.log.size(), 1u);
  EXPECT_EQ(rig.joints.log[0].joint, 3);
}

TEST(BusMaster, CommandWithDataSendsItAndTakesTheStatus) {
  MasterRig rig;
  BusResult r = rig.run(2, jb::cmd_drive_to, 4321);
  EXPECT_TRUE(r.ok);
  EXPECT_EQ(r.status, 220);
  EXPECT_EQ(rig.joints.position[2], 4321);
}

TEST(BusMaster, WrongReadyIsWrongJoint) {
  MasterRig rig;
  rig.joints.answers_as[4] = 6;
  BusResult r = rig.run(4, jb::cmd_get_position);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.status, jb::status_wrong_joint);
  EXPECT_TRUE(rig.joints.log.empty()) << "no COMMAND after a bad READY";
}

TEST(BusMaster, SilentJointIsNoAnswerWithinTheTimeoutThenAQuietBus) {
  MasterRig rig;
  rig.joints.dead[5] = true;
  const std::uint32_t start = rig.now;
  BusResult r = rig.run(5, jb::cmd_get_position);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.status, jb::status_no_answer);
  const std::uint32_t waited = rig.now - start;
  EXPECT_GE(waited, 3 * rig.master.word_time_us());
  EXPECT_LE(waited, 4 * rig.master.word_time_us() + 2200) << "bounded by the baud rate, not forever";
  EXPECT_FALSE(rig.master.can_start(rig.now)) << "quiet after a failure";
  EXPECT_TRUE(rig.master.can_start(rig.now + 4 * rig.master.word_time_us()));
}

TEST(BusMaster, PingEchoIsChecked) {
  MasterRig rig;
  BusResult r = rig.run(1, jb::cmd_ping, 777);
  EXPECT_TRUE(r.ok);
  EXPECT_EQ(r.response, 777);
}

TEST(BusMaster, RefusesUnknownCommandsAndJoints) {
  MasterRig rig;
  EXPECT_FALSE(rig.master.start(1, 99, 0, rig.now));
  EXPECT_FALSE(rig.master.start(0, jb::cmd_get_position, 0, rig.now));
  EXPECT_FALSE(rig.master.start(8, jb::cmd_get_position, 0, rig.now));
  EXPECT_FALSE(rig.master.busy());
}


// Pumps the wire until `results` results were taken (or the bus gave up).
std::vector<BusResult> take_results(MasterRig& rig, std::size_t results) {
  std::vector<BusResult> out;
  for (int i = 0; i < 100000 && out.size() < results; ++i) {
    rig.joints.pump([&](std::uint8_t b) { rig.master.on_rx_byte(b, rig.now); });
    BusResult r{};
    while (rig.master.take_result(&r)) out.push_back(r);
    rig.now += 100;
    rig.master.poll(rig.now);
  }
  return out;
}

TEST(BusMaster, AChainedTransactionStartsFromTheStatusItself) {
  MasterRig rig;
  rig.joints.position[1] = 11;
  rig.joints.position[2] = 22;
  ASSERT_TRUE(rig.master.start(1, jb::cmd_get_position, 0, rig.now));
  ASSERT_TRUE(rig.master.chain(2, jb::cmd_get_position, 0));
  EXPECT_TRUE(rig.master.chained());
  // Only bytes: no poll(), no start() between the two transactions.
  rig.joints.pump([&](std::uint8_t b) { rig.master.on_rx_byte(b, rig.now); });
  ASSERT_EQ(rig.joints.log.size(), 2u) << "joint 2's COMMAND went out behind joint 1's STATUS";
  EXPECT_EQ(rig.joints.log[1].joint, 2);
  const std::vector<BusResult> results = take_results(rig, 2);
  ASSERT_EQ(results.size(), 2u);
  EXPECT_EQ(results[0].joint, 1);
  EXPECT_EQ(results[0].response, 11);
  EXPECT_TRUE(results[0].chained_started);
  EXPECT_EQ(results[1].joint, 2);
  EXPECT_EQ(results[1].response, 22);
  EXPECT_TRUE(results[1].ok);
  EXPECT_FALSE(results[1].chained_started);
  EXPECT_FALSE(rig.master.busy());
}

TEST(BusMaster, AChainIsDroppedWhenTheTransactionAheadFails) {
  MasterRig rig;
  rig.joints.dead[5] = true;
  ASSERT_TRUE(rig.master.start(5, jb::cmd_get_position, 0, rig.now));
  ASSERT_TRUE(rig.master.chain(1, jb::cmd_get_position, 0));
  const std::vector<BusResult> results = take_results(rig, 1);
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].status, jb::status_no_answer);
  EXPECT_FALSE(results[0].chained_started);
  EXPECT_FALSE(rig.master.chained());
  EXPECT_FALSE(rig.master.busy()) << "a failed transaction leaves the bus quiet, not chained";
  EXPECT_TRUE(rig.joints.log.empty());
}

TEST(BusMaster, AChainWaitsUntilTheResultAheadIsTakenAndResultsComeInOrder) {
  MasterRig rig;
  ASSERT_TRUE(rig.master.start(1, jb::cmd_get_position, 0, rig.now));
  ASSERT_TRUE(rig.master.chain(2, jb::cmd_get_position, 0));
  // Nobody takes results: joint 2's transaction ends too, behind joint 1's result.
  for (int i = 0; i < 10; ++i) rig.joints.pump([&](std::uint8_t b) { rig.master.on_rx_byte(b, rig.now); });
  EXPECT_FALSE(rig.master.busy());
  // A chain queued now may not start: two results are waiting already.
  ASSERT_FALSE(rig.master.chain(3, jb::cmd_get_position, 0)) << "idle: nothing to chain behind";
  BusResult first{}, second{}, none{};
  ASSERT_TRUE(rig.master.take_result(&first));
  ASSERT_TRUE(rig.master.take_result(&second));
  EXPECT_FALSE(rig.master.take_result(&none));
  EXPECT_EQ(first.joint, 1);
  EXPECT_EQ(second.joint, 2);
  EXPECT_TRUE(rig.master.can_start(rig.now));
}

TEST(BusMaster, UnchainDropsAQueuedTransaction) {
  MasterRig rig;
  ASSERT_TRUE(rig.master.start(1, jb::cmd_get_position, 0, rig.now));
  EXPECT_FALSE(rig.master.unchain());
  ASSERT_TRUE(rig.master.chain(2, jb::cmd_get_position, 0));
  EXPECT_FALSE(rig.master.chain(3, jb::cmd_get_position, 0)) << "one queued at most";
  EXPECT_TRUE(rig.master.unchain());
  const std::vector<BusResult> results = take_results(rig, 1);
  ASSERT_EQ(results.size(), 1u);
  EXPECT_FALSE(results[0].chained_started);
  EXPECT_EQ(rig.joints.log.size(), 1u);
  EXPECT_FALSE(rig.master.busy());
}

TEST(BusMaster, ChainRefusesUnknownCommandsJointsAndAnIdleBus) {
  MasterRig rig;
  EXPECT_FALSE(rig.master.chain(1, jb::cmd_get_position, 0)) << "idle";
  ASSERT_TRUE(rig.master.start(1, jb::cmd_get_position, 0, rig.now));
  EXPECT_FALSE(rig.master.chain(1, 99, 0));
  EXPECT_FALSE(rig.master.chain(0, jb::cmd_get_position, 0));
  EXPECT_FALSE(rig.master.chain(8, jb::cmd_get_position, 0));
  EXPECT_FALSE(rig.master.chained());
}

// A port that logs what the master does to it, and when it asks for the time.
struct LoggingPort final : BusPort {
  explicit LoggingPort(FakeJoints& j) : joints(j) {}
  void set_select(std::uint8_t joint, bool high) override {
    log.push_back(std::string(high ? "rise " : "fall ") + std::to_string(joint));
    joints.set_select(joint, high);
  }
  void send_byte(std::uint8_t byte) override {
    log.push_back("byte");
    joints.send_byte(byte);
  }
  std::uint32_t now_us() override {
    log.push_back("time");
    return now;
  }
  FakeJoints& joints;
  std::vector<std::string> log;
  std::uint32_t now = 5000;
};

TEST(BusMaster, BytesWithoutATimeReadTheClockOnlyAfterTheirAction) {
  FakeJoints joints;
  LoggingPort port(joints);
  BusMaster master;
  master.begin(&port, 115200);
  ASSERT_TRUE(master.start(1, jb::cmd_get_position, 0, port.now));
  ASSERT_TRUE(master.chain(2, jb::cmd_get_position, 0));
  port.log.clear();
  joints.pump([&](std::uint8_t b) { master.on_rx_byte(b); });
  ASSERT_GE(port.log.size(), 8u);
  const std::vector<std::string> first_transaction(port.log.begin(), port.log.begin() + 8);
  EXPECT_EQ(first_transaction, (std::vector<std::string>{"byte", "byte", "time",  // READY: COMMAND, then the clock
                                                          "fall 1", "time",        // RESPONSE: select, then the clock
                                                          "rise 2", "time",        // STATUS: the chained select first
                                                          "byte"}));
  BusResult r{};
  ASSERT_TRUE(master.take_result(&r));
  EXPECT_TRUE(r.ok);
}

TEST(BusMaster, ADeadlineArmedFromThePortsClockTimesOut) {
  FakeJoints joints;
  joints.dead[3] = true;
  LoggingPort port(joints);
  BusMaster master;
  master.begin(&port, 115200);
  ASSERT_TRUE(master.start(1, jb::cmd_get_position, 0, port.now));
  ASSERT_TRUE(master.chain(3, jb::cmd_get_position, 0));
  port.now = 70000;  // the chained transaction starts at this time
  joints.pump([&](std::uint8_t b) { master.on_rx_byte(b); });
  BusResult r{};
  ASSERT_TRUE(master.take_result(&r));
  ASSERT_TRUE(r.chained_started);
  master.poll(70000 + 2000);
  EXPECT_FALSE(master.take_result(&r)) << "not timed out from the port's time yet";
  master.poll(70000 + 3 * master.word_time_us() + 2000 + 1);
  ASSERT_TRUE(master.take_result(&r));
  EXPECT_EQ(r.joint, 3);
  EXPECT_EQ(r.status, jb::status_no_answer);
}

}  // namespace
}  // namespace armctl::controller::testing
