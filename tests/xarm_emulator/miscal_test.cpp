// The emulated xArm mis-assembled on purpose (core/miscalibration.hpp): horns shifted and a
// servo reversed move only the physical arm (true_position); a servo answering another's ID
// shows on the bus as a real board would see it (colliding replies), and setting IDs with one
// servo plugged in at a time fixes it. SimClock throughout.
#include <gtest/gtest.h>

#include <filesystem>

#include "devices/xarm_emulator/bus_replies.hpp"
#include "harness.hpp"

namespace armctl::xarm::test {
namespace {

constexpr std::uint32_t kSeed = 7;

XarmEmulatorOptions miscal_options(std::uint32_t seed = kSeed) {
  XarmEmulatorOptions o;
  o.miscal = make_miscalibration(MiscalArm::xarm, seed);
  return o;
}

// The positions the board answers for `servos`, or nothing when it answered nothing.
std::optional<std::vector<std::int16_t>> read(Emulated& e, std::vector<std::uint8_t> servos) {
  e.out.clear();
  e.send(rc::ServoPositionRead{std::move(servos)});
  if (e.out.empty()) return std::nullopt;
  const auto reply = std::get<rc::ServoPositionReply>(*rc::decode_board_message(e.out.at(0)));
  std::vector<std::int16_t> out;
  for (const auto& p : reply.positions) out.push_back(p.position);
  return out;
}

std::optional<rc::BusServoInfoReply> info(Emulated& e) {
  e.out.clear();
  e.send(rc::BusServoInfoRead{});
  if (e.out.empty()) return std::nullopt;
  return std::get<rc::BusServoInfoReply>(*rc::decode_board_message(e.out.at(0)));
}

TEST(BusReplies, OneServoIsReadAsItAnswered) {
  const std::vector<std::vector<std::uint8_t>> one{{0x2A, 0x02}};
  EXPECT_EQ(read_over_bus(3, kServoPositionReadCmd, one), (std::vector<std::uint8_t>{0x2A, 0x02}));
  EXPECT_EQ(servo_reply_frame(3, kServoPositionReadCmd, one[0]),
            (std::vector<std::uint8_t>{0x55, 0x55, 3, 5, 28, 0x2A, 0x02, std::uint8_t(~(3 + 5 + 28 + 0x2A + 2))}));
  EXPECT_FALSE(read_over_bus(3, kServoPositionReadCmd, {}));
}

TEST(BusReplies, TwoServosCollideIntoTheAndOfTheirFrames) {
  // The same bytes survive the AND: two servos standing at the same position read as one.
  const std::vector<std::vector<std::uint8_t>> same{{0xF4, 0x01}, {0xF4, 0x01}};
  EXPECT_EQ(read_over_bus(2, kServoPositionReadCmd, same), (std::vector<std::uint8_t>{0xF4, 0x01}));
  // 500 and 520: the AND of the checksums is not the checksum of the AND: the board drops it.
  const std::vector<std::vector<std::uint8_t>> apart{{0xF4, 0x01}, {0x08, 0x02}};
  EXPECT_FALSE(read_over_bus(2, kServoPositionReadCmd, apart));
  // Exactly the case where it holds by chance: checked against the arithmetic by hand.
  for (int a = 0; a < 1000; a += 37) {
    for (int b = 0; b < 1000; b += 41) {
      const std::vector<std::vector<std::uint8_t>> two{{std::uint8_t(a & 0xFF), std::uint8_t(a >> 8)},
                                                       {std::uint8_t(b & 0xFF), std::uint8_t(b >> 8)}};
      const int lo = (a & 0xFF) & (b & 0xFF), hi = (a >> 8) & (b >> 8);
      const auto sum_a = std::uint8_t(~(2 + 5 + 28 + (a & 0xFF) + (a >> 8)));
      const auto sum_b = std::uint8_t(~(2 + 5 + 28 + (b & 0xFF) + (b >> 8)));
      const bool valid = std::uint8_t(sum_a & sum_b) == std::uint8_t(~(2 + 5 + 28 + lo + hi));
      const auto got = read_over_bus(2, kServoPositionReadCmd, two);
      EXPECT_EQ(got.has_value(), valid) << a << " " << b;
      if (got) {
        EXPECT_EQ(*got, (std::vector<std::uint8_t>{std::uint8_t(lo), std::uint8_t(hi)}));
      }
    }
  }
}

TEST(XarmMiscal, WithoutMiscalTheTruthIsTheReadingAndEveryIdAnswers) {
  Emulated e;
  e.send(rc::MultiServoMove{0, {{4, 612}}});
  e.advance_ms(500);
  for (ServoId place = 1; place <= 6; ++place) {
    EXPECT_EQ(e.emulator.servos().bus_id(place), place);
    EXPECT_EQ(e.emulator.servos().true_position(place), e.position(place));
  }
  EXPECT_EQ(read(e, {1, 2, 3, 4, 5, 6}), (std::vector<std::int16_t>{500, 500, 500, 612, 500, 500}));
}

TEST(XarmMiscal, ZerosAndTheReversedServoMoveOnlyThePhysicalArm) {
  Emulated e(miscal_options());
  const Miscalibration& m = *e.emulator.servos().miscalibration();
  const auto& dup = *m.duplicate;
  int flipped = 0;
  for (ServoId place = 1; place <= 6; ++place) {
    // At start every servo reads 500; the arm stands where a well-built one reads 500 + shift
    // (mirrored for the reversed one, which at its centre is the same).
    EXPECT_EQ(e.position(place), 500);
    EXPECT_EQ(e.emulator.servos().true_position(place), 500 + m.joint(place).zero_shift) << int(place);
    flipped += m.joint(place).flipped;
  }
  EXPECT_EQ(flipped, 1);
  // A move of each servo that answers its own ID alone: the reversed one goes the other way.
  for (ServoId id = 1; id <= 6; ++id) {
    if (id == dup.place || id == dup.answers_as) continue;
    e.send(rc::MultiServoMove{0, {{id, 600}}});
    e.advance_ms(500);
    const double moved = e.emulator.servos().true_position(id) - (500 + m.joint(id).zero_shift);
    EXPECT_DOUBLE_EQ(moved, m.joint(id).flipped ? -100 : 100) << int(id);
  }
}

TEST(XarmMiscal, TwoServosAnswerOneIdAndNoneTheOther) {
  Emulated e(miscal_options());
  const DuplicateId dup = *e.emulator.servos().miscalibration()->duplicate;
  EXPECT_EQ(e.emulator.servos().bus_id(ServoId(dup.place)), dup.answers_as);
  // Both stand at 500: their replies are the same bytes, so the shared ID reads as one servo.
  EXPECT_EQ(read(e, {ServoId(dup.answers_as)}), (std::vector<std::int16_t>{500}));
  // Nobody answers the place's own ID: the board answers nothing, and says why in its log.
  EXPECT_FALSE(read(e, {ServoId(dup.place)}));
  EXPECT_EQ(e.stats().no_answer, 1u);
  EXPECT_NE(e.emulator.board().last_rejection().find("did not answer"), std::string::npos);
  // The whole arm at once: nothing (one ID of the frame unanswered).
  EXPECT_FALSE(read(e, {1, 2, 3, 4, 5, 6}));
  // A move of the shared ID moves both servos; one of the missing ID moves none.
  e.send(rc::MultiServoMove{0, {{ServoId(dup.answers_as), 700}, {ServoId(dup.place), 300}}});
  e.advance_ms(500);
  EXPECT_EQ(e.position(ServoId(dup.answers_as)), 700);
  EXPECT_EQ(e.position(ServoId(dup.place)), 700);
  // Moved apart (by hand, limp), their replies collide: the board reads what the AND of the
  // two frames makes (bus_replies.hpp), here nothing it can use.
  e.send(rc::MultiServoOff{{ServoId(dup.answers_as)}});
  ASSERT_TRUE(e.emulator.servos().move_by_hand(ServoId(dup.place), 520));
  const std::vector<std::vector<std::uint8_t>> both{{0xBC, 0x02}, {0x08, 0x02}};  // 700, 520
  ASSERT_FALSE(read_over_bus(std::uint8_t(dup.answers_as), kServoPositionReadCmd, both));
  EXPECT_FALSE(read(e, {ServoId(dup.answers_as)}));
  // Offsets written to the shared ID reach both.
  e.send(rc::ServoOffsetAdjust{ServoId(dup.answers_as), 10});
  EXPECT_EQ(e.emulator.servos().offset(ServoId(dup.place)), 10);
  EXPECT_EQ(e.emulator.servos().offset(ServoId(dup.answers_as)), 10);
}

TEST(XarmMiscal, SettingTheIdWithOneServoPluggedInFixesTheDuplicate) {
  Emulated e(miscal_options());
  XarmServos& servos = e.emulator.servos();
  const DuplicateId dup = *servos.miscalibration()->duplicate;
  // Two servos plugged in: BusServoInfoRead collides, no reply.
  for (ServoId place = 1; place <= 6; ++place) servos.set_connected(place, place == 1 || place == dup.place);
  EXPECT_FALSE(info(e));
  // One at a time: each tells its ID.
  for (ServoId place = 1; place <= 6; ++place) {
    for (ServoId other = 1; other <= 6; ++other) servos.set_connected(other, other == place);
    const auto got = info(e);
    ASSERT_TRUE(got) << int(place);
    EXPECT_EQ(got->id, place == dup.place ? dup.answers_as : place) << int(place);
  }
  // The odd one, alone, is given the ID of its place. The write reaches only it.
  for (ServoId other = 1; other <= 6; ++other) servos.set_connected(other, other == dup.place);
  e.send(rc::BusServoInfoWrite{ServoId(dup.place), 0, 1000, 4500, 12000, 85, 0, 0});
  EXPECT_EQ(servos.bus_id(ServoId(dup.place)), dup.place);
  EXPECT_EQ(servos.bus_id(ServoId(dup.answers_as)), dup.answers_as);
  ASSERT_TRUE(info(e));
  EXPECT_EQ(info(e)->id, dup.place);
  // Everything plugged in again: every ID answers, each servo its own.
  for (ServoId place = 1; place <= 6; ++place) servos.set_connected(place, true);
  e.send(rc::MultiServoMove{0, {{1, 510}, {2, 520}, {3, 530}, {4, 540}, {5, 550}, {6, 560}}});
  e.advance_ms(1000);
  EXPECT_EQ(read(e, {1, 2, 3, 4, 5, 6}), (std::vector<std::int16_t>{510, 520, 530, 540, 550, 560}));
}

TEST(XarmMiscal, AnUnpluggedServoGoesLimpAndHearsNothing) {
  Emulated e(miscal_options());
  XarmServos& servos = e.emulator.servos();
  servos.set_connected(1, false);
  EXPECT_FALSE(servos.torque(1));
  e.send(rc::MultiServoMove{0, {{1, 800}}});
  e.advance_ms(500);
  EXPECT_EQ(e.position(1), 500);
  EXPECT_FALSE(read(e, {1}));
  servos.set_connected(1, true);
  e.send(rc::MultiServoMove{0, {{1, 800}}});
  e.advance_ms(500);
  EXPECT_EQ(e.position(1), 800);
}

TEST(XarmMiscal, AHandMovesTheLimpArmToATruePosition) {
  Emulated e(miscal_options());
  XarmServos& servos = e.emulator.servos();
  const Miscalibration& m = *servos.miscalibration();
  EXPECT_FALSE(servos.move_by_hand_to(3, 450));  // torque on: it holds
  e.send(rc::MultiServoOff{{1, 2, 3, 4, 5, 6}});
  for (ServoId place = 1; place <= 6; ++place) {
    ASSERT_TRUE(servos.move_by_hand_to(place, 450));
    EXPECT_DOUBLE_EQ(servos.true_position(place), 450);
    EXPECT_NEAR(e.position(place), m.device_position(place, 450), 0.5);
  }
}

TEST(XarmMiscal, AMisassembledArmKeepsNothingInTheStateDir) {
  TempDir dir;
  XarmEmulatorOptions o = miscal_options();
  o.state_dir = dir.path();
  Emulated e(o);
  e.send(rc::ServoOffsetAdjust{1, 20});
  e.send(rc::ServoOffsetWrite{{1}});
  e.send(rc::BusServoInfoWrite{1, 0, 1000, 4500, 12000, 85, 0, 0});
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

TEST(XarmMiscal, ASeedForTheScaraIsRefused) {
  XarmEmulatorOptions o;
  o.miscal = make_miscalibration(MiscalArm::scara, kSeed);
  SimClock clock;
  EXPECT_THROW(XarmEmulator(clock, o, [](const rc::Frame&) {}), ArmctlError);
}

}  // namespace
}  // namespace armctl::xarm::test
