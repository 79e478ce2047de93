// The device registry opens every device URI, the embedded simulators included; the SDK
// libraries parse `sim` but refuse to open it (they link no simulator).
#include <gtest/gtest.h>

#include <filesystem>

#include "core/error.hpp"
#include "devices/device_registry/device_registry.hpp"
#include "devices/joint_bus/bus_master.hpp"
#include "devices/joint_sim/sim_arm.hpp"
#include "devices/robot_commands/client.hpp"
#include "devices/xarm_emulator/emulator_runner.hpp"

namespace armctl::test {
namespace {

TEST(DeviceRegistry, OpensTheEmbeddedSimulatedArm) {
  auto opened = devices::open_joint_bus("sim?baud=115200");
  ASSERT_TRUE(opened) << opened.error().message;
  auto& connection = opened.value();
  ASSERT_NE(connection, nullptr);
  EXPECT_EQ(connection->link().baud(), 115200u);
  EXPECT_EQ(connection->link().joint_count(), 7);
  joint_bus::BusMaster master(connection->link(), connection->default_options());
  auto echo = master.ping(3, 1234);
  ASSERT_TRUE(echo.ok());
  EXPECT_EQ(echo.value(), 1234);
}

TEST(DeviceRegistry, SimWithDeadJointsHasThoseJointsSilent) {
  auto connection = devices::open_joint_bus("sim?dead=2").value();
  joint_bus::BusMaster master(connection->link(), connection->default_options());
  EXPECT_TRUE(master.ping(1, 7).ok());
  EXPECT_FALSE(master.ping(2, 7).ok());
}

TEST(DeviceRegistry, OpensTheEmbeddedEmulatedXarm) {
  ::setenv("ARMCTL_STATE_DIR", ::testing::TempDir().c_str(), 1);
  auto opened = devices::open_robot_commands("sim");
  ASSERT_TRUE(opened) << opened.error().message;
  auto& connection = opened.value();
  ASSERT_NE(connection, nullptr);
  EXPECT_TRUE(connection->embedded());
  robot_commands::Client client(connection->link());
  auto positions = client.read_all_positions();
  ASSERT_TRUE(positions) << positions.error().message;
  ASSERT_EQ(positions->size(), 6u);
  for (const auto& p : *positions) EXPECT_EQ(p.position, 500) << "servo " << int(p.servo);
}

TEST(DeviceRegistry, MiscalOpensAMisassembledSimulatedArmATestCanSee) {
  auto plain = devices::open_joint_bus("sim").value();
  ASSERT_NE(devices::embedded_sim_arm(*plain), nullptr);
  EXPECT_FALSE(devices::embedded_sim_arm(*plain)->miscalibration().has_value());
  auto connection = devices::open_joint_bus("sim?miscal=7").value();
  EXPECT_NE(connection->description().find("mis-assembled"), std::string::npos);
  joint_sim::SimArm* sim = devices::embedded_sim_arm(*connection);
  ASSERT_NE(sim, nullptr);
  ASSERT_TRUE(sim->miscalibration().has_value());
  EXPECT_EQ(describe(*sim->miscalibration()), describe(make_miscalibration(MiscalArm::scara, 7)));
  // The encoders read 0; the joints physically stand at their shifts.
  joint_bus::BusMaster master(connection->link(), connection->default_options());
  EXPECT_EQ(master.get_position(2).value(), 0);
  EXPECT_EQ(sim->true_position(2), sim->miscalibration()->joint(2).zero_shift);
}

TEST(DeviceRegistry, MiscalOpensAMisassembledXarmThatKeepsNothing) {
  const std::string state = ::testing::TempDir() + "/miscal-state";
  ::setenv("ARMCTL_STATE_DIR", state.c_str(), 1);
  auto connection = devices::open_robot_commands("sim?miscal=7").value();
  xarm::EmulatorRunner* runner = devices::embedded_xarm(*connection);
  ASSERT_NE(runner, nullptr);
  const Miscalibration m = make_miscalibration(MiscalArm::xarm, 7);
  // A real-time board: a read nobody answers ends at the timeout, kept short.
  robot_commands::Client client(connection->link(), robot_commands::ClientOptions{.reply_timeout = std::chrono::milliseconds(100)});
  // The place's own ID: nobody answers it (the board answers nothing).
  EXPECT_FALSE(client.read_positions({std::uint8_t(m.duplicate->place)}));
  double truth = 0;
  runner->with_servos([&](xarm::XarmServos& servos) { truth = servos.true_position(1); });
  EXPECT_EQ(truth, 500 + m.joint(1).zero_shift);
  EXPECT_FALSE(std::filesystem::exists(state + "/xarm-emulator"));
}

TEST(DeviceRegistry, BadUrisAreRefusedWithTheAllowedForms) {
  for (const char* uri : {"tcp:1.2.3.4", "sim?speed=3", "serial:/dev/null?baud=7", "sim?miscal=x"}) {
    const auto bus = devices::open_joint_bus(uri);
    ASSERT_FALSE(bus) << uri;
    EXPECT_EQ(bus.error().kind, ErrorKind::invalid_argument) << uri;
    EXPECT_NE(bus.error().message.find("allowed:"), std::string::npos) << bus.error().message;
    const auto board = devices::open_robot_commands(uri);
    ASSERT_FALSE(board) << uri;
    EXPECT_EQ(board.error().kind, ErrorKind::invalid_argument) << uri;
    EXPECT_NE(board.error().message.find("allowed:"), std::string::npos) << board.error().message;
  }
}

TEST(DeviceRegistry, ADeviceThatCannotBeOpenedIsAnErrorNamingIt) {
  const auto bus = devices::open_joint_bus("sim?config=/nonexistent/scara.json");
  ASSERT_FALSE(bus);
  EXPECT_NE(bus.error().message.find("/nonexistent/scara.json"), std::string::npos) << bus.error().message;
  const auto board = devices::open_robot_commands("serial:/nonexistent/ttyUSB0");
  ASSERT_FALSE(board);
  EXPECT_EQ(board.error().kind, ErrorKind::io);
  EXPECT_NE(board.error().message.find("/nonexistent/ttyUSB0"), std::string::npos) << board.error().message;
}

TEST(DeviceRegistry, TheSdkRefusesToOpenASimulator) {
  const auto bus = joint_bus::open_bus(joint_bus::SimDevice{});
  ASSERT_FALSE(bus) << "joint_bus::open_bus opened sim";
  EXPECT_EQ(bus.error().kind, ErrorKind::unsupported);
  EXPECT_NE(bus.error().message.find("devices::open_joint_bus"), std::string::npos)
      << bus.error().message;
  auto uri = robot_commands::parse_device_uri("sim");
  ASSERT_TRUE(uri);
  EXPECT_EQ(uri->kind, robot_commands::DeviceUri::Kind::sim);
  const auto link = robot_commands::open_link(*uri);
  ASSERT_FALSE(link) << "robot_commands::open_link opened sim";
  EXPECT_EQ(link.error().kind, ErrorKind::unsupported);
  EXPECT_NE(link.error().message.find("devices::open_robot_commands"), std::string::npos)
      << link.error().message;
}

}  // namespace
}  // namespace armctl::test
