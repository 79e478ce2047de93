#include <gtest/gtest.h>

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

}  // namespace
}  // namespace armctl::controller::testing
