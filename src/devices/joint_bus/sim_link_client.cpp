#include "devices/joint_bus/sim_link_client.hpp"

#include <unistd.h>

#include <array>
#include <chrono>

#include <fmt/core.h>

#include "core/error.hpp"
#include "devices/joint_bus/unix_socket.hpp"

namespace armctl::joint_bus {

namespace {
constexpr auto kHelloTimeout = std::chrono::seconds(3);
constexpr auto kFlushTimeout = std::chrono::seconds(2);
// Baud rates a simulated arm may announce: the arm config's lowest, the fastest standard rate.
constexpr std::uint32_t kMinBaud = 300;
constexpr std::uint32_t kMaxBaud = 4'000'000;
}  // namespace

SimLinkClient::SimLinkClient(const std::string& socket_path) : path_(socket_path) {
  fd_ = sim_link::connect_unix(socket_path);
  const TimePoint deadline = clock_.now() + kHelloTimeout;
  try {
    while (joints_ == 0) {
      if (!pump(deadline)) {
        throw ArmctlError(ErrorKind::timeout,
                          fmt::format("simulated arm at {} sent no hello within 3 s (is another "
                                      "client connected? the arm serves one at a time)",
                                      path_));
      }
    }
  } catch (...) {
    if (fd_ >= 0) ::close(fd_);
    throw;
  }
}

SimLinkClient::~SimLinkClient() {
  if (fd_ >= 0) ::close(fd_);  // the arm lowers any select line we left high
}

void SimLinkClient::close_for_protocol_error(const std::string& message) {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  throw ArmctlError(ErrorKind::protocol, message);
}

void SimLinkClient::ensure_open() const {
  if (fd_ < 0)
    throw ArmctlError(ErrorKind::io,
                      fmt::format("link to simulated arm at {} was closed after a protocol error", path_));
}

void SimLinkClient::send(sim_link::Type type, std::span<const std::uint8_t> payload) {
  ensure_open();
  if (!sim_link::send_all(fd_, sim_link::encode(type, payload))) {
    throw ArmctlError(ErrorKind::io, fmt::format("simulated arm at {} closed the connection", path_));
  }
}

void SimLinkClient::set_select(int joint, bool high) {
  if (joint < 1 || joint > joints_) {
    throw ArmctlError(ErrorKind::invalid_argument,
                      fmt::format("select line for joint {} does not exist: joints are 1..{}", joint, joints_));
  }
  const std::array<std::uint8_t, 2> p{static_cast<std::uint8_t>(joint), static_cast<std::uint8_t>(high ? 1 : 0)};
  send(sim_link::Type::select, p);
}

void SimLinkClient::write(std::span<const std::uint8_t> bytes) {
  while (!bytes.empty()) {
    const std::size_t n = std::min<std::size_t>(bytes.size(), 255);
    send(sim_link::Type::write, bytes.first(n));
    bytes = bytes.subspan(n);
  }
}

void SimLinkClient::flush() {
  send(sim_link::Type::flush, {});
  const int want = flushes_done_ + 1;
  const TimePoint deadline = clock_.now() + kFlushTimeout;
  while (flushes_done_ < want) {
    if (!pump(deadline)) {
      throw ArmctlError(ErrorKind::timeout, fmt::format("simulated arm at {} did not confirm a flush", path_));
    }
  }
}

bool SimLinkClient::pump(TimePoint deadline) {
  ensure_open();
  for (;;) {
    if (auto m = parser_.next()) {
      switch (m->type) {
        case sim_link::Type::hello: {
          // The joint count and baud are fixed for the session: the master sized its
          // selects and timing by the first hello, so a second one (fewer joints made
          // set_select throw inside the master) is a protocol error, not an update.
          if (joints_ != 0) {
            close_for_protocol_error(fmt::format(
                "simulated arm at {} sent a second hello ({} bytes) mid-session; expected only "
                "received/flushed/error after the first hello ({} joints, {} baud)",
                path_, m->payload.size(), joints_, baud_));
          }
          if (m->payload.size() != 5 || m->payload[0] < 1 || m->payload[0] > 7) {
            close_for_protocol_error(fmt::format("bad hello from simulated arm at {}", path_));
          }
          const std::uint32_t baud =
              static_cast<std::uint32_t>(m->payload[1]) | (static_cast<std::uint32_t>(m->payload[2]) << 8) |
              (static_cast<std::uint32_t>(m->payload[3]) << 16) |
              (static_cast<std::uint32_t>(m->payload[4]) << 24);
          // The bus timing divides by the baud: a hello with 0 (found by fuzz_sim_link_client)
          // crashed the master with SIGFPE. Allowed: what `armctl sim scara` can run at.
          if (baud < kMinBaud || baud > kMaxBaud) {
            close_for_protocol_error(fmt::format("bad hello from simulated arm at {}: baud {} (allowed: {}..{})",
                                          path_, baud, kMinBaud, kMaxBaud));
          }
          joints_ = m->payload[0];
          baud_ = baud;
          break;
        }
        case sim_link::Type::received: rx_.insert(rx_.end(), m->payload.begin(), m->payload.end()); break;
        case sim_link::Type::flushed: ++flushes_done_; break;
        case sim_link::Type::error:
          close_for_protocol_error(fmt::format("simulated arm at {} refused: {}", path_,
                                               std::string(m->payload.begin(), m->payload.end())));
        default:
          close_for_protocol_error(fmt::format("simulated arm at {} sent a master-side message", path_));
      }
      return true;
    }
    if (parser_.error()) close_for_protocol_error(*parser_.error());
    std::array<std::uint8_t, 512> buf{};
    const long n = sim_link::receive_some(fd_, buf, deadline, clock_);
    if (n < 0) throw ArmctlError(ErrorKind::io, fmt::format("simulated arm at {} closed the connection", path_));
    if (n == 0) return false;
    parser_.push(std::span<const std::uint8_t>(buf.data(), static_cast<std::size_t>(n)));
  }
}

std::optional<std::uint8_t> SimLinkClient::read_byte(TimePoint deadline) {
  while (rx_.empty()) {
    if (!pump(deadline)) return std::nullopt;
  }
  const std::uint8_t b = rx_.front();
  rx_.pop_front();
  return b;
}

std::size_t SimLinkClient::drain() {
  while (pump(clock_.now())) {
  }
  const std::size_t n = rx_.size();
  rx_.clear();
  return n;
}

}  // namespace armctl::joint_bus
