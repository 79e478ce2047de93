// Which client controls the arm (docs/http-api.md "Control"): one at a time; any client may
// take over (the one that had it sees so in its state), and only the holder may move or
// change the arm — except STOP, which anyone may send. Clients name themselves with the
// X-Armctl-Client header (a random id each page makes). Thread-safe.
#pragma once

#include <chrono>
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

class ControlLease {
 public:
  // Takes control for `client` (from whoever had it).
  void take(const std::string& client);
  // Releases it if `client` holds it.
  void release(const std::string& client);
  ControlView view(const std::string& client) const;
  // Throws ApiError 409 unless `client` holds control.
  void require(const std::string& client) const;

 private:
  mutable std::mutex mutex_;
  std::optional<std::string> holder_;
  std::string since_;
};

// The X-Armctl-Client value, checked: 1..64 characters of letters, digits, '-', '_', '.';
// missing gives "" (a client that can watch but not take control). Throws ApiError 400.
std::string check_client_id(std::string_view header, bool present);

}  // namespace armctl::web
