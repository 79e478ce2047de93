#include "apps/armctl/server_log.hpp"

#include <fmt/core.h>

#include "apps/armctl/json_output.hpp"
#include "core/printable.hpp"

namespace armctl::cli {

void ServerLog::event(const char* name, nlohmann::json fields) const {
  if (!fields.is_object()) fields = nlohmann::json::object();
  fields["source"] = source_;
  print_json_event(name, std::move(fields));
}

void ServerLog::line(const std::string& message) const {
  if (json_) {
    event("log", {{"message", printable(message)}});
    return;
  }
  fmt::print(text_, "{}: {}\n", source_, printable(message));
  std::fflush(text_);
}

void ServerLog::started(nlohmann::json fields, const std::string& text, const std::string& device_path) const {
  if (json_) {
    if (!device_path.empty()) fields["device"] = device_path;
    event("started", std::move(fields));
    return;
  }
  if (!device_path.empty()) {
    fmt::print("{}\n", device_path);
    std::fflush(stdout);
  }
  fmt::print(text_, "{}\n", text);
  std::fflush(text_);
}

void ServerLog::stopped(nlohmann::json fields, const std::string& text) const {
  if (json_) {
    event("stopped", std::move(fields));
    return;
  }
  fmt::print(text_, "{}\n", text);
  std::fflush(text_);
}

}  // namespace armctl::cli
