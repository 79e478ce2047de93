// Every request of the Robot Commands SDK against the Mega controller on emulated silicon
// (mega_rig.hpp), including the armctl extension JointFaultRead, and what must survive a
// reset of the Mega (offsets saved with ServoOffsetWrite, BusServoInfoWrite limits, groups).
// Judged by the joints' emulated encoders where something moves.
#include <gtest/gtest.h>

#include "mega_rig.hpp"

namespace armctl::hil {
namespace {

using namespace std::chrono_literals;
using robot_commands::ServoMode;

TEST(MegaSdk, EveryCommandIsAnsweredAsABoardDoes) {
  MegaRig rig(115200);
  auto& c = *rig.client;
  // GetBatteryVoltage, ServoPositionRead.
  auto mv = c.battery_millivolts();
  ASSERT_TRUE(mv.ok()) << mv.error().message;
  EXPECT_EQ(*mv, 24000);
  ASSERT_TRUE(c.read_all_positions().ok());
  // MultiServoMove (one servo left alone), read back.
  ASSERT_TRUE(c.move({{1, 550}, {2, std::nullopt}, {4, 450}}, 600).ok());
  rig.mega.advance(1000ms);
  EXPECT_NEAR(rig.clicks(1), clicks_for(1, 550), 20);
  EXPECT_NEAR(rig.clicks(2), 0, 20);
  auto read = c.read_positions({1, 4});
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_NEAR((*read)[0].position, 550, 1);
  EXPECT_NEAR((*read)[1].position, 450, 1);
  // MultiServoOff (the SDK reads back to confirm).
  ASSERT_TRUE(c.servos_off({5}).ok());
  rig.mega.advance(50ms);
  EXPECT_FALSE(rig.mega.arm().joint(5).chip().bridge_inputs().enable);
  // ServoOffsetAdjust, ServoOffsetRead, ServoOffsetWrite.
  ASSERT_TRUE(c.adjust_offset(6, -40).ok());
  ASSERT_TRUE(c.adjust_offset(7, 25).ok());
  ASSERT_TRUE(c.save_offsets({6}).ok());
  auto offsets = c.read_offsets({6, 7});
  ASSERT_TRUE(offsets.ok()) << offsets.error().message;
  EXPECT_EQ((*offsets)[0].offset, -40);
  EXPECT_EQ((*offsets)[1].offset, 25);
  // BusServoInfoWrite addresses joint 2 and narrows it to 100..900; BusServoInfoRead.
  ASSERT_TRUE(c.write_bus_servo_info({2, 100, 900, 5000, 11000, 70, 0, 3}).ok());
  auto info = c.read_bus_servo_info();
  ASSERT_TRUE(info.ok()) << info.error().message;
  EXPECT_EQ(info->id, 2);
  EXPECT_EQ(info->position_min, 100);
  EXPECT_EQ(info->position_max, 900);
  EXPECT_EQ(info->millivolts_min, 5000);
  EXPECT_EQ(info->millivolts_max, 11000);
  EXPECT_EQ(info->temp_max, 70);
  EXPECT_EQ(info->led_warning, 3);
  EXPECT_EQ(info->position, 500);
  EXPECT_EQ(info->millivolts, 24000) << "the supply";
  // ServoSpeed: motor mode jogs, servo mode stops.
  ASSERT_TRUE(c.set_mode(3, ServoMode::motor, 300).ok());
  rig.mega.advance(400ms);
  ASSERT_TRUE(c.set_mode(3, ServoMode::servo, 0).ok());
  rig.mega.advance(600ms);
  EXPECT_GT(rig.clicks(3), 300) << "jogged";
  // Action groups: GroupDownload, GroupSpeed, GroupRun, GroupStop, GroupErase.
  ASSERT_TRUE(c.download_group(1, {{300, {{1, 520}}}, {300, {{1, 560}}}}).ok());
  ASSERT_TRUE(c.set_group_speed(1, 200).ok());
  ASSERT_TRUE(c.run_group(1, 0).ok());
  auto started = c.wait_event(rig.now() + 500ms);
  ASSERT_TRUE(started.ok()) << started.error().message;
  EXPECT_EQ(started->kind, robot_commands::GroupEventKind::started);
  rig.mega.advance(200ms);
  ASSERT_TRUE(c.stop_group().ok());
  auto stopped = c.wait_event(rig.now() + 500ms);
  ASSERT_TRUE(stopped.ok()) << stopped.error().message;
  EXPECT_EQ(stopped->kind, robot_commands::GroupEventKind::stopped);
  ASSERT_TRUE(c.erase_group(1).ok());
  // JointFaultRead (the armctl extension): a healthy joint.
  auto faults = c.read_joint_faults(1);
  ASSERT_TRUE(faults.ok()) << faults.error().message;
  ASSERT_TRUE(faults->has_value());
  EXPECT_TRUE((*faults)->answering && (*faults)->following && !(*faults)->behind_ramp);

  // A reset (the watchdog, or the USB port opened): the saved offset and the limits stay,
  // the adjusted-only offset is gone, BusServoInfo addresses joint 1 again.
  rig.mega.advance(200ms);  // the EEPROM writes (3.4 ms a byte) are done
  rig.mega.reset_mega();
  rig.mega.advance(400ms);
  offsets = c.read_offsets({6, 7});
  ASSERT_TRUE(offsets.ok()) << offsets.error().message;
  EXPECT_EQ((*offsets)[0].offset, -40) << "saved with ServoOffsetWrite";
  EXPECT_EQ((*offsets)[1].offset, 0) << "only adjusted: lost";
  info = c.read_bus_servo_info();
  ASSERT_TRUE(info.ok()) << info.error().message;
  EXPECT_EQ(info->id, 1);
  EXPECT_EQ(info->position_max, 1000);
  ASSERT_TRUE(c.move({{2, 950}}, 500).ok());  // outside joint 2's kept 100..900: ignored
  rig.mega.advance(1000ms);
  EXPECT_NEAR(rig.clicks(2), 0, 20) << "the limit survived the reset";
  ASSERT_TRUE(c.move({{2, 850}}, 500).ok());  // 14,000 clicks: 2.26 s at the SHOULDER's limits
  rig.mega.advance(2800ms);
  EXPECT_NEAR(rig.clicks(2), clicks_for(2, 850), 20);
}

}  // namespace
}  // namespace armctl::hil
