#include "arm/arm_calibration.hpp"

#include <algorithm>

#include <fmt/core.h>

namespace armctl::arm {

namespace {

Error refuse(std::string m) { return Error{ErrorKind::invalid_argument, std::move(m)}; }

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
  for (ZeroChange& c : out) {
    const JointModel& j = model.joints[std::size_t(c.joint)];
    if (!j.limits.contains(c.shift, 1e-9))
      return refuse(fmt::format("joint {} stands at {}, outside its limits {}..{}: move it inside them first", j.name,
                                format_quantity(j.dimension, c.shift), format_quantity(j.dimension, j.limits.lower),
                                format_quantity(j.dimension, j.limits.upper)));
    // The URDF's zero is where the joint stands now: its travel, as the limits had it on
    // the device, shifts, and stays inside the URDF's mechanical limits.
    c.limits = j.limits;
    c.limits.lower = std::max(j.limits.lower - c.shift, j.urdf_lower);
    c.limits.upper = std::min(j.limits.upper - c.shift, j.urdf_upper);
    const bool coupled = std::any_of(model.couplings.begin(), model.couplings.end(),
                                     [&](const Coupling& k) { return k.first == c.joint || k.second == c.joint; });
    // The device positions of the new limits; a single joint's limit beyond the device's
    // end is pulled in to it.
    const double ends[2] = {c.map.to_actuator(range.min), c.map.to_actuator(range.max)};
    const double reach_lo = std::min(ends[0], ends[1]), reach_hi = std::max(ends[0], ends[1]);
    if (coupled) {
      if (c.limits.lower < reach_lo - 1e-9 || c.limits.upper > reach_hi + 1e-9)
        return refuse(fmt::format("joint {}: with its zero where it stands ({} from the old zero) its limits would "
                                  "reach beyond the device's range {}..{}: move it nearer the middle of its travel",
                                  j.name, format_quantity(j.dimension, c.shift), range.min, range.max));
    } else {
      c.limits.lower = std::max(c.limits.lower, reach_lo);
      c.limits.upper = std::min(c.limits.upper, reach_hi);
    }
  }
  for (const ZeroChange& c : out) {
    const JointModel& j = model.joints[std::size_t(c.joint)];
    if (!(c.limits.lower <= 0 && 0 <= c.limits.upper && c.limits.lower < c.limits.upper))
      return refuse(fmt::format("joint {}: with its zero {} from the old one, no travel would be left inside its URDF "
                                "limits and the device's range",
                                j.name, format_quantity(j.dimension, c.shift)));
  }
  // A coupled pair's actuators carry sums of both joints: check the corners of the box.
  for (const Coupling& k : model.couplings) {
    if (!chosen[std::size_t(k.first)]) continue;
    ArmModel changed = model;
    for (const ZeroChange& c : out) {
      *changed.joints[std::size_t(c.joint)].map(protocol) = c.map;
      changed.joints[std::size_t(c.joint)].limits = c.limits;
    }
    if (auto over = coupled_overrun(changed, protocol, k))
      return refuse(fmt::format("joints {} and {}: with their zeros where they stand, the ends of their travel "
                                "would need device position {:.0f}, outside {}..{}",
                                model.joints[std::size_t(k.first)].name, model.joints[std::size_t(k.second)].name,
                                over->device, range.min, range.max));
  }
  return out;
}

std::optional<CoupledOverrun> coupled_overrun(const ArmModel& model, Protocol protocol, const Coupling& pair,
                                              double slack) {
  const DeviceRange range = device_range(protocol);
  const JointLimits& a = model.joints[std::size_t(pair.first)].limits;
  const JointLimits& b = model.joints[std::size_t(pair.second)].limits;
  for (double qa : {a.lower, a.upper})
    for (double qb : {b.lower, b.upper}) {
      std::vector<double> q(model.joints.size(), 0.0);
      q[std::size_t(pair.first)] = qa;
      q[std::size_t(pair.second)] = qb;
      const auto d = model.to_device(protocol, q);
      for (int idx : {pair.first, pair.second})
        if (d[std::size_t(idx)] < range.min - slack || d[std::size_t(idx)] > range.max + slack)
          return CoupledOverrun{idx, d[std::size_t(idx)]};
    }
  return std::nullopt;
}

}  // namespace armctl::arm
