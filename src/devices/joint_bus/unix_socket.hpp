// Small helpers for the sim link's unix stream sockets (no SIGPIPE, errors as ArmctlError).
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "core/clock.hpp"

namespace armctl::joint_bus::sim_link {

int connect_unix(const std::string& path);  // throws ArmctlError(io) naming the path
int listen_unix(const std::string& path);   // replaces a stale socket file; throws on failure
// Sends everything; false if the peer is gone.
bool send_all(int fd, std::span<const std::uint8_t> bytes);
// Waits (steady clock) until fd is readable or `deadline`; then reads what is there.
// Returns bytes read; 0 on timeout; -1 if the peer closed or the socket failed.
long receive_some(int fd, std::span<std::uint8_t> buffer, TimePoint deadline, const Clock& clock);

}  // namespace armctl::joint_bus::sim_link
