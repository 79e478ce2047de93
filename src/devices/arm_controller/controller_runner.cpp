#include "devices/arm_controller/controller_runner.hpp"

#include <poll.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>

#include <fmt/core.h>

#include "core/error.hpp"
#include "protocol/robot_commands/frame.hpp"

namespace armctl::arm_controller {

namespace {

// A host that never reads must not make the controller block or grow without bound.
constexpr std::size_t kMaxQueuedOutput = 64 * 1024;
// Longest the loop waits on the bus without looking at the host (when no poll fits).
constexpr Duration kUpstreamCheck = std::chrono::milliseconds(2);

[[noreturn]] void bad_upstream(const std::string& text, const std::string& why) {
  throw ArmctlError(ErrorKind::invalid_argument,
                    fmt::format("--upstream \"{}\": {} (allowed: pty, serial:/dev/PATH[?baud=N], "
                                "or a /dev path)",
                                text, why));
}

}  // namespace

Upstream parse_upstream(const std::string& text) {
  Upstream u;
  if (text == "pty") {
    u.pty = true;
    return u;
  }
  std::string rest = text;
  if (rest.rfind("serial:", 0) == 0) rest = rest.substr(7);
  else if (rest.rfind("/dev/", 0) != 0) bad_upstream(text, "not a known form");
  auto q = rest.find('?');
  u.path = rest.substr(0, q);
  if (u.path.empty()) bad_upstream(text, "no device path");
  if (q != std::string::npos) {
    std::string query = rest.substr(q + 1);
    if (query.rfind("baud=", 0) != 0) bad_upstream(text, "the only option is baud=N");
    std::string value = query.substr(5);
    unsigned long baud = 0;
    auto [p, ec] = std::from_chars(value.data(), value.data() + value.size(), baud);
    if (ec != std::errc() || p != value.data() + value.size() || !transport::baud_constant(static_cast<std::uint32_t>(baud)))
      bad_upstream(text, fmt::format("baud \"{}\" is not a standard rate ({})", value,
                                     transport::standard_bauds_text()));
    u.baud = static_cast<std::uint32_t>(baud);
  }
  return u;
}

ControllerRunner::ControllerRunner(const Upstream& upstream) {
  if (upstream.pty) {
    pty_.emplace(transport::Pty::open());
    stream_ = &pty_->master();
    host_path_ = pty_->slave_path();
  } else {
    serial_ = transport::SerialPort::open(upstream.path, upstream.baud);
    stream_ = serial_.get();
    host_path_ = upstream.path;
  }
}

ControllerRunner::~ControllerRunner() = default;

rc_board::Board::Output ControllerRunner::make_output() {
  return [this](const rc::Frame& frame) {
    for (std::uint8_t b : rc::encode_frame(frame)) output_.push_back(b);
    while (output_.size() > kMaxQueuedOutput) {
      output_.pop_front();
      ++dropped_;
    }
    flush_output();  // at once: the reply should not wait for the next bus transaction
  };
}

void ControllerRunner::flush_output() {
  while (!output_.empty()) {
    std::uint8_t chunk[256];
    std::size_t n = std::min(output_.size(), sizeof chunk);
    std::copy_n(output_.begin(), n, chunk);
    ssize_t w = ::write(stream_->fd(), chunk, n);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return;  // EAGAIN: the host is not reading; retried every loop
    output_.erase(output_.begin(), output_.begin() + w);
  }
}

void ControllerRunner::read_upstream(ControllerDevice& device) {
  for (;;) {
    pollfd p{stream_->fd(), POLLIN, 0};
    if (::poll(&p, 1, 0) <= 0 || !(p.revents & POLLIN)) return;
    std::uint8_t buffer[512];
    ssize_t n = ::read(stream_->fd(), buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;  // EAGAIN, or no host has the pty open
    device.receive(std::span(buffer, static_cast<std::size_t>(n)));
  }
}

void ControllerRunner::run(ControllerDevice& device) {
  while (!stop_) {
    read_upstream(device);
    device.board().poll();
    flush_output();
    device.step(device.clock().now() + kUpstreamCheck);
  }
}

}  // namespace armctl::arm_controller
