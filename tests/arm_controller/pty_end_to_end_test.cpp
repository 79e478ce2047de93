// One real end-to-end run: SDK -> serial port (pty slave) -> ControllerRunner -> simulated
// joint bus paced to the wall clock -> seven simulated joints, the runner on its own thread
// as in `armctl controller`.
#include <gtest/gtest.h>

#include <thread>

#include "devices/arm_controller/controller_runner.hpp"
#include "devices/arm_controller/core_device.hpp"
#include "transport/paced_link.hpp"
#include "devices/joint_sim/sim_arm.hpp"
#include "devices/robot_commands/client.hpp"
#include "devices/robot_commands/stream_link.hpp"
#include "transport/serial_port.hpp"

namespace armctl::arm_controller {
namespace {

using namespace std::chrono_literals;

// `make_device(link, output)` builds the controller served; `after(device)` checks it once
// the runner stopped.
template <typename MakeDevice, typename After>
void drive_through_the_pty(MakeDevice make_device, After after) {
  auto arm = joint_sim::SimArm::from_default_config();
  ASSERT_TRUE(transport::runs_on_simulated_time(arm->link()));
  transport::PacedLink paced(arm->link());
  ControllerRunner runner(parse_upstream("pty"));
  auto device = make_device(paced, runner.make_output());
  std::thread serve([&] { runner.run(*device); });

  {
    robot_commands::StreamLink link(transport::SerialPort::open(runner.host_path()), runner.host_path());
    robot_commands::ClientOptions o;
    o.servo_count = 7;
    o.reply_timeout = 1s;
    robot_commands::Client client(link, o);
    auto mv = client.battery_millivolts();
    ASSERT_TRUE(mv.ok()) << mv.error().message;
    EXPECT_EQ(*mv, 24000);
    ASSERT_TRUE(client.move({{1, 550}, {3, 450}, {7, 600}}, 600).ok());
    EXPECT_TRUE(client.pump_events(client.clock().now() + 1000ms));  // the move takes 0.6 s of wall time
    auto p = client.read_positions({1, 3, 7});
    ASSERT_TRUE(p.ok()) << p.error().message;
    EXPECT_NEAR((*p)[0].position, 550, 1);
    EXPECT_NEAR((*p)[1].position, 450, 1);
    EXPECT_NEAR((*p)[2].position, 600, 1);
    ASSERT_TRUE(client.download_group(3, {{300, {{2, 520}}}, {300, {{2, 500}}}}).ok());
    ASSERT_TRUE(client.run_group(3, 1).ok());
    bool finished = false;
    while (auto e = client.wait_event(client.clock().now() + 2s))
      if (e->kind == robot_commands::GroupEventKind::finished) {
        finished = true;
        break;
      }
    EXPECT_TRUE(finished);
  }
  runner.request_stop();
  serve.join();
  after(*device);
}

TEST(PtyEndToEnd, SdkDrivesTheSimulatedArmThroughTheController) {
  drive_through_the_pty(
      [](transport::JointBusLink& link, auto output) {
        return std::make_unique<CoreDevice>(link, load_controller_config(default_controller_config_path()),
                                            CoreDeviceOptions{}, output);
      },
      [](CoreDevice& device) {
        EXPECT_EQ(device.core().stats().ignored_frames, 0u);
        EXPECT_EQ(device.core().stats().actions_played, 2u);
      });
}

}  // namespace
}  // namespace armctl::arm_controller
