// Every joint bus command and status path against both arms: the portable JointController
// on the host ("sim") and the joint firmware ELF on emulated ATmega328P chips ("avr"). The
// master and the bus are the same; only what is attached to the select lines differs, so
// whatever passes here passes for the real firmware byte for byte.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>
#include <tuple>

#include "arm_backends.hpp"
#include "devices/joint_bus/bus_master.hpp"
#include "portable/joint_bus_codes.hpp"

namespace armctl::hil {
namespace {

using joint_bus::BusMaster;
using std::chrono::milliseconds;

using Param = std::tuple<std::string, std::uint32_t>;  // backend, baud

class HilCommands : public ::testing::TestWithParam<Param> {
 protected:
  std::unique_ptr<ArmBackend> make(Scenario s = {}) {
    s.baud = std::get<1>(GetParam());
    auto b = make_backend(std::get<0>(GetParam()), s);
    b->advance(milliseconds(20));  // power-up: the firmware reads its EEPROM and starts
    return b;
  }
};

TEST_P(HilCommands, EveryCommandSucceedsWithItsStatusAndEffect) {
  auto arm = make();
  BusMaster m(arm->link());
  for (int j = 1; j <= 7; ++j) {
    SCOPED_TRACE("joint " + std::to_string(j));
    ASSERT_EQ(m.ping(j, -12345).value(), -12345);                      // 100
    ASSERT_EQ(m.ping(j, 1234).value(), 1234);
    ASSERT_EQ(m.get_joint_number(j).value(), j);                      // 180
    ASSERT_TRUE(m.set_pid_state(j, true).ok());                       // 120
    ASSERT_TRUE(m.set_speed(j, 80).ok());                             // 250
    ASSERT_TRUE(m.set_zone(j, 7).ok());                               // 260
    ASSERT_TRUE(m.drive_to(j, 400).ok());                             // 220
    EXPECT_EQ(m.get_target(j).value(), 400);                          // 170
    ASSERT_TRUE(m.drive_dist(j, -100).ok());                          // 200
    EXPECT_EQ(m.get_target(j).value(), 300);
  }
  arm->advance(std::chrono::seconds(2));
  for (int j = 1; j <= 7; ++j) {
    SCOPED_TRACE("joint " + std::to_string(j));
    EXPECT_TRUE(m.check_target_reached(j).value());                   // 300
    const std::int16_t p = m.get_position(j).value();                 // 160
    EXPECT_LE(std::abs(p - 300), 7);
    ASSERT_TRUE(m.drive_dist_max(j, 50).ok());                        // 210
    const std::int16_t t = m.get_target(j).value();
    EXPECT_LE(std::abs(t - (p + 50)), 2);  // position may creep inside the zone meanwhile
    ASSERT_TRUE(m.set_pid_state(j, false).ok());                      // 120, loop off
  }
  // Loop off: every joint coasts to rest. The position on the bus is then exactly the
  // motor model's encoder count: no edge was lost by the controller (or by the firmware's
  // interrupts) over the whole test.
  arm->advance(milliseconds(500));
  for (int j = 1; j <= 7; ++j) {
    SCOPED_TRACE("joint " + std::to_string(j));
    EXPECT_EQ(m.get_position(j).value(), arm->hardware(j).encoder_count());
    EXPECT_EQ(m.get_target(j).value(), arm->hardware(j).encoder_count());  // follows position
    ASSERT_TRUE(m.home(j).ok());                                      // 110
    EXPECT_EQ(m.get_target(j).value(), 0);
    EXPECT_EQ(m.get_position(j).value(), 0);
  }
  EXPECT_EQ(m.counters().failures, 0u);
  EXPECT_EQ(arm->bus().stats().contentions, 0u);
}

TEST_P(HilCommands, UnknownCommandIs930AndReadsNoData) {
  auto arm = make();
  BusMaster m(arm->link());
  for (std::int16_t code : {3, 5, 99, -1}) {
    auto r = m.transact(3, code, std::nullopt);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(joint_bus::joint_failure(r.error())->code(), 930) << code;
    EXPECT_EQ(joint_bus::joint_failure(r.error())->status_word, 930) << code;
  }
  EXPECT_EQ(m.ping(3, 77).value(), 77);  // still in step: no DATA was swallowed
}

TEST_P(HilCommands, BadDataIs940AndChangesNothing) {
  auto arm = make();
  BusMaster m(arm->link());
  ASSERT_TRUE(m.drive_to(1, 500).ok());
  EXPECT_EQ(joint_bus::joint_failure(m.set_speed(1, 101).error())->code(), 940);
  EXPECT_EQ(joint_bus::joint_failure(m.set_speed(1, -1).error())->code(), 940);
  EXPECT_EQ(joint_bus::joint_failure(m.set_zone(1, -1).error())->code(), 940);
  EXPECT_EQ(joint_bus::joint_failure(m.transact(1, joint_bus::cmd_set_pid_state, 5).error())->code(), 940);
  ASSERT_TRUE(m.drive_to(1, 32767).ok());
  auto r = m.drive_dist(1, 1);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(joint_bus::joint_failure(r.error())->code(), 940);
  EXPECT_EQ(joint_bus::joint_failure(r.error())->status_word, 940);
  EXPECT_EQ(m.get_target(1).value(), 32767);
  EXPECT_EQ(m.counters().failures, 5u);
}

TEST_P(HilCommands, BoardSetToAnotherJointNumberIs910) {
  Scenario s;
  s.believed_number[3] = 5;  // EEPROM of the board on select line 3 says joint 5
  auto arm = make(s);
  BusMaster m(arm->link());
  const auto sent_before = arm->bus().stats().bytes_to_joints;
  auto r = m.drive_to(3, 1000);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(joint_bus::joint_failure(r.error())->code(), 910);
  EXPECT_FALSE(joint_bus::joint_failure(r.error())->command_sent);
  EXPECT_EQ(arm->bus().stats().bytes_to_joints, sent_before);
  EXPECT_EQ(m.ping(2, 7).value(), 7);  // the others are fine
  EXPECT_EQ(m.ping(4, 8).value(), 8);
}

TEST_P(HilCommands, JointThatNeverAnswersIs990AndBlanksNoOther) {
  Scenario s;
  s.dead_lines.insert(5);  // "avr": chip held in reset; "sim": nothing on the line
  auto arm = make(s);
  BusMaster m(arm->link());
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
  EXPECT_EQ(arm->bus().stats().contentions, 0u);
}

std::string param_name(const ::testing::TestParamInfo<Param>& info) {
  return std::get<0>(info.param) + "_" + std::to_string(std::get<1>(info.param));
}

INSTANTIATE_TEST_SUITE_P(Backends, HilCommands,
                         ::testing::Combine(::testing::Values("sim", "avr"),
                                            ::testing::Values(9600u, 115200u)),
                         param_name);

}  // namespace
}  // namespace armctl::hil
