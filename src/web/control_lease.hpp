// Which client controls the arm (docs/http-api.md "Control"): one at a time; any client may
// take over (the one that had it sees so in its state), and only the holder may move or
// change the arm — except STOP, which anyone may send. Clients name themselves with the
// X-Armctl-Client header (a random id each page makes). Thread-safe.
#pragma once

#include <chrono>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>

namespace armctl::web {

struct ControlView {
  bool you = false;     // the asking client holds it
  bool holder = false;  // some client holds it
  std::string since;    // when it was taken (UTC, ISO 8601), "" when nobody holds it
};

// Control ends by itself when its page goes away: `grace` after the holder's last event
// stream closed (the tab was closed or reloaded; a stream that reopens within it, as
// EventSource does after a dropped connection, keeps control), and after `idle` without a
// request from a holder that never had a stream (a script that took control and ended).
class ControlLease {
 public:
  using Clock = std::function<std::chrono::steady_clock::time_point()>;
  static constexpr std::chrono::seconds kDefaultIdle{60};
  static constexpr std::chrono::seconds kDefaultGrace{5};

  explicit ControlLease(std::chrono::milliseconds idle = kDefaultIdle, std::chrono::milliseconds grace = kDefaultGrace,
                        Clock clock = std::chrono::steady_clock::now)
      : idle_(idle), grace_(grace), clock_(std::move(clock)) {}

  // Takes control for `client` (from whoever had it).
  void take(const std::string& client);
  // A request from `client` arrived (keeps a holder without a stream from going idle).
  void seen(const std::string& client);
  // `client`'s event stream opened or closed.
  void stream_opened(const std::string& client);
  void stream_closed(const std::string& client);
  // Releases it if `client` holds it.
  void release(const std::string& client);
  ControlView view(const std::string& client) const;
  // Who holds control now (nobody: empty), after ending an idle holder's.
  std::optional<std::string> holder() const;
  // Throws ApiError 409 unless `client` holds control.
  void require(const std::string& client) const;

 private:
  // Ends an idle holder's control (mutex_ held).
  void expire() const;

  const std::chrono::milliseconds idle_;
  const std::chrono::milliseconds grace_;
  const Clock clock_;
  mutable std::mutex mutex_;
  mutable std::optional<std::string> holder_;
  mutable std::string since_;
  std::chrono::steady_clock::time_point last_seen_{};
  std::optional<std::chrono::steady_clock::time_point> holder_left_;  // its last stream closed
  std::map<std::string, int> streams_;  // open event streams per client
};

// The X-Armctl-Client value, checked: 1..64 characters of letters, digits, '-', '_', '.';
// missing gives "" (a client that can watch but not take control). Throws ApiError 400.
std::string check_client_id(std::string_view header, bool present);

}  // namespace armctl::web
