#include "devices/joint_bus/sim_link_server.hpp"

#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <vector>

#include <fmt/core.h>

#include "core/error.hpp"
#include "devices/joint_bus/unix_socket.hpp"

namespace armctl::joint_bus {

namespace {
// Pacing granularity: simulated time trails the wall clock by <= 1 ms.
constexpr Duration kPacing = std::chrono::milliseconds(1);
}

SimLinkServer::SimLinkServer(transport::JointBusLink& bus, std::string socket_path)
    : bus_(bus), path_(std::move(socket_path)) {
  listen_fd_ = sim_link::listen_unix(path_);
  hold_ = wire_time(4, bus_.baud()) + std::chrono::microseconds(500);
}

SimLinkServer::~SimLinkServer() {
  if (client_fd_ >= 0) ::close(client_fd_);
  if (listen_fd_ >= 0) {
    ::close(listen_fd_);
    ::unlink(path_.c_str());
  }
}

void SimLinkServer::accept_client() {
  const int fd = ::accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC);
  if (fd < 0) return;
  client_fd_ = fd;
  parser_ = sim_link::Parser{};
  ++stats_.clients;
  const std::uint32_t baud = bus_.baud();
  const std::array<std::uint8_t, 5> hello{static_cast<std::uint8_t>(bus_.joint_count()),
                                          static_cast<std::uint8_t>(baud), static_cast<std::uint8_t>(baud >> 8),
                                          static_cast<std::uint8_t>(baud >> 16),
                                          static_cast<std::uint8_t>(baud >> 24)};
  bus_.drain();  // a new master starts on a quiet bus
  if (!sim_link::send_all(client_fd_, sim_link::encode(sim_link::Type::hello, hello))) {
    drop_client("could not send hello");
    return;
  }
  if (log_) log_("master connected");
}

void SimLinkServer::drop_client(const std::string& why) {
  ::close(client_fd_);
  client_fd_ = -1;
  // A master that leaves mid-transaction must not leave a joint selected.
  for (int j = 1; j <= bus_.joint_count(); ++j) bus_.set_select(j, false);
  selected_ = 0;
  if (log_) log_("master disconnected: " + why);
}

void SimLinkServer::refuse(const std::string& why) {
  ++stats_.protocol_errors;
  const std::vector<std::uint8_t> text(why.begin(), why.begin() + static_cast<std::ptrdiff_t>(std::min<std::size_t>(why.size(), 255)));
  sim_link::send_all(client_fd_, sim_link::encode(sim_link::Type::error, text));
  drop_client("refused: " + why);
}

bool SimLinkServer::handle(const sim_link::Message& m) {
  switch (m.type) {
    case sim_link::Type::select: {
      if (m.payload.size() != 2 || m.payload[0] < 1 || m.payload[0] > bus_.joint_count() || m.payload[1] > 1) {
        refuse(fmt::format("select needs joint 1..{} and level 0 or 1", bus_.joint_count()));
        return false;
      }
      bus_.set_select(m.payload[0], m.payload[1] == 1);
      if (m.payload[1] == 1) {
        selected_ |= 1 << m.payload[0];
      } else {
        selected_ &= ~(1 << m.payload[0]);
      }
      last_master_sim_ = bus_.clock().now();
      return true;
    }
    case sim_link::Type::write:
      stats_.bytes_from_master += m.payload.size();
      bus_.write(m.payload);
      last_master_sim_ = bus_.clock().now();
      return true;
    case sim_link::Type::flush: {
      if (!m.payload.empty()) {
        refuse("flush takes no payload");
        return false;
      }
      bus_.flush();
      last_master_sim_ = bus_.clock().now();
      // RX bytes that arrived while the TX drained go out before the confirmation.
      forward_received(bus_.clock().now());
      if (client_fd_ < 0) return false;
      if (!sim_link::send_all(client_fd_, sim_link::encode(sim_link::Type::flushed))) {
        drop_client("gone");
        return false;
      }
      return true;
    }
    default:
      refuse("only S, W and F messages are accepted from a master");
      return false;
  }
}

void SimLinkServer::handle_client_bytes() {
  std::array<std::uint8_t, 512> buf{};
  const ssize_t n = ::recv(client_fd_, buf.data(), buf.size(), MSG_DONTWAIT);
  if (n == 0 || (n < 0 && errno != EAGAIN && errno != EINTR)) {
    drop_client("connection closed");
    return;
  }
  if (n < 0) return;
  parser_.push(std::span<const std::uint8_t>(buf.data(), static_cast<std::size_t>(n)));
  while (client_fd_ >= 0) {
    auto m = parser_.next();
    if (!m) {
      if (parser_.error()) refuse(*parser_.error());
      return;
    }
    if (!handle(*m)) return;
  }
}

void SimLinkServer::forward_received(TimePoint sim_until) {
  std::vector<std::uint8_t> got;
  while (auto b = bus_.read_byte(sim_until)) {
    got.push_back(*b);
    if (got.size() == 255) break;
  }
  if (got.empty() || client_fd_ < 0) return;  // with no master, bytes fall on the floor
  stats_.bytes_to_master += got.size();
  if (!sim_link::send_all(client_fd_, sim_link::encode(sim_link::Type::received, got))) {
    drop_client("gone");
  }
}

void SimLinkServer::run() {
  TimePoint last_wall = wall_.now();
  while (!loop_.stop_requested()) {
    pollfd p[1] = {{client_fd_ >= 0 ? client_fd_ : listen_fd_, POLLIN, 0}};
    if (!loop_.wait(p, kPacing)) break;
    if (p[0].revents != 0) {
      if (client_fd_ >= 0) {
        handle_client_bytes();
      } else {
        accept_client();
      }
    }
    // Simulated time moves as far as the wall clock did (it may run ahead briefly after a
    // flush), except while a transaction waits for the master.
    const TimePoint wall_now = wall_.now();
    TimePoint sim_now = bus_.clock().now() + (wall_now - last_wall);
    last_wall = wall_now;
    if (selected_ != 0) sim_now = std::min(sim_now, last_master_sim_ + hold_);
    for (;;) {
      const std::size_t before = stats_.bytes_to_master;
      forward_received(sim_now);
      if (stats_.bytes_to_master - before < 255) break;
    }
    if (tick_) tick_();
  }
  if (client_fd_ >= 0) drop_client("simulated arm stopping");
}

}  // namespace armctl::joint_bus
