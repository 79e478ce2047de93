// Calibration changes as one value: checked as a whole, written in one atomic replacement
// with the previous file kept beside it, nothing written when any part is refused.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <numbers>

#include <unistd.h>

#include <fmt/core.h>

#include "arm_files.hpp"
#include "calibration/arm_file_writer.hpp"

namespace armctl::calibration {
namespace {

constexpr double kDeg = std::numbers::pi / 180;
constexpr double kMm = 1e-3;
namespace fs = std::filesystem;
using arm::Protocol;

class Changes : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = fs::temp_directory_path() /
          fmt::format("armctl-calfit-{}-{}", ::testing::UnitTest::GetInstance()->current_test_info()->name(), ::getpid());
    fs::create_directories(dir);
    for (const char* f : {"xarm.arm.json", "xarm.urdf", "scara.arm.json", "scara.urdf"})
      fs::copy_file(arm::testing::config_path(f), dir / f, fs::copy_options::overwrite_existing);
  }
  void TearDown() override { fs::remove_all(dir); }
  arm::ArmModel load(const char* arm) { return arm::load_arm_model(dir / fmt::format("{}.arm.json", arm)).value(); }
  std::string text(const char* arm) { return arm::testing::read_text((dir / fmt::format("{}.arm.json", arm)).string()); }
  // A refused change leaves the file as it was and writes no .prev.
  void expect_refused(const char* arm, const CalibrationChanges& c, const std::string& words) {
    const arm::ArmModel m = load(arm);
    const std::string before = text(arm);
    auto r = write_calibration(m, c);
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find(words), std::string::npos) << r.error().message;
    EXPECT_EQ(text(arm), before);
    EXPECT_FALSE(fs::exists(previous_file(m.file)));
  }
  fs::path dir;
};

TEST_F(Changes, EveryPartIsWrittenAndThePreviousFileKept) {
  const arm::ArmModel m = load("xarm");
  const std::string before = text("xarm");
  CalibrationChanges c;
  c.joints.push_back({"servo5", true, 0, std::nullopt});
  c.joints.push_back({"servo4", false, 2 * kDeg, std::nullopt});
  c.joints.push_back({"servo6", false, 0, PositionRange{-100 * kDeg, 95 * kDeg}});
  c.gripper = GripperPositions{-60 * kDeg, 40 * kDeg};
  c.link_lengths.push_back({"servo4", 98 * kMm});
  c.servo_offsets.push_back({"servo3", 3, -17});
  auto written = write_calibration(m, c);
  ASSERT_TRUE(written) << written.error().message;
  EXPECT_EQ(arm::testing::read_text(previous_file(m.file).string()), before);
  const arm::ArmModel again = load("xarm");
  const std::vector<double> device{560, 620, 450, 530, 500, 700};
  const auto old_q = m.from_device(Protocol::robot_commands, device);
  const auto new_q = again.from_device(Protocol::robot_commands, device);
  EXPECT_NEAR(new_q[1], -old_q[1], 1e-6);            // servo5 flipped about its zero
  EXPECT_NEAR(new_q[2], old_q[2] + 2 * kDeg, 1e-6);  // servo4 shifted
  EXPECT_NEAR(new_q[3], old_q[3], 1e-9);             // servo3: its offset goes to the servo, not here
  EXPECT_NEAR(new_q[0], old_q[0], 1e-9);
  EXPECT_NEAR(again.joints[0].limits.lower, -100 * kDeg, 1e-6);
  EXPECT_NEAR(again.joints[0].limits.upper, 95 * kDeg, 1e-6);
  // servo4's limits carried over with the shift, inside the URDF's +-120 deg.
  EXPECT_NEAR(again.joints[2].limits.lower, -118 * kDeg, 1e-6);
  EXPECT_NEAR(again.joints[2].limits.upper, 120 * kDeg, 1e-6);
  ASSERT_TRUE(again.gripper);
  EXPECT_NEAR(again.gripper->open, -60 * kDeg, 1e-6);
  EXPECT_NEAR(again.gripper->closed, 40 * kDeg, 1e-6);
  ASSERT_EQ(again.link_lengths.size(), 1u);
  EXPECT_NEAR(again.link_lengths[0].length, 98 * kMm, 1e-9);
  // The returned model is the one the file now holds.
  EXPECT_NEAR(written->joints[2].limits.lower, again.joints[2].limits.lower, 1e-12);
  // A second calibration keeps the first one's file as .prev.
  const std::string first = text("xarm");
  CalibrationChanges c2;
  c2.link_lengths.push_back({"tool_point", 52 * kMm});
  ASSERT_TRUE(write_calibration(again, c2));
  EXPECT_EQ(arm::testing::read_text(previous_file(m.file).string()), first);
  EXPECT_EQ(load("xarm").link_lengths.size(), 2u);
}

