// Firmware-only behaviour on emulated silicon: the EEPROM joint number (valid, erased,
// corrupt), the LED blink code, the motor safe state, and a step move that must settle like
// the portable-code simulation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "arm_backends.hpp"
#include "devices/joint_avr/eeprom_image.hpp"
#include "devices/joint_bus/bus_master.hpp"

namespace armctl::hil {
namespace {

using joint_bus::BusMaster;
using std::chrono::milliseconds;

std::unique_ptr<joint_avr::AvrArm> avr_arm(joint_avr::AvrArmOptions options = {}) {
  auto arm = std::make_unique<joint_avr::AvrArm>(hil_arm_config(9600), std::move(options));
  arm->advance(milliseconds(20));
  return arm;
}

TEST(HilFirmware, ErasedOrCorruptEepromNeverAnswersAndBlinks) {
  joint_avr::AvrArmOptions options;
  options.eeprom_overrides[2] = joint_avr::erased_eeprom_image();
  options.eeprom_overrides[3] = joint_avr::raw_eeprom_image(0x4A, 3, 0, 0x00);  // bad check
  options.eeprom_overrides[4] = joint_avr::raw_eeprom_image(0x4A, 9, 0, 0xFF ^ 0x4A ^ 9);  // 9
  auto arm = avr_arm(options);
  BusMaster m(arm->link());
  for (int j : {2, 3, 4}) {
    auto r = m.ping(j, 1);
    ASSERT_FALSE(r.ok()) << j;
    EXPECT_EQ(joint_bus::joint_failure(r.error())->code(), 990) << j;
    EXPECT_FALSE(arm->joint(j).chip().uart_receiver_enabled()) << j;
    EXPECT_FALSE(arm->joint(j).tx_enabled()) << j;
  }
  EXPECT_EQ(m.ping(1, 5).value(), 5);
  // Blink code: two 150 ms flashes every 2 s. Sample the LED of joint 2 every 10 ms for 2 s
  // and count rising edges and lit time.
  int rises = 0;
  int lit_ms = 0;
  bool was = arm->joint(2).chip().led();
  for (int i = 0; i < 200; ++i) {
    arm->advance(milliseconds(10));
    const bool on = arm->joint(2).chip().led();
    if (on && !was) ++rises;
    if (on) lit_ms += 10;
    was = on;
    EXPECT_FALSE(arm->joint(2).chip().bridge_inputs().enable);
  }
  EXPECT_EQ(rises, 2);
  EXPECT_NEAR(lit_ms, 300, 20);
}

TEST(HilFirmware, EepromToolWritesWhatTheFirmwareReads) {
  // firmware/tools/joint_eeprom.sh is how a maker sets the joint number: its Intel HEX must
  // hold exactly the bytes the harness (and the firmware) use.
  const std::string out = std::string(ARMCTL_BINARY_DIR) + "/hil_joint6.eep";
  const std::string cmd = std::string(ARMCTL_SOURCE_DIR) + "/firmware/tools/joint_eeprom.sh 6 115200 " +
                          out + " > /dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  std::ifstream in(out);
  std::string record;
  std::getline(in, record);
  const auto image = joint_avr::joint_eeprom_image(6, 115200, std::nullopt);
  char expected[32];
  std::snprintf(expected, sizeof expected, ":04000000%02X%02X%02X%02X", image[0], image[1], image[2],
                image[3]);
  EXPECT_EQ(record.substr(0, 17), expected);
  const std::string bad = std::string(ARMCTL_SOURCE_DIR) + "/firmware/tools/joint_eeprom.sh 8 " + out +
                          " 2> /dev/null";
  EXPECT_NE(std::system(bad.c_str()), 0);  // joint 8 refused
}

TEST(HilFirmware, ResetLeavesTheMotorInTheSafeState) {
  auto arm = avr_arm();
  BusMaster m(arm->link());
  ASSERT_TRUE(m.drive_to(2, 3000).ok());
  arm->advance(milliseconds(100));
  ASSERT_TRUE(arm->joint(2).chip().bridge_inputs().enable);  // moving
  arm->joint(2).set_held_in_reset(true);
  arm->advance(milliseconds(1));
  joint_avr::BridgeInputs in = arm->joint(2).chip().bridge_inputs();
  EXPECT_FALSE(in.enable);
  EXPECT_EQ(in.left, 0.0);
  EXPECT_EQ(in.right, 0.0);
  // Released: the first instructions (.init3) drive enable and both inputs LOW; then the
  // firmware starts over with the loop holding position 0 = wherever the joint coasted to.
  arm->joint(2).set_held_in_reset(false);
  arm->advance(std::chrono::microseconds(5));
  in = arm->joint(2).chip().bridge_inputs();
  EXPECT_FALSE(in.enable);
  EXPECT_EQ(in.left, 0.0);
  EXPECT_EQ(in.right, 0.0);
  arm->advance(milliseconds(50));
  EXPECT_EQ(m.get_target(2).value(), 0);
  EXPECT_LE(std::abs(m.get_position(2).value()), 20);  // counted from where it restarted
}

// A step of 2000 clicks on SHOULDER (the heaviest joint) and on SKE, sampled every 20 ms on
// both arms. Tolerance: the emulated chip differs from the host simulation only in timing
// (bus latency of a few microseconds, the control tick phase, 50 us drive sampling), so the
// trajectories must agree within 5 % of the step at every sample and the settle times
// (inside the zone for good) within 40 ms.
struct Trace {
  std::vector<int> position;
  int settled_ms = -1;
};

Trace step_trace(const std::string& backend, int joint, std::int16_t target) {
  auto arm = make_backend(backend, Scenario{});
  arm->advance(milliseconds(20));
  BusMaster m(arm->link());
  EXPECT_TRUE(m.set_zone(joint, 5).ok());
  EXPECT_TRUE(m.drive_to(joint, target).ok());
  Trace t;
  for (int ms = 20; ms <= 2000; ms += 20) {
    arm->advance(milliseconds(20));
    t.position.push_back(static_cast<int>(std::lround(arm->hardware(joint).position_clicks())));
  }
  for (std::size_t i = t.position.size(); i-- > 0;) {
    if (std::abs(t.position[i] - target) > 5) {
      t.settled_ms = static_cast<int>((i + 2) * 20);
      break;
    }
  }
  EXPECT_TRUE(m.check_target_reached(joint).value()) << backend;
  return t;
}

TEST(HilFirmware, StepMoveSettlesLikeThePortableSimulation) {
  for (int joint : {2, 5}) {
    SCOPED_TRACE("joint " + std::to_string(joint));
    const Trace sim = step_trace("sim", joint, 2000);
    const Trace avr = step_trace("avr", joint, 2000);
    ASSERT_EQ(sim.position.size(), avr.position.size());
    int worst = 0;
    for (std::size_t i = 0; i < sim.position.size(); ++i) {
      worst = std::max(worst, std::abs(sim.position[i] - avr.position[i]));
    }
    EXPECT_LE(worst, 100) << "largest difference between the trajectories (clicks)";
    ASSERT_GT(sim.settled_ms, 0);
    ASSERT_GT(avr.settled_ms, 0);
    EXPECT_LE(std::abs(sim.settled_ms - avr.settled_ms), 40)
        << "sim settles at " << sim.settled_ms << " ms, avr at " << avr.settled_ms << " ms";
    EXPECT_LE(std::abs(avr.position.back() - 2000), 5);
    std::printf("joint %d: settle sim %d ms, avr %d ms; worst difference %d clicks\n", joint,
                sim.settled_ms, avr.settled_ms, worst);
  }
}

// Back-to-back transactions to moving joints at 115200: each joint lets go of TX as soon as
// its STATUS is in its UART, from the interrupt that put it there. (Releasing it only from
// the main loop left TX driven whenever that loop had gone to sleep just before the select
// fell: both STATUS bytes went straight to the UART and nothing woke it before the next
// joint's READY.)
TEST(HilFirmware, BackToBackTransactionsNeverMeetATransmitterStillDriven) {
  joint_sim::ArmConfig config = hil_arm_config(115200);
  joint_avr::AvrArm arm(config);
  arm.advance(milliseconds(20));
  BusMaster master(arm.link());
  int failures = 0;
  for (int round = 0; round < 6; ++round) {
    for (int j = 1; j <= 7; ++j) failures += master.drive_to(j, round % 2 == 0 ? 3000 : -1000).ok() ? 0 : 1;
    for (int step = 0; step < 40; ++step) {
      for (int j = 1; j <= 7; ++j) {
        failures += master.ping(j, static_cast<std::int16_t>(step * 7 + j)).ok() ? 0 : 1;
        failures += master.get_position(j).ok() ? 0 : 1;
      }
      arm.advance(milliseconds(10));
    }
  }
  EXPECT_EQ(failures, 0);
  EXPECT_EQ(arm.bus().stats().contentions, 0u);
}

}  // namespace
}  // namespace armctl::hil
