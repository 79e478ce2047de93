#include "web/security.hpp"

#include <cctype>
#include <fstream>

#include <fmt/core.h>

#include "core/ascii.hpp"
#include "core/error.hpp"
#include "core/printable.hpp"

namespace armctl::web {

namespace {

bool is_ip_literal(std::string_view host) {
  if (host.size() > 2 && host.front() == '[' && host.back() == ']') {
    for (char c : host.substr(1, host.size() - 2))
      if (!std::isxdigit(static_cast<unsigned char>(c)) && c != ':' && c != '.') return false;
    return true;
  }
  if (host.empty()) return false;
  for (char c : host)
    if (!std::isdigit(static_cast<unsigned char>(c)) && c != '.') return false;
  return true;
}

// "[::1]" for an IPv6 listen address as a Host header writes it.
std::string bracketed(const std::string& host) {
  return host.find(':') != std::string::npos && host.front() != '[' ? "[" + host + "]" : host;
}

bool host_allowed(const SecurityPolicy& p, std::string_view header) {
  const std::string h = ascii_lower(header);
  // Split off the port: the last ':' after any ']'.
  const auto bracket = h.rfind(']');
  const auto colon = h.rfind(':');
  std::string name = h, port = "80";
  if (colon != std::string::npos && (bracket == std::string::npos || colon > bracket)) {
    name = h.substr(0, colon);
    port = h.substr(colon + 1);
  }
  if (port != std::to_string(p.port)) return false;
  const std::string listen = ascii_lower(bracketed(p.listen_host));
  if (name == listen || name == "localhost" || name == "127.0.0.1" || name == "[::1]") return true;
  // Listening on every address: any address literal (a DNS name could be rebound to us).
  if (p.listen_host == "0.0.0.0" || p.listen_host == "::") return is_ip_literal(name);
  return false;
}

// Equal in time independent of where they differ.
bool same_secret(std::string_view a, std::string_view b) {
  unsigned diff = a.size() == b.size() ? 0 : 1;
  for (std::size_t i = 0; i < a.size(); ++i) diff |= unsigned(a[i]) ^ unsigned(i < b.size() ? b[i] : 0);
  return diff == 0;
}

bool token_given(const SecurityPolicy& p, const RequestFacts& r) {
  if (r.authorization) {
    const std::string_view a = *r.authorization;
    if (a.size() > 7 && ascii_lower(a.substr(0, 7)) == "bearer " && same_secret(a.substr(7), p.token)) return true;
  }
  return r.token_parameter && same_secret(*r.token_parameter, p.token);
}

// `url` ("http://127.0.0.1:8080/page?x") is at `origin` ("http://127.0.0.1:8080").
bool same_origin_url(std::string_view url, const std::string& origin) {
  if (url.substr(0, origin.size()) != origin) return false;
  return url.size() == origin.size() || url[origin.size()] == '/' || url[origin.size()] == '?' ||
         url[origin.size()] == '#';
}

}  // namespace

bool is_loopback(std::string_view host) {
  const std::string h = ascii_lower(host);
  return h == "localhost" || h == "::1" || h == "[::1]" || h.rfind("127.", 0) == 0;
}

std::optional<Refusal> check_request(const SecurityPolicy& policy, const RequestFacts& r) {
  if (!r.host)
    return Refusal{403, "the request has no Host header; this server answers only to its own address"};
  if (!host_allowed(policy, *r.host))
    return Refusal{403, fmt::format("Host '{}' is not this server; allowed: {}:{}, localhost:{}, 127.0.0.1:{}",
                                    printable(r.host->substr(0, 100)), bracketed(policy.listen_host), policy.port,
                                    policy.port, policy.port)};
  if (!policy.token.empty() && !token_given(policy, r))
    return Refusal{401, "this server needs its token (printed when it started): an 'Authorization: Bearer TOKEN' "
                        "header or ?token=TOKEN"};
  if (r.origin && *r.origin != "http://" + std::string(*r.host))
    return Refusal{403, fmt::format("Origin '{}' is not allowed: only pages served by this server (http://{}) may "
                                    "send requests",
                                    printable(r.origin->substr(0, 100)), printable(*r.host))};
  const bool safe = r.method == "GET" || r.method == "HEAD";
  // Browsers send Origin with every request that can change something; a Referer without it
  // comes from an old browser or an extension, and names the page that sent it. Scripts and
  // curl send neither, and are allowed (they could forge either anyway: the token is what
  // guards a server off the loopback address).
  if (!safe && !r.origin && r.referer && !same_origin_url(*r.referer, "http://" + std::string(*r.host)))
    return Refusal{403, fmt::format("Referer '{}' is not allowed: only pages served by this server (http://{}) may "
                                    "send requests",
                                    printable(r.referer->substr(0, 100)), printable(*r.host))};
  if (!safe && r.has_body) {
    const std::string type = r.content_type ? ascii_lower(*r.content_type) : "";
    const auto semicolon = type.find(';');
    std::string base = type.substr(0, semicolon);
    while (!base.empty() && base.back() == ' ') base.pop_back();
    if (base != "application/json")
      return Refusal{415, fmt::format("Content-Type '{}' is not allowed: a request body must be JSON "
                                      "(Content-Type: application/json)",
                                      printable(type.substr(0, 100)))};
  }
  return std::nullopt;
}

std::string make_token() {
  std::ifstream random("/dev/urandom", std::ios::binary);
  unsigned char bytes[16];
  if (!random.read(reinterpret_cast<char*>(bytes), sizeof bytes))
    throw ArmctlError(ErrorKind::io, "cannot read /dev/urandom for the access token");
  std::string token;
  for (unsigned char b : bytes) token += fmt::format("{:02x}", b);
  return token;
}

}  // namespace armctl::web
