#include "devices/xarm_emulator/emulator_runner.hpp"

#include <poll.h>
#include <sys/prctl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <optional>

#include <fmt/core.h>

#include "core/error.hpp"
#include "protocol/robot_commands/frame.hpp"
#include "transport/serial_port.hpp"

namespace armctl::xarm {
namespace {

// A host that never reads must not make the emulator block or grow without bound.
constexpr std::size_t kMaxQueuedOutput = 64 * 1024;

}  // namespace

EmulatorRunner::EmulatorRunner(EmulatorRunnerOptions options, Log log)
    : options_(std::move(options)),
      log_(std::move(log)),
      pty_(transport::Pty::open()),
      emulator_(clock_, options_.emulator, [this](const rc::Frame& f) { on_output(f); }) {
  if (options_.wire_timing && !transport::baud_constant(options_.baud))
    throw ArmctlError(ErrorKind::invalid_argument,
                      fmt::format("baud {} is not a standard rate ({})", options_.baud,
                                  transport::standard_bauds_text()));
  if (log_) emulator_.board().set_log([this](const std::string& m) { log_(m); });
  for (const std::string& problem : emulator_.groups().problems())
    if (log_) log_("state dir: " + problem);
}

EmulatorRunner::~EmulatorRunner() { stop(); }

Duration EmulatorRunner::byte_time() const {
  return wire_time(1, options_.baud);
}

void EmulatorRunner::start() {
  if (thread_.joinable()) return;
  loop_.clear_stop();
  thread_ = std::thread([this] { run(); });
}

void EmulatorRunner::stop() {
  request_stop();
  if (thread_.joinable()) thread_.join();
}

void EmulatorRunner::request_stop() { loop_.request_stop(); }

void EmulatorRunner::with_servos(const std::function<void(XarmServos&)>& f) {
  std::lock_guard lock(emulator_mutex_);
  emulator_.servos().advance_to(clock_.now());
  f(emulator_.servos());
}

rc_board::BoardStats EmulatorRunner::stats() const {
  std::lock_guard lock(stats_mutex_);
  return stats_;
}

void EmulatorRunner::on_output(const rc::Frame& frame) {
  auto bytes = rc::encode_frame(frame);
  const TimePoint now = reply_origin_.value_or(clock_.now());
  if (!options_.wire_timing) {
    output_.push_back({now, std::move(bytes)});
  } else {
    for (std::uint8_t b : bytes) {
      output_free_ = std::max(output_free_, now) + byte_time();
      output_.push_back({output_free_, {b}});  // each byte leaves when its 10 bits are sent
    }
  }
  std::size_t queued = 0;
  for (const Timed& t : output_) queued += t.bytes.size();
  while (queued > kMaxQueuedOutput && !output_.empty()) {
    queued -= output_.front().bytes.size();
    dropped_output_ += output_.front().bytes.size();
    output_.pop_front();
  }
}

void EmulatorRunner::read_input(TimePoint now) {
  std::uint8_t buffer[512];
  for (;;) {
    ssize_t n = ::read(pty_.master().fd(), buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;  // EAGAIN: drained; EIO: no host has the pty open
    if (!options_.wire_timing) {
      emulator_.receive(std::span(buffer, static_cast<std::size_t>(n)));
      continue;
    }
    for (ssize_t i = 0; i < n; ++i) {
      input_free_ = std::max(input_free_, now) + byte_time();
      input_.push_back({input_free_, {buffer[i]}});
    }
  }
}

void EmulatorRunner::flush_output(TimePoint now) {
  // Every byte that is due goes out in one write(): when the loop wakes a little late, the
  // host gets one wake-up for the bytes that piled up, not one per byte.
  std::vector<std::uint8_t> due;
  for (const Timed& t : output_) {
    if (t.at > now) break;
    due.insert(due.end(), t.bytes.begin(), t.bytes.end());
  }
  if (due.empty()) return;
  ssize_t n = 0;
  do {
    n = ::write(pty_.master().fd(), due.data(), due.size());
  } while (n < 0 && errno == EINTR);
  if (n <= 0) return;  // EAGAIN: the host is not reading; try again when writable
  auto written = static_cast<std::size_t>(n);
  while (written > 0) {
    auto& bytes = output_.front().bytes;
    const std::size_t k = std::min(written, bytes.size());
    bytes.erase(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(k));
    written -= k;
    if (bytes.empty()) output_.pop_front();
  }
}

void EmulatorRunner::run() {
  // Linux lets a timed wait end up to 50 us late by default ("timer slack", per thread) to
  // batch wake-ups. With wire timing every reply byte is released by a timed ppoll(), so that
  // slack would land on every round trip (about 14 % of a 115200-baud GetBatteryVoltage).
  ::prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
  const int fd = pty_.master().fd();
  while (!loop_.stop_requested()) {
    std::unique_lock emulator_lock(emulator_mutex_);
    TimePoint now = clock_.now();
    while (!input_.empty() && input_.front().at <= now) {
      // The emulated board answers at the instant the byte has arrived, not when this loop
      // got round to it: a reply's bytes are timed from there, so the loop's own wake-up
      // latency is not added on top of the wire time (late bytes go out at once, together).
      reply_origin_ = input_.front().at;
      emulator_.receive(input_.front().bytes);
      input_.pop_front();
    }
    reply_origin_.reset();
    emulator_.poll();
    {  // before the replies leave, so a host that has its reply sees up-to-date counters
      std::lock_guard lock(stats_mutex_);
      stats_ = emulator_.board().stats();
    }
    flush_output(now);

    std::optional<TimePoint> wake = emulator_.board().next_wakeup();
    auto earliest = [&](TimePoint t) { wake = wake ? std::min(*wake, t) : t; };
    if (!input_.empty()) earliest(input_.front().at);
    bool blocked = !output_.empty() && output_.front().at <= now;  // pty full
    if (!output_.empty() && !blocked) earliest(output_.front().at);

    pollfd fds[1] = {{fd, static_cast<short>(POLLIN | (blocked ? POLLOUT : 0)), 0}};
    std::optional<Duration> timeout;
    if (wake) timeout = *wake - clock_.now();
    emulator_lock.unlock();  // the wait is where with_servos gets its turn
    try {
      if (!loop_.wait(fds, timeout)) return;
    } catch (const ArmctlError& e) {
      if (log_) log_(e.what());
      return;
    }
    if (fds[0].revents & POLLIN) {
      const std::lock_guard lock(emulator_mutex_);
      read_input(clock_.now());
    }
    if ((fds[0].revents & (POLLHUP | POLLERR)) && !(fds[0].revents & POLLIN)) {
      // No host on the other side: nothing to read; do not spin on the hang-up.
      if (!loop_.wait({}, std::chrono::milliseconds(10))) return;
    }
  }
}

}  // namespace armctl::xarm
