// Stop now (issue "Safe in the field", 5): the time from a stop request to every joint at
// rest, on each simulated arm at 9600 and 115200 baud, against the wire time of the stop
// frames.
//  - SCARA on the joint bus (Arm API, BusArmDevice): set_speed 0 to seven joints back to
//    back. Two figures: until the last joint has been told (limit: 7 transactions of wire
//    time), and until every joint is at rest (limit: that plus the slowest joint's braking
//    time at its acceleration limit from the speed it had).
//  - SCARA through the arm controller: a GroupStop frame arrives; the controller tells the
//    seven joints (limit: GroupStop's wire time plus the seven transactions).
//  - xArm (emulated board on a pty with wire-timed replies, real time): GroupStop, a
//    position read and the hold move (limit: those frames' wire time both ways; the pty
//    times only the board's reply, so the figure comes in under it; the emulated servos
//    stop when the board takes GroupStop).
// "At rest" limits: the stop frames' wire time plus the slowest joint's braking from top
// speed at its acceleration limit and 50 ms to settle.
// Simulated time for the SCARA figures: they are the bus's and the joints', not this
// machine's.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "arm/arm.hpp"
#include "arm/bus_arm_device.hpp"
#include "arm/rc_arm_device.hpp"
#include "core/config_files.hpp"
#include "devices/arm_controller/core_device.hpp"
#include "devices/joint_bus/bus_connection.hpp"
#include "devices/joint_sim/sim_arm.hpp"
#include "devices/robot_commands/stream_link.hpp"
#include "devices/xarm_emulator/emulator_runner.hpp"
#include "transport/serial_port.hpp"

