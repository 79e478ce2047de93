// The checks every request passes before it is routed (docs/http-api.md "Security"): the
// Host header names this server (no DNS rebinding), an Origin header is this server's own
// (no cross-site requests; without an Origin, a Referer from another site is refused too, and a
// request with neither, as curl and scripts send, is allowed), a body other than a GET's is JSON (an HTML form from another
// site cannot send that type), and off the loopback address the token. Pure code.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace armctl::web {

struct SecurityPolicy {
  std::string listen_host;  // as given to --listen: "127.0.0.1", "0.0.0.0", "::1", "192.168.1.5"
  int port = 0;
  std::string token;        // "" = none needed
};

struct RequestFacts {
  std::string_view method;
  std::optional<std::string_view> host;
  std::optional<std::string_view> origin;
  std::optional<std::string_view> content_type;
  bool has_body = false;
  std::optional<std::string_view> authorization;
  std::optional<std::string_view> token_parameter;  // ?token=
  std::optional<std::string_view> referer;
};

struct Refusal {
  int status;
  std::string message;
};

std::optional<Refusal> check_request(const SecurityPolicy& policy, const RequestFacts& request);

// A loopback address (127.0.0.0/8, ::1, localhost): no token needed there.
bool is_loopback(std::string_view host);

// A random token of 32 hex digits (from /dev/urandom).
std::string make_token();

}  // namespace armctl::web
