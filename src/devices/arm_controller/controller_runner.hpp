// Serves the arm controller (CoreDevice) to a host over a byte stream (a pty it creates, or a serial
// port): Robot Commands frames in the serial form upstream, the joint bus downstream. One
// thread, one loop (transport::ServeLoop, like every server): read what the host sent, let
// the board act, send replies and notifications, then one bus step (a due command, a short
// wait, or a position poll), so a request waits at most one bus transaction before it is
// handled.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "devices/arm_controller/core_device.hpp"
#include "transport/fd_stream.hpp"
#include "transport/pty.hpp"
#include "transport/serial_port.hpp"
#include "transport/serve_loop.hpp"

namespace armctl::arm_controller {

// Where the host is: "pty" (create one) or "serial:/dev/ttyS0[?baud=N]" / a bare /dev path.
struct Upstream {
  bool pty = false;
  std::string path;
  std::uint32_t baud = 9600;
};
// Throws ArmctlError(invalid_argument) naming what was wrong and the accepted forms.
Upstream parse_upstream(const std::string& text);

class ControllerRunner {
 public:
  // Opens the upstream (throws ArmctlError io). The served device's output must be
  // make_output().
  explicit ControllerRunner(const Upstream& upstream);
  ~ControllerRunner();
  ControllerRunner(const ControllerRunner&) = delete;
  ControllerRunner& operator=(const ControllerRunner&) = delete;

  // Where the device's replies and notifications go.
  std::function<void(const rc::Frame&)> make_output();
  // The path a host opens: the pty slave, or the serial port's path.
  const std::string& host_path() const { return host_path_; }

  // Serves until request_stop() (async-signal-safe).
  void run(CoreDevice& device);
  void request_stop() { loop_.request_stop(); }
  std::size_t dropped_output_bytes() const { return dropped_; }

 private:
  void read_upstream(CoreDevice& device);
  void flush_output();

  std::optional<transport::Pty> pty_;
  std::unique_ptr<transport::SerialPort> serial_;
  transport::FdStream* stream_ = nullptr;
  std::string host_path_;
  std::deque<std::uint8_t> output_;
  std::size_t dropped_ = 0;
  transport::ServeLoop loop_;
};

}  // namespace armctl::arm_controller
