// A program of a user's own, built against the installed armctl package: opens the embedded
// simulated SCARA arm and the embedded emulated xArm by URI, as any app would, and talks to
// both (joint bus master; Robot Commands client and codec).
#include <cstdio>

#include "devices/device_registry/device_registry.hpp"
#include "devices/joint_bus/bus_master.hpp"
#include "devices/robot_commands/client.hpp"

int main() {
  auto bus = armctl::devices::open_joint_bus("sim").value();
  armctl::joint_bus::BusMaster master(bus->link(), bus->default_options());
  const auto echo = master.ping(2, 4321);
  if (!echo.ok() || echo.value() != 4321) {
    std::fprintf(stderr, "consumer: joint 2 did not echo 4321\n");
    return 1;
  }
  auto board = armctl::devices::open_robot_commands("sim").value();
  armctl::robot_commands::Client client(board->link());
  const auto millivolts = client.battery_millivolts();
  if (!millivolts) {
    std::fprintf(stderr, "consumer: battery: %s\n", millivolts.error().message.c_str());
    return 1;
  }
  std::printf("consumer: joint 2 echoed %d on the %s; embedded xArm battery %u mV\n", echo.value(),
              bus->description().c_str(), static_cast<unsigned>(*millivolts));
  return 0;
}
