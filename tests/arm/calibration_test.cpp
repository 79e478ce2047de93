// `calibrate zero`: the new zero is where the joints stand; bad shifts are refused before
// anything is written; the file written (by the calibration layer's writer, as the CLI does)
// loads again with the new zero.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <numbers>

#include <unistd.h>

#include <fmt/core.h>

#include "arm/arm_calibration.hpp"
#include "calibration/arm_file_writer.hpp"
#include "calibration/calibration_changes.hpp"
#include "arm_files.hpp"

namespace armctl::arm {
namespace {

constexpr double kDeg = std::numbers::pi / 180;
namespace fs = std::filesystem;

class Calibration : public ::testing::Test {
 protected:
  void SetUp() override {
    // One directory per test and process: CTest runs these tests side by side.
    dir = fs::temp_directory_path() / fmt::format("armctl-cal-{}-{}", ::testing::UnitTest::GetInstance()->current_test_info()->name(),
                                                  ::getpid());
    fs::create_directories(dir);
    for (const char* f : {"xarm.arm.json", "xarm.urdf", "scara.arm.json", "scara.urdf"})
      fs::copy_file(testing::config_path(f), dir / f, fs::copy_options::overwrite_existing);
  }
  void TearDown() override { fs::remove_all(dir); }
  fs::path dir;
};

TEST_F(Calibration, WhereItStandsBecomesZeroAndIsSaved) {
  ArmModel m = load_arm_model(dir / "xarm.arm.json").value();
  std::vector<double> device{520, 500, 480, 500, 500, 500};  // servo6 at +4.8 deg, servo4 at -4.8 deg
  auto changes = calibrate_zero(m, Protocol::robot_commands, device, {0, 2});
  ASSERT_TRUE(changes) << changes.error().message;
  ASSERT_EQ(changes->size(), 2u);
  EXPECT_NEAR((*changes)[0].shift, 4.8 * kDeg, 1e-9);
  ASSERT_TRUE(calibration::write_calibration(m, calibration::from_zero_changes(m, *changes)));
  ArmModel again = load_arm_model(dir / "xarm.arm.json").value();
  const auto q = again.from_device(Protocol::robot_commands, device);
  EXPECT_NEAR(q[0], 0, 1e-6);
  EXPECT_NEAR(q[2], 0, 1e-6);
  EXPECT_NEAR(q[1], 0, 1e-9);  // untouched
  // The travel stays where it was on the servo: 0..1000 is now -124.8..115.2 deg, inside
  // the URDF's -120..120 deg.
  EXPECT_NEAR(again.joints[0].limits.lower, -120 * kDeg, 1e-6);
  EXPECT_NEAR(again.joints[0].limits.upper, 115.2 * kDeg, 1e-6);
}

TEST_F(Calibration, AJointOutsideItsLimitsIsRefused) {
  auto doc = testing::arm_json("xarm");
  doc["joints"][0]["limits"]["position"] = {"-60deg", "60deg"};
  { std::ofstream(dir / "xarm.arm.json") << doc.dump(); }
  ArmModel m = load_arm_model(dir / "xarm.arm.json").value();
  const auto before = testing::read_text((dir / "xarm.arm.json").string());
  std::vector<double> device{900, 500, 500, 500, 500, 500};  // servo6 at +96 deg
  auto changes = calibrate_zero(m, Protocol::robot_commands, device, {0});
  ASSERT_FALSE(changes);
  EXPECT_NE(changes.error().message.find("outside its limits"), std::string::npos) << changes.error().message;
  EXPECT_EQ(testing::read_text((dir / "xarm.arm.json").string()), before);
}

TEST_F(Calibration, ACoupledPairOutsideItsLimitsIsRefused) {
  ArmModel m = load_arm_model(dir / "scara.arm.json").value();
  std::vector<double> device(7, 0.0);
  device[0] = -15000;
  device[4] = 30000;  // both wrist motors far over: SKE at about 1067 deg
  device[5] = 30000;
  auto changes = calibrate_zero(m, Protocol::joint_bus, device, {4, 5});
  ASSERT_FALSE(changes);
  EXPECT_NE(changes.error().message.find("SKE stands at"), std::string::npos) << changes.error().message;
}

TEST_F(Calibration, CoupledJointsAreZeroedTogether) {
  ArmModel m = load_arm_model(dir / "scara.arm.json").value();
  std::vector<double> device(7, 0.0);
  device[0] = -15000;
  device[4] = 300;
  device[5] = 100;
  auto one = calibrate_zero(m, Protocol::joint_bus, device, {4});
  ASSERT_FALSE(one);
  EXPECT_NE(one.error().message.find("coupled"), std::string::npos);
  auto both = calibrate_zero(m, Protocol::joint_bus, device, {4, 5});
  ASSERT_TRUE(both) << both.error().message;
  ASSERT_TRUE(calibration::write_calibration(m, calibration::from_zero_changes(m, *both)));
  ArmModel again = load_arm_model(dir / "scara.arm.json").value();
  const auto q = again.from_device(Protocol::joint_bus, device);
  EXPECT_NEAR(q[4], 0, 1e-6);
  EXPECT_NEAR(q[5], 0, 1e-6);
}

}  // namespace
}  // namespace armctl::arm