namespace {

using namespace armctl;
using namespace std::chrono_literals;

double ms(Duration d) { return std::chrono::duration<double, std::milli>(d).count(); }

arm::ArmModel model(const char* name) { return arm::load_arm_model(arm::arm_file_path(name)).value(); }

std::unique_ptr<joint_sim::SimArm> sim_arm(std::uint32_t baud) {
  auto c = joint_sim::load_arm_config(joint_sim::default_arm_config_path());
  c.baud = baud;
  return std::make_unique<joint_sim::SimArm>(std::move(c));
}

// Steps the simulation until every joint has moved at most 2 clicks (a position loop
// holding dithers by a click) over two 10 ms samples in a row; returns the first of them.
// Gives up after 10 s (printed as such: the figure would then be the cap).
TimePoint at_rest(joint_sim::SimArm& sim) {
  int last[8] = {};
  for (int j = 1; j <= 7; ++j) last[j] = sim.joint(j).controller().position();
  const TimePoint give_up = sim.now() + 10s;
  int still = 0;
  TimePoint first_still = sim.now();
  while (sim.now() < give_up) {
    sim.advance(10ms);
    bool moved = false;
    for (int j = 1; j <= 7; ++j) {
      const int p = sim.joint(j).controller().position();
      if (std::abs(p - last[j]) > 2) moved = true;
      last[j] = p;
    }
    if (moved) {
      still = 0;
    } else if (++still == 1) {
      first_still = sim.now() - 10ms;
    } else if (still == 2) {
      return first_still;
    }
  }
  std::fprintf(stderr, "bench_stop: joints not at rest after 10 s\n");
  return sim.now();
}

// The longest a joint can take to brake: from its top speed at its acceleration limit (the
// joints' tuning, the arm file's joint_bus entries), plus 50 ms for the
// position loop to settle.
Duration worst_braking(const arm::ArmModel& m) {
  double s = 0;
  for (const auto& j : m.joints) {
    const auto* bus = j.map(arm::Protocol::joint_bus);
    s = std::max(s, bus->max_speed_cps / bus->max_accel_cps2);
  }
  return std::chrono::duration_cast<Duration>(std::chrono::duration<double>(s)) + 50ms;
}

void scara_bus(std::uint32_t baud) {
  auto sim = sim_arm(baud);
  joint_bus::BusMaster master(sim->link());
  arm::ArmModel m = model("scara");
  arm::Arm a(m, std::make_unique<arm::BusArmDevice>(m, master, sim->link(), "sim"));
  std::vector<std::optional<double>> t(7);
  t[1] = 2.0;   // SHOULDER
  t[2] = -2.0;  // UAE
  t[0] = 0.28;  // Z
  arm::MoveOptions o;
  o.speed = 1.0;
  (void)a.move_joints(t, o).value();
  joint_bus::idle(sim->link(), 600ms);  // every joint at speed
  const TimePoint t0 = sim->now();
  (void)a.stop().value();
  const Duration told = sim->now() - t0;
  const Duration rest = at_rest(*sim) - t0;
  const Duration wire = wire_time(8, baud) * 7;
  const Duration limit = wire + worst_braking(m);
  std::printf("BENCH stop_scara_bus_told_%u %.3f ms limit %.3f ratio %.3f\n", baud, ms(told), ms(wire),
              ms(told) / ms(wire));
  std::printf("BENCH stop_scara_bus_at_rest_%u %.3f ms limit %.3f ratio %.3f\n", baud, ms(rest), ms(limit),
              ms(rest) / ms(limit));
}

void scara_controller(std::uint32_t baud) {
  auto sim = sim_arm(baud);
  using namespace armctl::arm_controller;
  CoreDevice device(sim->link(), load_controller_config(default_controller_config_path()), CoreDeviceOptions{},
                    [](const rc::Frame&) {});
  device.run_for(300ms);
  device.handle(*rc::encode(rc::Request{rc::MultiServoMove{3000, {{2, 900}, {3, 100}, {1, 800}}}},
                            rc::ServoRange{1, 7}));
  device.run_for(1200ms);
  const TimePoint t0 = device.clock().now();
  const auto stop_frame = *rc::encode(rc::Request{rc::GroupStop{}}, rc::ServoRange{1, 7});
  device.handle(stop_frame);
  // The controller tells every joint set_speed 0 before it polls again: run until then.
  device.run_for(wire_time(8, baud) * 7 + wire_time(8, baud) * 2);
  const Duration rest = at_rest(*sim) - t0;
  const Duration wire = wire_time(rc::encode_frame(stop_frame).size(), baud) + wire_time(8, baud) * 7;
  const Duration limit = wire + worst_braking(model("scara"));
  std::printf("BENCH stop_scara_controller_at_rest_%u %.3f ms limit %.3f ratio %.3f\n", baud, ms(rest), ms(limit),
              ms(rest) / ms(limit));
}

void xarm_board(std::uint32_t baud) {
  xarm::EmulatorRunnerOptions o;
  o.wire_timing = true;
  o.baud = baud;
  xarm::EmulatorRunner runner(o);
  runner.start();
  robot_commands::StreamLink link(transport::SerialPort::open(runner.device_path(), baud), "bench");
  robot_commands::Client client(link);
  arm::ArmModel m = model("xarm");
  arm::Arm a(m, std::make_unique<arm::RcArmDevice>(m, client));
  std::vector<std::optional<double>> t(6);
  t[0] = 1.5;
  arm::MoveOptions mo;
  mo.duration = 3s;
  (void)a.move_joints(t, mo).value();
  (void)client.pump_events(link.clock().now() + 500ms).value();  // lets the move get under way (a failure throws)
  const TimePoint t0 = link.clock().now();
  (void)a.stop().value();
  const Duration took = link.clock().now() - t0;
  // GroupStop (4 bytes), ServoPositionRead of 6 (11) and its reply (23), the hold move (25).
  const Duration wire = wire_time(4 + 11 + 23 + 25, baud);
  std::printf("BENCH stop_xarm_%u %.3f ms limit %.3f ratio %.3f\n", baud, ms(took), ms(wire), ms(took) / ms(wire));
  runner.stop();
}

}  // namespace

int main() {
  for (std::uint32_t baud : {9600u, 115200u}) {
    scara_bus(baud);
    scara_controller(baud);
    xarm_board(baud);
  }
  return 0;
}
