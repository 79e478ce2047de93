#include "web/router.hpp"

#include <fmt/core.h>

#include "core/printable.hpp"
#include "web/api_error.hpp"
#include "web/request_body.hpp"

namespace armctl::web {

json Call::body() const { return parse_body(request.body); }

void Call::reply(const json& body, int status) const {
  response.status = status;
  response.set_header("Cache-Control", "no-store");
  response.set_content(body.dump(-1, ' ', false, json::error_handler_t::replace), "application/json");
}

void reply_error(httplib::Response& response, int status, const std::string& message, const Error* error,
                 const ErrorDetailWriter& detail) {
  response.status = status;
  response.set_header("Cache-Control", "no-store");
  json body{{"error", message}};
  if (error) {
    body["kind"] = to_string(error->kind);
    if (detail) detail(body, *error);
  }
  response.set_content(body.dump(-1, ' ', false, json::error_handler_t::replace), "application/json");
}

void Router::add(std::string method, const std::string& pattern, Handler handler) {
  routes_.push_back({std::move(method), std::regex(pattern), std::move(handler)});
}

bool Router::knows(const std::string& path) const {
  for (const auto& r : routes_)
    if (std::regex_match(path, r.pattern)) return true;
  return false;
}

bool Router::dispatch(const httplib::Request& request, httplib::Response& response, const std::string& client) const {
  std::string allowed;
  const std::string method = request.method == "HEAD" ? "GET" : request.method;
  for (const auto& r : routes_) {
    std::smatch m;
    if (!std::regex_match(request.path, m, r.pattern)) continue;
    if (r.method != method) {
      if (allowed.find(r.method) == std::string::npos) allowed += (allowed.empty() ? "" : ", ") + r.method;
      continue;
    }
    Call call{request, response, client, {}};
    for (std::size_t k = 1; k < m.size(); ++k) call.params.push_back(m[k].str());
    try {
      r.handler(call);
    } catch (const ApiError& e) {
      reply_error(response, e.status(), e.what(), e.error(), error_detail);
    } catch (const ArmctlError& e) {
      reply_error(response, status_of(e.error()), e.what(), &e.error(), error_detail);
    } catch (const std::exception& e) {
      reply_error(response, 500, fmt::format("internal error: {}", printable(e.what())));
    }
    return true;
  }
  if (allowed.empty()) return false;
  response.set_header("Allow", allowed);
  reply_error(response, 405,
              fmt::format("{} is not allowed on {}; allowed: {}", printable(request.method), printable(request.path),
                          allowed));
  return true;
}

}  // namespace armctl::web
