// The web API's request bodies (web/request_body.hpp, web/group_frames.hpp) and its
// per-request security check (web/security.hpp) on hostile input. Byte 0 chooses the
// request; the rest is its body (or, for the security check, header lines). A body must be
// refused with an ApiError of 400 or 413 (never another exception, never a crash), or give
// values inside the ranges the API documents.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "arm/arm_model.hpp"
#include "web/api_error.hpp"
#include "web/base64.hpp"
#include "web/calibration_request.hpp"
#include "web/group_frames.hpp"
#include "web/request_body.hpp"
#include "web/security.hpp"

namespace {

using armctl::web::json;

void check(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "fuzz_request_body: accepted request breaks: %s\n", what);
  std::abort();
}

const armctl::arm::ArmModel& xarm() {
  static const armctl::arm::ArmModel m =
      armctl::arm::load_arm_model(std::string(ARMCTL_SOURCE_DIR) + "/config/xarm.arm.json").value();
  return m;
}

void security(std::string_view text) {
  std::vector<std::string_view> lines;
  while (lines.size() < 5) {
    const auto nl = text.find('\n');
    lines.push_back(text.substr(0, nl));
    if (nl == std::string_view::npos) break;
    text.remove_prefix(nl + 1);
  }
  lines.resize(5);
  const armctl::web::SecurityPolicy policy{"127.0.0.1", 8080, "0123456789abcdef"};
  const armctl::web::RequestFacts facts{"POST", lines[0], lines[1], lines[2], !lines[3].empty(), lines[3], lines[4]};
  if (auto refusal = armctl::web::check_request(policy, facts))
    check(refusal->status == 401 || refusal->status == 403 || refusal->status == 415, "security status");
}

void body(std::uint8_t kind, std::string_view text) {
  namespace web = armctl::web;
  const json b = web::parse_body(text);
  check(b.is_object(), "a body is an object");
  switch (kind % 14) {
    case 0: {
      const auto r = web::parse_joints_request(xarm(), b);
      check(r.targets.size() == xarm().joints.size(), "one target per joint");
      for (const auto& t : r.targets) check(!t || std::isfinite(*t), "finite targets");
      check(r.speed > 0 && r.speed <= 1, "speed in (0, 1]");
      check(!r.duration || (*r.duration > 0 && *r.duration <= armctl::motion::kMaxMoveDuration), "duration in range");
      break;
    }
    case 1: {
      const auto r = web::parse_tool_request(b);
      check(r.position.allFinite() && r.position.norm() <= 2 * web::kMaxReach, "tool position in range");
      check(r.speed > 0 && r.speed <= 1, "tool speed in (0, 1]");
      break;
    }
    case 2: {
      const auto r = web::parse_jog_request(b);
      check(r.axis >= 0 && r.axis < 6 && r.step != 0 && std::isfinite(r.step), "jog axis and step");
      check(std::abs(r.step) <= (r.axis < 3 ? web::kMaxJogLength : web::kMaxJogAngle) + 1e-12, "jog step in range");
      break;
    }
    case 3: {
      const double c = web::parse_gripper_request(b);
      check(c >= 0 && c <= 1, "gripper in 0..1");
      break;
    }
    case 4: web::parse_torque_request(b); break;
    case 5: web::parse_control_request(b); break;
    case 6: web::parse_point_request(b); break;
    case 7: {
      const auto r = web::parse_program_request(b, true);
      check(r.speed > 0 && r.speed <= 1, "program speed in (0, 1]");
      break;
    }
    case 8: {
      const auto g = web::frames_to_group(xarm(), b.contains("frames") ? b["frames"] : b);
      check(!g.group.actions.empty() && g.group.actions.size() <= 1020, "1..1020 actions");
      for (const auto& a : g.group.actions) {
        check(a.time_ms <= 30000, "action time");
        for (const auto& t : a.targets) check(!t.position || *t.position <= 1000, "servo position");
      }
      // What was accepted converts back.
      web::group_to_frames(xarm(), g.group);
      break;
    }
    case 9: {
      const auto times = web::parse_group_run(b);
      (void)times;
      const auto p = b.contains("percent") ? web::parse_group_speed(b) : std::uint16_t(1);
      check(p >= 1 && p <= 1000, "group speed");
      break;
    }
    case 10: {
      const auto g = web::parse_group_import(b);
      web::group_to_frames(xarm(), g);
      break;
    }
    case 12: {
      const auto c = web::parse_servo_request(xarm(), b);
      if (const auto* t = std::get_if<armctl::arm::ToolTwist>(&c.motion)) {
        check(t->linear.allFinite() && t->linear.norm() <= 0.1 + 1e-12, "servo linear speed in range");
        check(t->angular.allFinite() && t->angular.norm() <= 60 * M_PI / 180 + 1e-12, "servo angular speed in range");
      } else {
        const auto& v = std::get<armctl::arm::JointVelocities>(c.motion).values;
        check(v.size() == xarm().joints.size(), "one velocity per joint");
        for (std::size_t i = 0; i < v.size(); ++i)
          check(std::abs(v[i]) <= xarm().joints[i].limits.velocity + 1e-12, "joint velocity within its limit");
      }
      break;
    }
    case 13: {
      // The step from the body's own "step" field when it is a string (else "which"), so that
      // every step's parser is reached; the field is then taken out (it is not a body field).
      json rest = b;
      std::string step = "which";
      if (rest.contains("step") && rest["step"].is_string()) step = rest["step"].get<std::string>();
      rest.erase("step");
      const auto q = web::parse_calibration_request(xarm(), step, rest);
      const int n = xarm().joint_count();
      check(q.joint >= -1 && q.joint < n && q.moved >= -1 && q.moved < n, "calibration joints in range");
      check(std::isfinite(q.end_a) && std::isfinite(q.end_b) && std::isfinite(q.open) && std::isfinite(q.closed),
            "calibration readings finite");
      check(!q.mark || std::isfinite(*q.mark), "calibration mark finite");
      check(q.position.allFinite() && q.position.norm() <= web::kMaxReach, "calibration point within reach");
      break;
    }
    default: web::export_group(xarm(), b); break;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  if (data[0] == 0xff) {
    security(text);
    auto decoded = armctl::web::base64_decode(text);
    if (decoded) check(armctl::web::base64_decode(armctl::web::base64_encode(*decoded)) == decoded, "base64 round trip");
    return 0;
  }
  try {
    body(data[0], text);
  } catch (const armctl::web::ApiError& e) {
    check(e.status() == 400 || e.status() == 409 || e.status() == 413, "a refusal is 400, 409 or 413");
    check(std::string_view(e.what()).size() > 0, "a refusal says why");
  }
  return 0;
}
