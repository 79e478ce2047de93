#include "devices/arm_controller/controller_runner.hpp"

#include <poll.h>
#include <unistd.h>

#include <cerrno>

#include <fmt/core.h>

#include "core/error.hpp"
#include "protocol/robot_commands/frame.hpp"
#include "transport/device_uri_parts.hpp"

namespace armctl::arm_controller {

namespace {

// A host that never reads must not make the controller block or grow without bound.
constexpr std::size_t kMaxQueuedOutput = 64 * 1024;
// Longest the loop waits on the bus without looking at the host (when no poll fits).
constexpr Duration kUpstreamCheck = std::chrono::milliseconds(2);

constexpr const char* kUpstreamForms = "pty, serial:/dev/PATH[?baud=N], or a /dev path";

template <typename T>
T checked(const std::string& text, Result<T> r) {
  if (!r) {
    throw ArmctlError(transport::uri_error(text, r.error(), kUpstreamForms));
  }
  return std::move(r).value();
}

}  // namespace

Upstream parse_upstream(const std::string& text) {
  auto parts = checked(text, transport::split_uri(text));
  Upstream u;
  if (parts.kind == "pty" && !parts.has_path) {
    checked(text, transport::check_options(parts, {}));
    u.pty = true;
    return u;
  }
  if (parts.kind != "serial") {
    throw ArmctlError(transport::uri_error(
        text, Error{ErrorKind::invalid_argument, "unknown kind of upstream"}, kUpstreamForms));
  }
  const auto serial = checked(text, transport::parse_serial_uri(parts, transport::kDefaultBaud));
  u.path = serial.path;
  u.baud = serial.baud;
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

std::function<void(const rc::Frame&)> ControllerRunner::make_output() {
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

void ControllerRunner::read_upstream(CoreDevice& device) {
  for (;;) {
    pollfd p[1] = {{stream_->fd(), POLLIN, 0}};
    if (!loop_.wait(p, Duration::zero()) || !(p[0].revents & POLLIN)) return;
    std::uint8_t buffer[512];
    ssize_t n = ::read(stream_->fd(), buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;  // EAGAIN, or no host has the pty open
    device.receive(std::span(buffer, static_cast<std::size_t>(n)));
  }
}

void ControllerRunner::run(CoreDevice& device) {
  // The host is looked at between bus steps (each at most kUpstreamCheck long): the bus
  // link's own wait is the loop's wait, so a stop is seen within one step.
  while (!loop_.stop_requested()) {
    read_upstream(device);
    flush_output();
    device.step(device.clock().now() + kUpstreamCheck);
  }
}

}  // namespace armctl::arm_controller
