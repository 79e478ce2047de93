#include "apps/armctl/bus_report.hpp"

#include <fmt/core.h>

namespace armctl::cli {

int BusReport::failures() const {
  int n = 0;
  for (const auto& r : rows) n += failed(r) ? 1 : 0;
  return n;
}

void print_report(const BusReport& report, bool json) {
  if (json) {
    nlohmann::json doc;
    doc["command"] = report.command;
    doc["device"] = report.device;
    doc["ok"] = report.failures() == 0;
    doc["joints"] = nlohmann::json::array();
    for (const auto& r : report.rows) {
      nlohmann::json j;
      j["joint"] = r.joint;
      j["ok"] = !failed(r);
      if (r.problem) {
        j["error"] = {{"kind", "not reached"}, {"code", nullptr}, {"status", nullptr}, {"message", *r.problem}};
      } else if (r.failure) {
        const auto& f = *r.failure;
        j["error"] = {{"kind", joint_bus::to_string(f.kind)},
                      {"code", f.code() == 0 ? nlohmann::json(nullptr) : nlohmann::json(f.code())},
                      {"status", f.status_word ? nlohmann::json(*f.status_word) : nlohmann::json(nullptr)},
                      {"command_sent", f.command_sent},
                      {"message", f.message}};
      } else if (!r.value.is_null()) {
        j["value"] = r.value;
      }
      doc["joints"].push_back(std::move(j));
    }
    for (const auto& [k, v] : report.extra.items()) doc[k] = v;
    fmt::print("{}\n", doc.dump(2));
    return;
  }
  for (const auto& r : report.rows) {
    if (r.problem) {
      fmt::print("joint {}: FAILED {}\n", r.joint, *r.problem);
    } else if (r.failure) {
      const auto& f = *r.failure;
      fmt::print("joint {}: FAILED {}{}: {}\n", r.joint, joint_bus::to_string(f.kind),
                 f.code() ? fmt::format(" ({})", f.code()) : std::string(), f.message);
    } else {
      fmt::print("joint {}: {}\n", r.joint, r.text.empty() ? std::string("ok") : r.text);
    }
  }
}

}  // namespace armctl::cli
