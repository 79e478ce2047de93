#include "web/control_lease.hpp"

#include <cctype>
#include <ctime>

#include <fmt/core.h>

#include "core/printable.hpp"
#include "web/api_error.hpp"

namespace armctl::web {

namespace {

std::string utc_now() {
  const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&t, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

}  // namespace

void ControlLease::take(const std::string& client) {
  if (client.empty())
    throw ApiError(400, "taking control needs an X-Armctl-Client header naming this client (any id, e.g. a random one)");
  std::lock_guard lock(mutex_);
  last_seen_ = clock_();
  holder_left_.reset();
  if (holder_ == client) return;
  holder_ = client;
  since_ = utc_now();
}

void ControlLease::seen(const std::string& client) {
  std::lock_guard lock(mutex_);
  if (holder_ && *holder_ == client) last_seen_ = clock_();
}

void ControlLease::stream_opened(const std::string& client) {
  std::lock_guard lock(mutex_);
  ++streams_[client];
  if (holder_ && *holder_ == client) holder_left_.reset();
}

void ControlLease::stream_closed(const std::string& client) {
  std::lock_guard lock(mutex_);
  auto it = streams_.find(client);
  if (it == streams_.end()) return;
  if (--it->second > 0) return;
  streams_.erase(it);
  // The page went away (closed, reloaded), or its stream dropped and will reopen.
  if (holder_ && *holder_ == client) holder_left_ = clock_();
}

void ControlLease::expire() const {
  if (!holder_ || streams_.contains(*holder_)) return;
  const auto now = clock_();
  const bool gone = holder_left_ ? now - *holder_left_ >= grace_ : now - last_seen_ >= idle_;
  if (!gone) return;
  holder_.reset();
  since_.clear();
}

void ControlLease::release(const std::string& client) {
  std::lock_guard lock(mutex_);
  if (holder_ && *holder_ == client) {
    holder_.reset();
    since_.clear();
  }
}

ControlView ControlLease::view(const std::string& client) const {
  std::lock_guard lock(mutex_);
  expire();
  return {holder_ && !client.empty() && *holder_ == client, holder_.has_value(), since_};
}

std::optional<std::string> ControlLease::holder() const {
  std::lock_guard lock(mutex_);
  expire();
  return holder_;
}

void ControlLease::require(const std::string& client) const {
  std::lock_guard lock(mutex_);
  expire();
  if (holder_ && !client.empty() && *holder_ == client) return;
  if (client.empty())
    throw ApiError(409, "this request names no client (X-Armctl-Client header): take control first with POST "
                        "/api/v1/control {\"take\": true} and that header");
  if (!holder_)
    throw ApiError(409, "no client has control; take it first: POST /api/v1/control {\"take\": true}");
  throw ApiError(409, fmt::format("another client has control (since {}); take over first: POST /api/v1/control "
                                  "{{\"take\": true}}",
                                  since_));
}

std::string check_client_id(std::string_view header, bool present) {
  if (!present) return "";
  const bool ok_chars = !header.empty() && header.size() <= 64 && [&] {
    for (char c : header)
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') return false;
    return true;
  }();
  if (!ok_chars)
    throw ApiError(400, fmt::format("X-Armctl-Client: '{}' is not allowed; 1..64 letters, digits, '-', '_' or '.'",
                                    printable(header.substr(0, 80))));
  return std::string(header);
}

}  // namespace armctl::web
