// Every command over the bus: success statuses and values, 940 on every out-of-range
// value with the state unchanged, 930 for unknown commands (no DATA read), int16 limits
// and the inclusive zone.
#include <gtest/gtest.h>

#include "joint_bus_harness.hpp"
#include "portable/joint_controller.hpp"

namespace armctl::joint_bus {
namespace {

using testing::BusHarness;
using testing::EncoderDriver;
using testing::Exchange;

struct Snapshot {
  int16_t position, target, zone;
  uint8_t speed;
  bool loop;
  int32_t setpoint;
  bool operator==(const Snapshot&) const = default;
};

Snapshot snapshot(const JointController& j) {
  return Snapshot{j.position(), j.target(), j.zone(), j.speed_percent(), j.loop_enabled(), j.setpoint_q8()};
}

class CommandsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(joint.begin(5, default_tuning(), 9600));
    joint.init_encoder(false, false);
  }
  JointController joint;
  BusHarness bus{joint};
  EncoderDriver encoder;
};

TEST_F(CommandsTest, ReadyIsTheJointNumberForEveryTransaction) {
  for (int i = 0; i < 3; ++i) EXPECT_EQ(bus.transact(cmd_get_position).ready_word(), 5);
}

TEST_F(CommandsTest, PingEchoesEveryKindOfValue) {
  for (int16_t v : {int16_t{0}, int16_t{1}, int16_t{-1}, int16_t{32767}, int16_t{-32768}, int16_t{1234}}) {
    const Exchange e = bus.transact(cmd_ping, v);
    EXPECT_EQ(e.response_word(), v);
    EXPECT_EQ(e.status_word(), 100);
  }
}

TEST_F(CommandsTest, HomeZeroesPositionAndTargetAndKeepsLoopState) {
  encoder.move(joint, 500);
  ASSERT_EQ(bus.transact(cmd_drive_to, int16_t{800}).status_word(), 220);
  Exchange e = bus.transact(cmd_home);
  EXPECT_TRUE(e.response.empty());
  EXPECT_EQ(e.status_word(), 110);
  EXPECT_EQ(joint.position(), 0);
  EXPECT_EQ(joint.target(), 0);
  EXPECT_EQ(joint.setpoint_q8(), 0);
  EXPECT_TRUE(joint.loop_enabled());

  ASSERT_EQ(bus.transact(cmd_set_pid_state, int16_t{0}).status_word(), 120);
  encoder.move(joint, -40);
  EXPECT_EQ(bus.transact(cmd_home).status_word(), 110);
  EXPECT_FALSE(joint.loop_enabled()) << "home must not re-enable the loop";
  EXPECT_EQ(joint.position(), 0);
  EXPECT_FALSE(joint.control_tick().enable);
}

TEST_F(CommandsTest, SetPidStateAcceptsOnlyZeroAndOne) {
  EXPECT_EQ(bus.transact(cmd_set_pid_state, int16_t{0}).status_word(), 120);
  EXPECT_FALSE(joint.loop_enabled());
  EXPECT_EQ(bus.transact(cmd_set_pid_state, int16_t{1}).status_word(), 120);
  EXPECT_TRUE(joint.loop_enabled());
  for (int16_t bad : {int16_t{2}, int16_t{-1}, int16_t{5}, int16_t{32767}, int16_t{-32768}}) {
    const Snapshot before = snapshot(joint);
    EXPECT_EQ(bus.transact(cmd_set_pid_state, bad).status_word(), 940) << bad;
    EXPECT_EQ(snapshot(joint), before);
  }
}

TEST_F(CommandsTest, GetPositionTargetAndJointNumber) {
  encoder.move(joint, -300);
  Exchange e = bus.transact(cmd_get_position);
  EXPECT_EQ(e.response_word(), -300);
  EXPECT_EQ(e.status_word(), 160);
  bus.transact(cmd_drive_to, int16_t{1000});
  e = bus.transact(cmd_get_target);
  EXPECT_EQ(e.response_word(), 1000);
  EXPECT_EQ(e.status_word(), 170);
  e = bus.transact(cmd_get_joint_number);
  EXPECT_EQ(e.response_word(), 5);
  EXPECT_EQ(e.status_word(), 180);
}