TEST_F(Changes, ACoupledPairShiftsBothActuators) {
  const arm::ArmModel m = load("scara");
  CalibrationChanges c;
  c.joints.push_back({"SKE", false, 1.5 * kDeg, std::nullopt});
  ASSERT_TRUE(write_calibration(m, c));
  const arm::ArmModel again = load("scara");
  const std::vector<double> device{0, 100, 200, 300, 400, -250, 50};
  const auto old_q = m.from_device(Protocol::joint_bus, device);
  const auto new_q = again.from_device(Protocol::joint_bus, device);
  EXPECT_NEAR(new_q[4], old_q[4] + 1.5 * kDeg, 1e-6);
  EXPECT_NEAR(new_q[5], old_q[5], 1e-6);
  const auto rc_old = m.from_device(Protocol::robot_commands, {500, 500, 500, 500, 520, 470, 500});
  const auto rc_new = again.from_device(Protocol::robot_commands, {500, 500, 500, 500, 520, 470, 500});
  EXPECT_NEAR(rc_new[4], rc_old[4] + 1.5 * kDeg, 1e-6);
}

TEST_F(Changes, CalibrateZerosChangesAreWrittenAsTheyWereComputed) {
  // `armctl arm calibrate zero`'s changes through write_calibration: the maps and limits
  // calibrate_zero computed, on both arms (the SCARA's wrist pair included), .prev kept.
  struct Case {
    const char* arm;
    Protocol protocol;
    std::vector<double> device;
    std::vector<int> joints;
  };
  for (const Case& k : {Case{"xarm", Protocol::robot_commands, {520, 500, 480, 510, 500, 500}, {0, 2, 3}},
                        Case{"scara", Protocol::joint_bus, {300, 400, -500, 250, 600, -200, 0}, {1, 2, 4, 5}}}) {
    SCOPED_TRACE(k.arm);
    const arm::ArmModel m = load(k.arm);
    const auto zeros = arm::calibrate_zero(m, k.protocol, k.device, k.joints);
    ASSERT_TRUE(zeros) << zeros.error().message;
    auto written = write_calibration(m, from_zero_changes(m, *zeros));
    ASSERT_TRUE(written) << written.error().message;
    EXPECT_TRUE(fs::exists(previous_file(m.file)));
    const arm::ArmModel again = load(k.arm);
    std::vector<bool> zeroed(m.joints.size(), false);
    for (const arm::ZeroChange& c : *zeros) {
      const auto i = std::size_t(c.joint);
      zeroed[i] = true;
      // The protocol the zero was taken on maps as calibrate_zero computed (the layer moves
      // every map of the joint: its zero is one, whichever device reads it).
      const arm::DeviceMap& map = *again.joints[i].map(k.protocol);
      EXPECT_NEAR(map.to_actuator(c.map.device_a), c.map.actuator_a, 1e-6) << m.joints[i].name;
      EXPECT_NEAR(map.to_actuator(c.map.device_b), c.map.actuator_b, 1e-6) << m.joints[i].name;
      EXPECT_NEAR(again.joints[i].limits.lower, c.limits.lower, 1e-6) << m.joints[i].name;
      EXPECT_NEAR(again.joints[i].limits.upper, c.limits.upper, 1e-6) << m.joints[i].name;
    }
    for (std::size_t i = 0; i < m.joints.size(); ++i) {
      if (zeroed[i]) continue;
      EXPECT_NEAR(again.joints[i].limits.lower, m.joints[i].limits.lower, 1e-9) << m.joints[i].name;
      EXPECT_NEAR(again.joints[i].limits.upper, m.joints[i].limits.upper, 1e-9) << m.joints[i].name;
    }
    // Where the joints stand reads zero for the zeroed ones.
    const auto q = again.from_device(k.protocol, k.device);
    for (int j : k.joints) EXPECT_NEAR(q[std::size_t(j)], 0, 1e-6) << m.joints[std::size_t(j)].name;
  }
}

