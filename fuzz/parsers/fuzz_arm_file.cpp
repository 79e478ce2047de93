// The arm-file parser (arm/arm_model.hpp) on hostile input, with the shipped URDFs. Byte 0
// chooses the mode: even = the rest is the JSON text; odd = the rest chooses edits to
// config/scara.arm.json (json_edits.hpp). The parser must return an invalid_config error
// naming the source, or a model whose every value is usable: finite limits in order,
// mappings that convert both ways, a gripper inside its joint's limits, and kinematics.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "arm/arm_model.hpp"
#include "arm/reduced_mode.hpp"
#include "json_edits.hpp"

namespace {

void check(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "fuzz_arm_file: accepted arm file breaks: %s\n", what);
  std::abort();
}

void check_model(const armctl::arm::ArmModel& m) {
  check(m.kinematics != nullptr, "kinematics built");
  check(m.chain_joints() >= 1 && m.chain_joints() <= m.joint_count(), "chain joints counted");
  for (const auto& j : m.joints) {
    const auto& l = j.limits;
    check(std::isfinite(l.lower) && std::isfinite(l.upper) && l.lower < l.upper, "position limits in order");
    check(l.velocity > 0 && l.acceleration > 0 && l.jerk > 0, "rate limits above zero");
    check(std::isfinite(l.velocity) && std::isfinite(l.acceleration) && std::isfinite(l.jerk), "finite rates");
    for (const auto& [protocol, map] : j.devices)
      check(std::isfinite(map.device_per_unit()) && map.device_per_unit() != 0, "mapping slope");
  }
  if (m.fence)
    check(m.fence->low.allFinite() && m.fence->high.allFinite() && (m.fence->low.array() < m.fence->high.array()).all(),
          "fence corners finite and in order");
  if (m.reduced) check(armctl::arm::reduced_limits(m, *m.reduced).ok(), "reduced ranges inside the joints' limits");
  if (m.gripper) {
    const auto& g = m.joints[std::size_t(m.gripper->joint)];
    check(g.limits.contains(m.gripper->open) && g.limits.contains(m.gripper->closed), "gripper inside limits");
  }
  for (auto p : {armctl::arm::Protocol::robot_commands, armctl::arm::Protocol::joint_bus}) {
    if (!m.supports(p)) continue;
    std::vector<double> q;
    for (const auto& j : m.joints) q.push_back((j.limits.lower + j.limits.upper) / 2);
    const auto back = m.from_device(p, m.to_device(p, q));
    for (std::size_t i = 0; i < q.size(); ++i)
      check(std::abs(back[i] - q[i]) <= 1e-6 * (1 + std::abs(q[i])), "device round trip");
  }
}

const std::string& base_text() {
  static const std::string text =
      armctl::fuzz::read_text_file(std::string(ARMCTL_SOURCE_DIR) + "/config/scara.arm.json");
  return text;
}
const std::string& urdf_text() {
  static const std::string text = armctl::fuzz::read_text_file(std::string(ARMCTL_SOURCE_DIR) + "/config/scara.urdf");
  return text;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string text = armctl::fuzz::config_text_from(data, size, base_text());
  auto model = armctl::arm::parse_arm_model(text, "fuzz.arm.json", urdf_text(), "scara.urdf");
  if (model) {
    check_model(*model);
  } else {
    check(model.error().kind == armctl::ErrorKind::invalid_config, "error kind is invalid_config");
    check(model.error().message.find("fuzz.arm.json") != std::string::npos ||
              model.error().message.find("scara.urdf") != std::string::npos,
          "error message names the source");
  }
  return 0;
}