TEST_F(CommandsTest, DriveDistAddsToTargetWithinInt16) {
  EXPECT_EQ(bus.transact(cmd_drive_dist, int16_t{250}).status_word(), 200);
  EXPECT_EQ(bus.transact(cmd_drive_dist, int16_t{-50}).status_word(), 200);
  EXPECT_EQ(joint.target(), 200);
  bus.transact(cmd_drive_to, int16_t{32000});
  EXPECT_EQ(bus.transact(cmd_drive_dist, int16_t{767}).status_word(), 200);
  EXPECT_EQ(joint.target(), 32767);
  Snapshot before = snapshot(joint);
  EXPECT_EQ(bus.transact(cmd_drive_dist, int16_t{1}).status_word(), 940);
  EXPECT_EQ(bus.transact(cmd_drive_dist, int16_t{32767}).status_word(), 940);
  EXPECT_EQ(snapshot(joint), before);
  bus.transact(cmd_drive_to, int16_t{-32768});
  before = snapshot(joint);
  EXPECT_EQ(bus.transact(cmd_drive_dist, int16_t{-1}).status_word(), 940);
  EXPECT_EQ(bus.transact(cmd_drive_dist, int16_t{-32768}).status_word(), 940);
  EXPECT_EQ(snapshot(joint), before);
  EXPECT_EQ(bus.transact(cmd_drive_dist, int16_t{32767}).status_word(), 200);
  EXPECT_EQ(joint.target(), -1);
}

TEST_F(CommandsTest, DriveDistMaxIsRelativeToPosition) {
  encoder.move(joint, 100);
  bus.transact(cmd_drive_to, int16_t{5000});
  EXPECT_EQ(bus.transact(cmd_drive_dist_max, int16_t{-250}).status_word(), 210);
  EXPECT_EQ(joint.target(), -150);
  // Position near the top of the range: position + distance past 32767 is bad data.
  bus.transact(cmd_set_pid_state, int16_t{0});
  encoder.move(joint, 32600);  // position 32700
  joint.control_tick();        // loop off: target follows position
  ASSERT_EQ(joint.position(), 32700);
  Snapshot before = snapshot(joint);
  EXPECT_EQ(bus.transact(cmd_drive_dist_max, int16_t{68}).status_word(), 940);
  EXPECT_EQ(snapshot(joint), before);
  EXPECT_EQ(bus.transact(cmd_drive_dist_max, int16_t{67}).status_word(), 210);
  EXPECT_EQ(joint.target(), 32767);
}

TEST_F(CommandsTest, DriveToTakesTheWholeInt16Range) {
  for (int16_t v : {int16_t{-32768}, int16_t{32767}, int16_t{0}, int16_t{-7}}) {
    EXPECT_EQ(bus.transact(cmd_drive_to, v).status_word(), 220);
    EXPECT_EQ(joint.target(), v);
  }
}

TEST_F(CommandsTest, SetSpeedAcceptsZeroToHundredPercent) {
  for (int16_t v : {int16_t{0}, int16_t{1}, int16_t{50}, int16_t{100}}) {
    EXPECT_EQ(bus.transact(cmd_set_speed, v).status_word(), 250);
    EXPECT_EQ(joint.speed_percent(), v);
  }
  for (int16_t bad : {int16_t{101}, int16_t{150}, int16_t{255}, int16_t{-1}, int16_t{-32768}, int16_t{32767}}) {
    const Snapshot before = snapshot(joint);
    EXPECT_EQ(bus.transact(cmd_set_speed, bad).status_word(), 940) << bad;
    EXPECT_EQ(snapshot(joint), before);
  }
}

TEST_F(CommandsTest, SetZoneAcceptsZeroTo32767) {
  for (int16_t v : {int16_t{0}, int16_t{5}, int16_t{32767}}) {
    EXPECT_EQ(bus.transact(cmd_set_zone, v).status_word(), 260);
    EXPECT_EQ(joint.zone(), v);
  }
  for (int16_t bad : {int16_t{-1}, int16_t{-32768}}) {
    const Snapshot before = snapshot(joint);
    EXPECT_EQ(bus.transact(cmd_set_zone, bad).status_word(), 940);
    EXPECT_EQ(snapshot(joint), before);
  }
}

