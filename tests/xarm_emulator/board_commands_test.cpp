// Every Robot Commands request against the emulated xArm, in process on a SimClock.
#include "harness.hpp"

namespace armctl::xarm::test {
namespace {

using rc::ServoTarget;

TEST(XarmCommands, MultiServoMoveVectorIsTimedAndLinear) {
  Emulated e;
  e.send(vector_bytes("MultiServoMove 6 servos, 1500 ms"));
  EXPECT_EQ(e.position(1), 500);  // nothing moved yet at t = 0
  e.advance_ms(750);              // halfway: 500 -> 300 is at 400
  EXPECT_EQ(e.position(1), 400);
  EXPECT_EQ(e.position(6), 650);  // 500 -> 800
  EXPECT_TRUE(e.emulator.servos().moving(1));
  e.advance_ms(750);
  EXPECT_EQ(e.position(1), 300);
  EXPECT_EQ(e.position(2), 400);
  EXPECT_EQ(e.position(3), 500);
  EXPECT_EQ(e.position(4), 600);
  EXPECT_EQ(e.position(5), 700);
  EXPECT_EQ(e.position(6), 800);
  EXPECT_FALSE(e.emulator.servos().moving(1));
  EXPECT_TRUE(e.out.empty());  // MultiServoMove has no reply
  EXPECT_EQ(e.stats().handled, 1u);
}

TEST(XarmCommands, NullPositionLeavesServoAlone) {
  Emulated e;
  e.send(rc::MultiServoMove{0, {{2, 700}}});
  e.advance_ms(1000);
  ASSERT_EQ(e.position(2), 700);
  e.send(vector_bytes("MultiServoMove 2 servos, 1000 ms"));  // 1 -> 500, 2 null
  e.send(rc::MultiServoMove{1000, {{1, 900}, {2, std::nullopt}}});
  e.advance_ms(1000);
  EXPECT_EQ(e.position(1), 900);
  EXPECT_EQ(e.position(2), 700);
}

TEST(XarmCommands, ZeroTimeMovesAsFastAsTheServoCan) {
  Emulated e;
  e.send(rc::MultiServoMove{0, {{1, 1000}}});  // 500 units at 1500 units/s = 333 ms
  e.advance_ms(100);
  EXPECT_EQ(e.position(1), 650);
  e.advance_ms(250);
  EXPECT_EQ(e.position(1), 1000);
}

TEST(XarmCommands, MoveIsSynchronizedAllServosArriveTogether) {
  Emulated e;
  // Servo 1 asks for 500 units in 100 ms (too fast: takes 333 ms); servo 2 a small step.
  e.send(rc::MultiServoMove{100, {{1, 0}, {2, 550}}});
  e.advance_ms(167);
  EXPECT_NEAR(e.position(1), 250, 1);
  EXPECT_NEAR(e.position(2), 525, 1);  // halfway too
  e.advance_ms(167);
  EXPECT_EQ(e.position(1), 0);
  EXPECT_EQ(e.position(2), 550);
}

TEST(XarmCommands, ServoPositionReadMatchesVector) {
  Emulated e;
  e.send(rc::MultiServoMove{500, {{2, 300}}});
  e.advance_ms(500);
  e.send(vector_bytes("ServoPositionRead servos 1, 2"));
  EXPECT_EQ(to_hex(e.take_bytes()), to_hex(vector_bytes("ServoPositionRead reply")));
}

TEST(XarmCommands, BatteryVoltageMatchesVectorAndSagsWhileMoving) {
  Emulated e;
  e.send(vector_bytes("GetBatteryVoltage"));
  EXPECT_EQ(to_hex(e.take_bytes()), to_hex(vector_bytes("GetBatteryVoltage reply 7500 mV")));
  e.send(rc::MultiServoMove{1000, {{1, 100}, {2, 900}}});
  e.advance_ms(10);
  e.send(rc::GetBatteryVoltage{});
  ASSERT_EQ(e.out.size(), 1u);
  auto reply = rc::decode_board_message(e.out[0]);
  ASSERT_TRUE(reply.ok());
  auto mv = std::get<rc::BatteryVoltageReply>(*reply).millivolts;
  EXPECT_EQ(mv, 7500 - 2 * XarmServos::kSagPerMovingServo);
  e.out.clear();
  e.advance_ms(1000);
  e.send(rc::GetBatteryVoltage{});
  EXPECT_EQ(std::get<rc::BatteryVoltageReply>(*rc::decode_board_message(e.out[0])).millivolts,
            7500);
}

TEST(XarmCommands, ConfiguredBatteryVoltage) {
  XarmEmulatorOptions options;
  options.battery_millivolts = 6100;
  Emulated e(options);
  e.send(rc::GetBatteryVoltage{});
  EXPECT_EQ(std::get<rc::BatteryVoltageReply>(*rc::decode_board_message(e.out.at(0))).millivolts,
            6100);
}

TEST(XarmCommands, TorqueOffThenNextMoveRestoresIt) {
  Emulated e;
  e.send(rc::MultiServoMove{1000, {{1, 900}, {6, 100}}});
  e.advance_ms(500);  // 1 at 700, 6 at 300
  e.send(vector_bytes("MultiServoOff servos 1 and 6"));
  EXPECT_FALSE(e.emulator.servos().torque(1));
  EXPECT_FALSE(e.emulator.servos().torque(6));
  EXPECT_TRUE(e.emulator.servos().torque(2));
  e.advance_ms(1000);
  EXPECT_EQ(e.position(1), 700);  // limp where it was: the move did not continue
  EXPECT_EQ(e.position(6), 300);
  e.send(rc::MultiServoMove{200, {{1, 500}}});
  EXPECT_TRUE(e.emulator.servos().torque(1));
  EXPECT_FALSE(e.emulator.servos().torque(6));
  e.advance_ms(200);
  EXPECT_EQ(e.position(1), 500);
}

TEST(XarmCommands, OffsetAdjustActsAtOnceAndReadMatchesVector) {
  Emulated e;
  e.send(rc::ServoOffsetAdjust{3, 10});
  e.send(vector_bytes("ServoOffsetAdjust servo 4 by -20"));
  EXPECT_EQ(e.position(3), 510);  // at once, no move needed
  EXPECT_EQ(e.position(4), 480);
  e.send(vector_bytes("ServoOffsetRead servos 3, 4"));
  EXPECT_EQ(to_hex(e.take_bytes()), to_hex(vector_bytes("ServoOffsetRead reply (+10, -20)")));
}

TEST(XarmCommands, OffsetsMakeReadsLeaveZeroToThousand) {
  Emulated e;
  e.send(rc::MultiServoMove{0, {{1, 1000}}});
  e.advance_ms(1000);
  e.send(rc::ServoOffsetAdjust{1, 25});
  e.send(rc::ServoPositionRead{{1}});
  auto reply = std::get<rc::ServoPositionReply>(*rc::decode_board_message(e.out.at(0)));
  EXPECT_EQ(reply.positions.at(0).position, 1025);
}

TEST(XarmCommands, OffsetsAdjustedAreLostOnRestartSavedAreKept) {
  TempDir dir;
  XarmEmulatorOptions options;
  options.state_dir = dir.path();
  {
    Emulated e(options);
    e.send(rc::ServoOffsetAdjust{3, 10});
    e.send(rc::ServoOffsetAdjust{4, -20});
    e.send(vector_bytes("ServoOffsetWrite servo 3"));  // only servo 3 is saved
    EXPECT_EQ(e.emulator.servos().saved_offset(3), 10);
    EXPECT_EQ(e.emulator.servos().saved_offset(4), 0);
  }
  Emulated restarted(options);
  EXPECT_EQ(restarted.emulator.servos().offset(3), 10);
  EXPECT_EQ(restarted.emulator.servos().offset(4), 0);
}

TEST(XarmCommands, ServoSpeedMotorModeTurnsContinuouslyUntilAMove) {
  Emulated e;
  e.send(vector_bytes("ServoSpeed servo 2 motor mode 500"));  // 750 units/s
  EXPECT_EQ(e.emulator.servos().mode(2), rc_board::ServoMode::motor);
  e.advance_ms(1000);
  EXPECT_EQ(e.position(2), 1250);
  e.advance_ms(1000);  // wraps after a turn (1500 units)
  EXPECT_EQ(e.position(2), 500);
  EXPECT_TRUE(e.emulator.servos().moving(2));
  e.send(rc::ServoSpeed{2, rc::ServoMode::motor, static_cast<std::uint16_t>(-1000)});
  e.advance_ms(200);  // -1500 units/s
  EXPECT_EQ(e.position(2), 200);
  e.send(rc::MultiServoMove{100, {{2, 300}}});
  EXPECT_EQ(e.emulator.servos().mode(2), rc_board::ServoMode::servo);
  e.advance_ms(1000);
  EXPECT_EQ(e.position(2), 300);
  e.send(rc::ServoSpeed{2, rc::ServoMode::motor, 1001});  // out of range: ignored
  EXPECT_EQ(e.emulator.servos().mode(2), rc_board::ServoMode::servo);
  EXPECT_EQ(e.stats().out_of_range, 1u);
}

TEST(XarmCommands, BusServoInfoWriteThenReadMatchesVector) {
  XarmEmulatorOptions options;
  options.battery_millivolts = 7400;
  options.temperature = 41;
  Emulated e(options);
  e.send(vector_bytes("BusServoInfoWrite servo 1"));
  e.send(rc::MultiServoMove{0, {{1, 503}}});
  e.advance_ms(100);
  e.send(rc::ServoOffsetAdjust{1, -5});
  e.send(vector_bytes("BusServoInfoRead"));
  EXPECT_EQ(to_hex(e.take_bytes()), to_hex(vector_bytes("BusServoInfoRead reply")));
}

TEST(XarmCommands, BusServoLimitsRefuseMovesOutsideAndPersist) {
  TempDir dir;
  XarmEmulatorOptions options;
  options.state_dir = dir.path();
  {
    Emulated e(options);
    e.send(rc::BusServoInfoWrite{3, 200, 800, 5000, 9000, 70, 1, 5});
    e.send(rc::MultiServoMove{0, {{1, 100}, {3, 900}}});  // 900 > 800: whole frame ignored
    e.advance_ms(1000);
    EXPECT_EQ(e.position(1), 500);
    EXPECT_EQ(e.stats().out_of_range, 1u);
    // min > max (the host library refuses to send it; a board must ignore it)
    e.send_raw(27, hex("03 84 03 64 00 88 13 28 23 46 00 00 00"));
    EXPECT_EQ(e.stats().ignored(), 2u);
    EXPECT_EQ(e.emulator.servos().position_range(3).min, 200);
  }
  Emulated restarted(options);
  restarted.send(rc::BusServoInfoRead{});
  auto info = std::get<rc::BusServoInfoReply>(*rc::decode_board_message(restarted.out.at(0)));
  EXPECT_EQ(info.id, 1);  // the addressed servo is not persisted: servo 1 after a start
  EXPECT_EQ(restarted.emulator.servos().position_range(3).min, 200);
  EXPECT_EQ(restarted.emulator.servos().position_range(3).max, 800);
  restarted.out.clear();
  restarted.send(rc::BusServoInfoWrite{3, 200, 800, 5000, 9000, 70, 1, 5});
  restarted.send(rc::BusServoInfoRead{});
  info = std::get<rc::BusServoInfoReply>(*rc::decode_board_message(restarted.out.at(0)));
  EXPECT_EQ(info.id, 3);
  EXPECT_EQ(info.millivolts_min, 5000);
  EXPECT_EQ(info.temp_max, 70);
  EXPECT_EQ(info.led_warning, 5);
}

TEST(XarmCommands, RequestsWithRepliesAreAnsweredInOrder) {
  Emulated e;
  std::vector<std::uint8_t> burst;
  for (auto name : {"GetBatteryVoltage", "ServoPositionRead servos 1, 2", "BusServoInfoRead"}) {
    auto b = vector_bytes(name);
    burst.insert(burst.end(), b.begin(), b.end());
  }
  e.send(burst);
  ASSERT_EQ(e.out.size(), 3u);
  EXPECT_EQ(e.out[0].cmd, 15);
  EXPECT_EQ(e.out[1].cmd, 21);
  EXPECT_EQ(e.out[2].cmd, 28);
}

}  // namespace
}  // namespace armctl::xarm::test