TEST_F(Changes, LimitsThatExcludeTheZeroAreRefused) {
  CalibrationChanges c;
  c.joints.push_back({"servo6", false, 0, PositionRange{5 * kDeg, 60 * kDeg}});
  expect_refused("xarm", c, "exclude its zero");
}

TEST_F(Changes, LimitsBeyondTheDeviceRangeAreRefused) {
  // servo6's zero 10 deg along: servo position 0 now reads -110 deg.
  CalibrationChanges c;
  c.joints.push_back({"servo6", false, 10 * kDeg, PositionRange{-115 * kDeg, 100 * kDeg}});
  expect_refused("xarm", c, "outside the device's range");
}

TEST_F(Changes, LimitsBeyondTheUrdfAreRefused) {
  CalibrationChanges c;
  c.joints.push_back({"servo6", false, 0, PositionRange{-125 * kDeg, 100 * kDeg}});
  expect_refused("xarm", c, "URDF");
}

TEST_F(Changes, OneJointOfACoupledPairCannotBeFlipped) {
  CalibrationChanges c;
  c.joints.push_back({"SKE", true, 0, std::nullopt});
  expect_refused("scara", c, "flip both");
}

TEST_F(Changes, APartThatIsWrongRefusesTheWhole) {
  CalibrationChanges c;
  c.joints.push_back({"servo5", true, 0, std::nullopt});      // fine
  c.link_lengths.push_back({"servo4", 98 * kMm});             // fine
  c.gripper = GripperPositions{-60 * kDeg, 130 * kDeg};       // beyond the gripper's limits
  expect_refused("xarm", c, "outside its limits");
  c.gripper.reset();
  c.servo_offsets.push_back({"servo3", 3, 126});
  expect_refused("xarm", c, "-125..125");
  c.servo_offsets = {{"servo3", 4, 10}};
  expect_refused("xarm", c, "servo 3, not 4");
  c.servo_offsets = {{"servo4", 4, 10}};  // servo4's zero also shifts in the file
  c.joints.push_back({"servo4", false, 1 * kDeg, std::nullopt});
  expect_refused("xarm", c, "choose one");
  c = CalibrationChanges{};
  c.link_lengths.push_back({"servo1", 20 * kMm});  // the gripper's, not the chain's
  expect_refused("xarm", c, "chain");
  c = CalibrationChanges{};
  c.joints.push_back({"elbow", false, 0, std::nullopt});
  expect_refused("xarm", c, "no joint named 'elbow'");
  c = CalibrationChanges{};
  c.joints.push_back({"servo5", false, std::nan(""), std::nullopt});
  expect_refused("xarm", c, "not a number");
}

TEST_F(Changes, AReadOnlyArmFileIsRefusedBeforeAnythingIsWritten) {
  fs::permissions(dir / "xarm.arm.json", fs::perms::owner_write | fs::perms::group_write | fs::perms::others_write,
                  fs::perm_options::remove);
  CalibrationChanges c;
  c.joints.push_back({"servo5", true, 0, std::nullopt});
  expect_refused("xarm", c, "read-only");
}

TEST_F(Changes, AFlippedGripperJointCarriesItsPositions) {
  const arm::ArmModel m = load("xarm");
  CalibrationChanges c;
  c.joints.push_back({"servo1", true, 0, std::nullopt});
  ASSERT_TRUE(write_calibration(m, c));
  const arm::ArmModel again = load("xarm");
  EXPECT_NEAR(again.gripper->open, -m.gripper->open, 1e-6);
  EXPECT_NEAR(again.gripper->closed, -m.gripper->closed, 1e-6);
  // The same physical opening: the device position of "open" is unchanged.
  EXPECT_NEAR(again.joints[5].map(Protocol::robot_commands)->to_device(again.gripper->open),
              m.joints[5].map(Protocol::robot_commands)->to_device(m.gripper->open), 1e-3);
}

}  // namespace
}  // namespace armctl::calibration
