#include "arm/arm_calibration.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "devices/rc_board/atomic_file.hpp"

namespace armctl::arm {

namespace {

Error refuse(std::string m) { return Error{ErrorKind::invalid_argument, std::move(m)}; }

std::string unit_text(Dimension d, double si) {
  return fmt::format("{:.6f}{}", to_display(d, si), display_unit(d));
}

}  // namespace

Result<std::vector<ZeroChange>> calibrate_zero(const ArmModel& model, Protocol protocol,
                                               const std::vector<double>& device_now,
                                               const std::vector<int>& joints) {
  if (device_now.size() != model.joints.size()) return refuse("one device position per joint is needed");
  std::vector<bool> chosen(model.joints.size(), false);
  for (int i : joints) {
    if (i < 0 || i >= model.joint_count()) return refuse(fmt::format("no joint {}", i));
    if (chosen[std::size_t(i)]) return refuse(fmt::format("joint {} is named twice", model.joints[std::size_t(i)].name));
    chosen[std::size_t(i)] = true;
  }
  for (const Coupling& c : model.couplings)
    if (chosen[std::size_t(c.first)] != chosen[std::size_t(c.second)])
      return refuse(fmt::format("joints {} and {} are coupled: zero them together", model.joints[std::size_t(c.first)].name,
                                model.joints[std::size_t(c.second)].name));
  const DeviceRange range = device_range(protocol);
  std::vector<ZeroChange> out;
  std::vector<DeviceMap> maps;
  for (const auto& j : model.joints) maps.push_back(*j.map(protocol));
  for (int i : joints) {
    const JointModel& j = model.joints[std::size_t(i)];
    ZeroChange c;
    c.joint = i;
    c.map = *j.map(protocol);
    // Shift in actuator space: the actuator reads 0 where it stands now.
    c.shift = c.map.to_actuator(device_now[std::size_t(i)]);
    c.map.actuator_a -= c.shift;
    c.map.actuator_b -= c.shift;
    maps[std::size_t(i)] = c.map;
    out.push_back(c);
  }
  // Check every changed joint: zero inside its limits, its limits inside the device range.
  ArmModel changed = model;
  for (std::size_t i = 0; i < maps.size(); ++i) {
    auto& slot = protocol == Protocol::robot_commands ? changed.joints[i].robot_commands : changed.joints[i].joint_bus;
    slot = maps[i];
  }
  const std::vector<double> q_now = changed.from_device(protocol, device_now);
  for (const ZeroChange& c : out) {
    const JointModel& j = model.joints[std::size_t(c.joint)];
    if (!j.limits.contains(0.0))
      return refuse(fmt::format("joint {}: its limits {}..{} do not contain zero, so it cannot be zeroed", j.name,
                                format_quantity(j.dimension, j.limits.lower), format_quantity(j.dimension, j.limits.upper)));
    (void)q_now;
    for (double end : {j.limits.lower, j.limits.upper}) {
      std::vector<double> q(model.joints.size(), 0.0);
      q[std::size_t(c.joint)] = end;
      const double device = changed.to_device(protocol, q)[std::size_t(c.joint)];
      if (device < range.min || device > range.max)
        return refuse(fmt::format(
            "joint {}: with its zero where it stands ({} from the old zero), its limit {} would be device position "
            "{:.0f}, outside {}..{}: move it nearer the middle of its travel first",
            j.name, format_quantity(j.dimension, c.shift), format_quantity(j.dimension, end), device, range.min, range.max));
    }
  }
  return out;
}

Status save_calibration(const ArmModel& model, Protocol protocol, const std::vector<ZeroChange>& changes) {
  if (model.file.empty()) return refuse("this arm model was not read from a file: nothing to save");
  using nlohmann::json;
  json doc;
  try {
    std::ifstream in(model.file);
    if (!in) return Error{ErrorKind::io, fmt::format("cannot read arm file {}", model.file.string())};
    doc = json::parse(in);
  } catch (const json::exception& e) {
    return Error{ErrorKind::invalid_config, fmt::format("{}: not valid JSON: {}", model.file.string(), e.what())};
  }
  const char* key = to_string(protocol);
  for (const ZeroChange& c : changes) {
    const JointModel& j = model.joints[std::size_t(c.joint)];
    bool done = false;
    for (auto& entry : doc["joints"]) {
      if (!entry.is_object() || entry.value("name", "") != j.name || !entry.contains(key)) continue;
      entry[key]["joint"] = json::array({unit_text(j.dimension, c.map.actuator_a), unit_text(j.dimension, c.map.actuator_b)});
      done = true;
    }
    if (!done) return Error{ErrorKind::invalid_config, fmt::format("{}: joint {} not found", model.file.string(), j.name)};
  }
  const std::string text = doc.dump(2) + "\n";
  return rc_board::write_file_atomically(
      model.file, std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

}  // namespace armctl::arm
