// armctl-mega-sim [--baud 9600|115200] [--link PATH]
// Runs the Mega controller firmware on an emulated ATmega2560 driving seven emulated joint
// controllers (joint_avr::AvrMegaArm) and serves its UART0 — Robot Commands — on a pty:
// prints the pty path, then `armctl xarm --device serial:/dev/pts/N --servos 7 ...` drives
// the emulated arm. The emulation follows the wall clock; where eight emulated chips cannot
// keep up with it, emulated time runs slower (replies still come in order, only later).
// SIGINT/SIGTERM stop it.
#include <poll.h>
#include <signal.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "core/error.hpp"
#include "devices/joint_avr/avr_mega_arm.hpp"
#include "devices/joint_sim/arm_config.hpp"
#include "transport/pty.hpp"

namespace {

using namespace armctl;

volatile std::sig_atomic_t stop_requested = 0;
void on_signal(int) { stop_requested = 1; }

struct Args {
  std::uint32_t baud = 9600;
  std::string link;
};

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--baud" && i + 1 < argc) {
      const std::string v = argv[++i];
      if (v != "9600" && v != "115200")
        throw ArmctlError(ErrorKind::invalid_argument, "--baud " + v + ": the Mega images are built for 9600 or 115200");
      a.baud = static_cast<std::uint32_t>(std::stoul(v));
    } else if (arg == "--link" && i + 1 < argc) {
      a.link = argv[++i];
    } else {
      throw ArmctlError(ErrorKind::invalid_argument,
                        "unknown argument '" + arg + "' (allowed: --baud 9600|115200, --link PATH)");
    }
  }
  return a;
}

int serve(const Args& args) {
  joint_sim::ArmConfig config = joint_sim::load_arm_config(joint_sim::default_arm_config_path());
  config.baud = args.baud;
  const std::string elf =
      args.baud == 115200 ? joint_avr::mega_firmware_elf_115200() : joint_avr::default_mega_firmware_elf();
  joint_avr::AvrMegaArm arm(std::move(config), elf, args.baud);
  transport::Pty pty = transport::Pty::open();
  const int fd = pty.master().fd();
  if (!args.link.empty()) {
    ::unlink(args.link.c_str());
    if (::symlink(pty.slave_path().c_str(), args.link.c_str()) != 0)
      throw ArmctlError(ErrorKind::io, "cannot link " + args.link + " to " + pty.slave_path() + ": " +
                                           std::strerror(errno));
  }
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  fmt::print("{}\n", pty.slave_path());
  fmt::print(stderr,
             "mega sim: Mega controller (emulated ATmega2560) + 7 emulated joints, Robot Commands on {}{} at {} "
             "baud (servos 1..7); Ctrl-C to stop\n",
             pty.slave_path(), args.link.empty() ? "" : " linked from " + args.link, args.baud);
  std::fflush(stdout);
  std::fflush(stderr);

  using Wall = std::chrono::steady_clock;
  const Wall::time_point wall0 = Wall::now();
  const TimePoint sim0 = arm.now();
  std::array<std::uint8_t, 256> buffer{};
  while (stop_requested == 0) {
    pollfd p{fd, POLLIN, 0};
    const Duration ahead = (arm.now() - sim0) - std::chrono::duration_cast<Duration>(Wall::now() - wall0);
    const int wait_ms = ahead > Duration::zero()
                            ? int(std::chrono::duration_cast<std::chrono::milliseconds>(ahead).count())
                            : 0;
    if (::poll(&p, 1, wait_ms) > 0 && (p.revents & POLLIN) != 0) {
      const ssize_t n = ::read(fd, buffer.data(), buffer.size());
      if (n > 0) arm.send_upstream(std::span<const std::uint8_t>(buffer.data(), std::size_t(n)));
    }
    const Duration behind = std::chrono::duration_cast<Duration>(Wall::now() - wall0) - (arm.now() - sim0);
    if (behind > Duration::zero()) arm.advance(std::min<Duration>(behind, std::chrono::milliseconds(5)));
    std::vector<std::uint8_t> out;
    for (const auto& b : arm.take_upstream()) out.push_back(b.value);
    if (!out.empty()) pty.master().write(out);
  }
  const double sim_s = std::chrono::duration<double>(arm.now() - sim0).count();
  const double wall_s = std::chrono::duration<double>(Wall::now() - wall0).count();
  fmt::print(stderr, "mega sim: stopped after {:.1f} s of emulated time in {:.1f} s\n", sim_s, wall_s);
  if (!args.link.empty()) ::unlink(args.link.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return serve(parse(argc, argv));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "armctl-mega-sim: %s\n", e.what());
    return 2;
  }
}
