// The two simulated arms under the Arm API, on simulated time, as test fixtures: the emulated
// xArm board over Robot Commands, and the SCARA's simulated joints on the joint bus.
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include <fmt/core.h>

#include "arm/arm.hpp"
#include "arm/bus_arm_device.hpp"
#include "arm/plan_moves.hpp"
#include "arm/rc_arm_device.hpp"
#include "arm_files.hpp"
#include "joint_bus/sim_fixture.hpp"
#include "robot_commands/sim_links.hpp"

namespace armctl::arm::testing {

// A turn of `joint` by `radians`, planned from where the arm stands with the scene it has
// now, as move `line` of a file ("line N (PTP)").
inline Plan turn(Arm& arm, std::size_t joint, double radians, std::size_t line) {
  const auto from = arm.read().value().positions;
  PtpMove ptp;
  std::vector<std::optional<double>> targets(from.size());
  targets[joint] = from[joint] + radians;
  ptp.target = targets;
  return plan_moves(*arm.kinematics(), from, std::vector<Move>{{ptp, fmt::format("line {} (PTP)", line), line}}).value();
}

class XarmOnEmulator : public ::testing::Test {
 protected:
  robot_commands::testing::EmulatedLink link{9600};
  robot_commands::Client client{link};
  Arm arm{shipped("xarm"), std::make_unique<RcArmDevice>(shipped("xarm"), client)};
  std::vector<double> here() { return arm.read().value().positions; }
};

class ScaraOnBus : public ::testing::Test {
 protected:
  std::unique_ptr<joint_sim::SimArm> sim = test::make_arm(115200);
  joint_bus::BusMaster master{sim->link()};
  Arm arm{shipped("scara"), std::make_unique<BusArmDevice>(shipped("scara"), master, sim->link(), "simulated SCARA")};
  std::vector<double> here() { return arm.read().value().positions; }
  // An obstacle holds joint `number` (its joint-bus number) within a few clicks of where it
  // stands.
  void hold_where_it_stands(int number) {
    auto& hw = sim->joint(number).hardware();
    const auto at = static_cast<std::int32_t>(hw.position_clicks());
    hw.set_end_stops({at - 5, at + 5});
  }
};

}  // namespace armctl::arm::testing
