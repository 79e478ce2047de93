// Round trips through the SDK over a pty to the emulated xArm (EmulatorRunner), with the
// emulator's wire timing at 9600 and 115200 baud (ratio = wire-time floor / measured,
// target >= 0.90) and without wire timing (host overhead per command).
#include <chrono>
#include <cstdio>

#include "core/clock.hpp"
#include "devices/robot_commands/client.hpp"
#include "devices/robot_commands/device_uri.hpp"
#include "devices/xarm_emulator/emulator_runner.hpp"
#include "protocol/robot_commands/messages.hpp"

namespace {

using namespace armctl;
using namespace std::chrono_literals;

// Bytes on the wire for one GetBatteryVoltage round trip, counted from the encoder rather
// than written down: request `55 55 02 0F` (4) + reply `55 55 04 0F lo hi` (6).
std::size_t round_trip_bytes() {
  const auto request = rc::encode(rc::GetBatteryVoltage{}, rc::ServoRange::of_count(6)).value();
  const auto reply = rc::encode(rc::BoardMessage{rc::BatteryVoltageReply{7500}}).value();
  return rc::encode_frame(request).size() + rc::encode_frame(reply).size();
}

// The honest floor: every byte is 10 bits (start + 8 data + stop) at `baud`, each direction
// once, no slack added. Anything above it is host, pty and emulator time.
Duration wire_floor(std::uint32_t baud) { return wire_time(round_trip_bytes(), baud); }

// Mean seconds per GetBatteryVoltage round trip.
double measure(bool wire_timing, std::uint32_t baud, int rounds) {
  xarm::EmulatorRunnerOptions options;
  options.wire_timing = wire_timing;
  options.baud = baud;
  xarm::EmulatorRunner runner(options);
  runner.start();
  auto link = robot_commands::open_link(
      robot_commands::parse_device_uri("serial:" + runner.device_path() + "?baud=" +
                                       std::to_string(baud))
          .value())
                  .value();
  robot_commands::Client client(*link, robot_commands::ClientOptions{.reply_timeout = 2s});
  for (int i = 0; i < 3; ++i) client.battery_millivolts().value();  // warm up
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < rounds; ++i) client.battery_millivolts().value();
  const auto t1 = std::chrono::steady_clock::now();
  runner.stop();
  return std::chrono::duration<double>(t1 - t0).count() / rounds;
}

void report_wire(const char* name, std::uint32_t baud, int rounds) {
  const double floor_s = std::chrono::duration<double>(wire_floor(baud)).count();
  const double measured = measure(true, baud, rounds);
  std::printf("BENCH rc_rtt_%s %.3f ms limit %.3f ratio %.3f\n", name, measured * 1e3,
              floor_s * 1e3, floor_s / measured);
  std::printf("BENCH rc_cmds_per_s_%s %.1f cmd/s limit %.1f ratio %.3f\n", name, 1.0 / measured,
              1.0 / floor_s, floor_s / measured);
}

}  // namespace

int main() {
  report_wire("9600", 9600, 60);
  report_wire("115200", 115200, 400);
  // Without wire timing: what the host side (SDK, pty, emulator loop) costs per command.
  // Limit: one 115200-baud wire floor, which host overhead should stay well under.
  const double overhead = measure(false, 115200, 2000);
  const double limit_us = std::chrono::duration<double>(wire_floor(115200)).count() * 1e6;
  std::printf("BENCH rc_host_overhead %.1f us limit %.1f ratio %.3f\n", overhead * 1e6, limit_us,
              limit_us / (overhead * 1e6));
  return 0;
}