TEST_F(CommandsTest, CheckTargetReachedZoneIsInclusive) {
  bus.transact(cmd_set_pid_state, int16_t{0});  // keep the loop from moving anything
  bus.transact(cmd_set_pid_state, int16_t{1});
  bus.transact(cmd_drive_to, int16_t{10});
  auto reached = [&] {
    const Exchange e = bus.transact(cmd_check_target_reached);
    EXPECT_EQ(e.status_word(), 300);
    return e.response_word();
  };
  bus.transact(cmd_set_zone, int16_t{0});
  EXPECT_EQ(reached(), 0);
  bus.transact(cmd_set_zone, int16_t{9});
  EXPECT_EQ(reached(), 0);
  bus.transact(cmd_set_zone, int16_t{10});
  EXPECT_EQ(reached(), 1);  // |10 - 0| <= 10
  encoder.move(joint, 10);
  bus.transact(cmd_set_zone, int16_t{0});
  EXPECT_EQ(reached(), 1);  // zone 0: exactly at target
  encoder.move(joint, 1);
  EXPECT_EQ(reached(), 0);
  // Extremes: no int16 overflow in the difference.
  bus.transact(cmd_drive_to, int16_t{-32768});
  bus.transact(cmd_set_zone, int16_t{32767});
  EXPECT_EQ(reached(), 0);  // |-32768 - 11| = 32779 > 32767
  bus.transact(cmd_drive_to, int16_t{-32756});
  EXPECT_EQ(reached(), 1);  // exactly 32767
}

TEST_F(CommandsTest, UnknownCommandsAre930AndReadNoData) {
  for (int16_t code : {int16_t{3}, int16_t{4}, int16_t{5}, int16_t{9}, int16_t{13}, int16_t{99},
                       int16_t{-1}, int16_t{32767}, int16_t{-32768}}) {
    const Snapshot before = snapshot(joint);
    bus.select(true);
    EXPECT_EQ(bus.drain().size(), 2u);
    bus.send_word(code);
    // A master that wrongly sends a DATA word: it is not read as anything.
    bus.send_word(cmd_drive_to);
    bus.send_word(1234);
    EXPECT_TRUE(bus.drain().empty()) << "no RESPONSE for an unknown command";
    bus.select(false);
    const auto status = bus.drain();
    ASSERT_EQ(status.size(), 2u);
    EXPECT_EQ(word_from(status[0], status[1]), 930) << code;
    EXPECT_EQ(snapshot(joint), before);
  }
  EXPECT_EQ(bus.transact(cmd_ping, int16_t{7}).response_word(), 7) << "next transaction is clean";
}

TEST_F(CommandsTest, ExecuteDirectlyMatchesTheBus) {
  EXPECT_EQ(joint.execute(cmd_get_joint_number, 0).response, 5);
  EXPECT_EQ(joint.execute(42, 0).status, status_unknown_command);
  EXPECT_EQ(joint.execute(cmd_set_speed, 101).status, status_bad_data);
}

TEST(JointControllerBegin, RejectsJointNumbersOutsideOneToSevenAndStaysSilent) {
  for (uint8_t n : {uint8_t{0}, uint8_t{8}, uint8_t{255}}) {
    JointController joint;
    EXPECT_FALSE(joint.begin(n, default_tuning(), 9600));
    BusHarness bus(joint);
    const Exchange e = bus.transact(cmd_ping, int16_t{1});
    EXPECT_TRUE(e.ready.empty());
    EXPECT_TRUE(e.response.empty());
    EXPECT_TRUE(e.status.empty());
    EXPECT_FALSE(joint.tx_enabled());
    EXPECT_FALSE(joint.control_tick().enable);
  }
  JointController joint;
  EXPECT_FALSE(joint.begin(3, default_tuning(), 0));
  for (uint8_t n = 1; n <= 7; ++n) {
    JointController j;
    EXPECT_TRUE(j.begin(n, default_tuning(), 115200));
    BusHarness bus(j, 115200);
    EXPECT_EQ(bus.transact(cmd_get_joint_number).response_word(), n);
  }
}

}  // namespace
}  // namespace armctl::joint_bus
