// The API's routing: method + path pattern -> handler, with the API's error answers: an
// unknown path 404, a known path with another method 405 (and Allow), an ApiError its
// status, an armctl error by its kind (web/api_error.hpp), anything else 500 — always
// {"error": "..."}.
#pragma once

#include <functional>
#include <regex>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "web/httplib.hpp"
#include <nlohmann/json.hpp>

namespace armctl::web {

using json = nlohmann::json;

struct Call {
  const httplib::Request& request;
  httplib::Response& response;
  std::string client;               // X-Armctl-Client (or ?client=), "" if none
  std::vector<std::string> params;  // the pattern's groups
  json body() const;                // parse_body(request.body)
  void reply(const json& body, int status = 200) const;
};

// Adds an armctl error's typed detail to the body of its answer (web/error_detail.hpp).
using ErrorDetailWriter = std::function<void(json& body, const Error& error)>;

// {"error": message} with `status`; with the armctl error behind it, also {"kind": its kind}
// as every armctl app names kinds ("invalid argument", "busy"...; README "Exit status"), and
// what `detail` adds.
void reply_error(httplib::Response& response, int status, const std::string& message, const Error* error = nullptr,
                 const ErrorDetailWriter& detail = {});

class Router {
 public:
  using Handler = std::function<void(Call&)>;
  void add(std::string method, const std::string& pattern, Handler handler);
  // True when some route's pattern matches the path (whatever the method).
  bool knows(const std::string& path) const;
  // Runs the route for the request; false when no pattern matches its path.
  bool dispatch(const httplib::Request& request, httplib::Response& response, const std::string& client) const;
  // How the errors of the routes' handlers show their detail (none by default).
  ErrorDetailWriter error_detail;

 private:
  struct Route {
    std::string method;
    std::regex pattern;
    Handler handler;
  };
  std::vector<Route> routes_;
};

}  // namespace armctl::web
