// The bounds `armctl serve` keeps on its clients (web/connection_guard.hpp enforces them;
// docs/http-api.md "Limits" explains them).
#pragma once

#include <chrono>
#include <cstddef>

namespace armctl::web {

struct ConnectionLimits {
  std::size_t max_connections = 64;              // open at once, in total
  std::size_t max_connections_per_address = 48;  // from one client address
  std::chrono::milliseconds request_time{10'000};  // from a request's first byte to its last
  std::size_t max_head_bytes = 64 * 1024;        // request line and headers
  std::size_t max_header_count = 100;
  std::size_t max_event_streams = 32;            // in total
  std::size_t max_event_streams_per_client = 8;  // per page (X-Armctl-Client / ?client=)
};

struct ConnectionCounts {
  std::size_t connections = 0;  // open now
  std::size_t streams = 0;      // of them, event streams
  std::size_t evicted = 0;      // closed so far to make room for new ones
};

}  // namespace armctl::web
