#include "apps/armctl/bus_report.hpp"

#include <fmt/core.h>

#include "apps/armctl/json_output.hpp"

namespace armctl::cli {

namespace {

// The joint-bus failure kind when the error has one ("no answer"), else the error's kind.
std::string error_kind_text(const Error& e) {
  if (const auto* f = joint_bus::joint_failure(e)) return joint_bus::to_string(f->kind);
  return to_string(e.kind);
}

}  // namespace

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
      } else if (r.error) {
        j["error"] = {{"kind", error_kind_text(*r.error)}, {"code", nullptr}, {"status", nullptr},
                      {"message", r.error->message}};
        if (const auto* f = joint_bus::joint_failure(*r.error)) {
          if (f->code() != 0) j["error"]["code"] = f->code();
          if (f->status_word) j["error"]["status"] = *f->status_word;
          j["error"]["command_sent"] = f->command_sent;
        }
      } else if (!r.value.is_null()) {
        j["value"] = r.value;
      }
      doc["joints"].push_back(std::move(j));
    }
    for (const auto& [k, v] : report.extra.items()) doc[k] = v;
    print_json_line(doc);  // one line, as every other --json output
    return;
  }
  for (const auto& r : report.rows) {
    if (r.problem) {
      fmt::print("joint {}: FAILED {}\n", r.joint, *r.problem);
    } else if (r.error) {
      const auto* f = joint_bus::joint_failure(*r.error);
      fmt::print("joint {}: FAILED {}{}: {}\n", r.joint, error_kind_text(*r.error),
                 f && f->code() ? fmt::format(" ({})", f->code()) : std::string(), r.error->message);
    } else {
      fmt::print("joint {}: {}\n", r.joint, r.text.empty() ? std::string("ok") : r.text);
    }
  }
}

}  // namespace armctl::cli
