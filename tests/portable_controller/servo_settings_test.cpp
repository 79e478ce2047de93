// Servo settings in the portable core: ServoOffsetWrite and BusServoInfoWrite persisted in
// the memory's settings record (they survive a restart of the core on the same memory),
// BusServoInfoRead, the narrowed range, and refusal of what is malformed or out of range.
#include <gtest/gtest.h>

#include <vector>

#include "memory_rig.hpp"

namespace armctl::controller::testing {
namespace {

std::vector<std::uint8_t> info_write(int servo, int pmin, int pmax, int vmin, int vmax, int temp, int led, int warn) {
  std::vector<std::uint8_t> d{static_cast<std::uint8_t>(servo)};
  for (int v : {pmin, pmax, vmin, vmax, temp}) {
    d.push_back(static_cast<std::uint8_t>(v & 0xFF));
    d.push_back(static_cast<std::uint8_t>(v >> 8));
  }
  d.push_back(static_cast<std::uint8_t>(led));
  d.push_back(static_cast<std::uint8_t>(warn));
  return d;
}

const SentFrame* last_of(const RecordingUpstream& up, std::uint8_t command) {
  for (auto it = up.frames.rbegin(); it != up.frames.rend(); ++it)
    if (it->command == command) return &*it;
  return nullptr;
}

int u16_at(const std::vector<std::uint8_t>& d, int at) { return d[at] | (d[at + 1] << 8); }

TEST(ServoSettings, SavedOffsetsAndLimitsSurviveARestartAndAdjustedOnesDoNot) {
  RamMemory memory;
  {
    GroupRig rig(memory);
    rig.send(rc_servo_offset_adjust, {3, 0xE2, 0xFF});  // -30
    rig.send(rc_servo_offset_adjust, {5, 12, 0});
    rig.send(rc_servo_offset_write, {1, 3});  // only joint 3's is saved
    rig.send(rc_bus_servo_info_write, info_write(2, 100, 900, 5000, 11000, 70, 1, 5));
    rig.run_us(200000);  // the queued writes reach the memory
  }
  GroupRig rig(memory);  // a reset: the core starts again on the same memory
  rig.send(rc_servo_offset_read, {2, 3, 5});
  const SentFrame* offsets = last_of(rig.upstream, rc_servo_offset_read);
  ASSERT_NE(offsets, nullptr);
  EXPECT_EQ(offsets->data, (std::vector<std::uint8_t>{2, 3, 0xE2, 5, 0})) << "saved -30 kept, adjusted 12 lost";
  rig.send(rc_bus_servo_info_write, info_write(4, 0, 1000, 4500, 12000, 85, 0, 0));  // addresses joint 4
  rig.send(rc_bus_servo_info_write, info_write(2, 100, 900, 5000, 11000, 70, 1, 5));  // back to joint 2
  rig.upstream.frames.clear();
  rig.send(rc_bus_servo_info_read, {});
  const SentFrame* info = last_of(rig.upstream, rc_bus_servo_info_read);
  ASSERT_NE(info, nullptr);
  ASSERT_EQ(info->data.size(), 19u);
  EXPECT_EQ(info->data[0], 2);
  EXPECT_EQ(u16_at(info->data, 1), 100);
  EXPECT_EQ(u16_at(info->data, 3), 900);
  EXPECT_EQ(u16_at(info->data, 5), 5000);
  EXPECT_EQ(u16_at(info->data, 7), 11000);
  EXPECT_EQ(u16_at(info->data, 9), 70);
  EXPECT_EQ(info->data[11], 1);
  EXPECT_EQ(info->data[12], 5);
  EXPECT_EQ(info->data[13], 0) << "joint 2's offset";
  EXPECT_EQ(u16_at(info->data, 14), 500) << "its polled position";
  EXPECT_EQ(info->data[16], 0) << "no temperature sensor";
}

TEST(ServoSettings, TheLimitsNarrowWhatAMoveMayAsk) {
  RamMemory memory;
  GroupRig rig(memory);
  rig.send(rc_bus_servo_info_write, info_write(1, 400, 600, 4500, 12000, 85, 0, 0));
  rig.joints.log.clear();
  rig.send(rc_multi_servo_move, {1, 0xE8, 0x03, 1, 0xBC, 0x02});  // 700: outside 400..600
  rig.run_us(100000);
  EXPECT_TRUE(rig.joints.commands_of(joint_bus::cmd_drive_to).empty()) << "ignored whole";
  rig.send(rc_multi_servo_move, {1, 0xE8, 0x03, 1, 0x58, 0x02});  // 600: allowed
  rig.run_us(100000);
  EXPECT_EQ(rig.joints.commands_of(joint_bus::cmd_drive_to).size(), 1u);
}

TEST(ServoSettings, MalformedOrOutOfRangeWritesChangeNothing) {
  RamMemory memory;
  GroupRig rig(memory);
  rig.run_us(200000);
  const std::vector<std::uint8_t> before = memory.bytes;
  const auto ignored = rig.core.stats().ignored_frames;
  rig.send(rc_bus_servo_info_write, info_write(9, 0, 1000, 4500, 12000, 85, 0, 0));    // no joint 9
  rig.send(rc_bus_servo_info_write, info_write(1, 600, 400, 4500, 12000, 85, 0, 0));   // min > max
  rig.send(rc_bus_servo_info_write, info_write(1, 0, 1001, 4500, 12000, 85, 0, 0));    // past 1000
  rig.send(rc_bus_servo_info_write, info_write(1, 0, 1000, 4000, 12000, 85, 0, 0));    // below 4500 mV
  rig.send(rc_bus_servo_info_write, info_write(1, 0, 1000, 4500, 12000, 101, 0, 0));   // over 100 C
  rig.send(rc_bus_servo_info_write, info_write(1, 0, 1000, 4500, 12000, 85, 2, 0));    // LED status 2
  rig.send(rc_bus_servo_info_write, info_write(1, 0, 1000, 4500, 12000, 85, 0, 8));    // warning bit 3
  rig.send(rc_servo_offset_write, {2, 1, 9});  // joint 9: the whole frame
  rig.send(rc_servo_offset_write, {2, 1});     // count disagrees with the length
  rig.send(rc_bus_servo_info_read, {1});       // the read takes no DATA
  rig.run_us(200000);
  EXPECT_EQ(rig.core.stats().ignored_frames, ignored + 10);
  EXPECT_EQ(memory.bytes, before);
}

TEST(ServoSettings, AMemoryWithoutTheRecordGetsTheDefaultsAndATornRecordReadsAsThem) {
  RamMemory memory;
  {
    GroupRig rig(memory);
    rig.run_us(200000);
  }
  // 'S', format 1 at the start of the last 96 bytes: written after the defaults.
  EXPECT_EQ(memory.bytes[4096 - 96], 'S');
  EXPECT_EQ(memory.bytes[4096 - 95], 1);
  // Joint 1's record torn (position max 0xFFFF): it reads as the defaults.
  memory.bytes[4096 - 96 + 2 + 3] = 0xFF;
  memory.bytes[4096 - 96 + 2 + 4] = 0xFF;
  memory.bytes[4096 - 96 + 2] = 40;  // its offset
  GroupRig rig(memory);
  rig.send(rc_servo_offset_read, {1, 1});
  const SentFrame* offsets = last_of(rig.upstream, rc_servo_offset_read);
  ASSERT_NE(offsets, nullptr);
  EXPECT_EQ(offsets->data, (std::vector<std::uint8_t>{1, 1, 0}));
}

}  // namespace
}  // namespace armctl::controller::testing
