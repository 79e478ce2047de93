#include "arm/protocols.hpp"

#include "arm/arm_model.hpp"
#include "core/named_registry.hpp"
#include "portable/joint_tuning.hpp"

namespace armctl::arm {

namespace {

// The built-in protocols, registered here and nowhere else.
void add_builtin(NamedRegistry<ProtocolInfo>& table) {
  ProtocolInfo rc{"robot_commands", "servo", 19, {0, 1000}, "servo units", {}};
  ProtocolInfo bus{"joint_bus", "number", 7, {-32768, 32767}, "counts", {}};
  // The joint's own speed at set_speed 100 % and its acceleration, as in its tuning
  // (the simulator section of config/scara.arm.json), so that moves can be planned to arrive together.
  bus.read_extras = [](json_reader::ObjectReader& r, DeviceMap& m) {
    m.max_speed_cps = r.number("max_speed_cps", 1, joint_bus::max_speed_cps_limit);
    m.max_accel_cps2 = r.number("max_accel_cps2", joint_bus::min_accel_cps2_limit, joint_bus::max_accel_cps2_limit);
  };
  table.add(std::move(rc)).value();
  table.add(std::move(bus)).value();
}

NamedRegistry<ProtocolInfo>& table() {
  static auto* t = new NamedRegistry<ProtocolInfo>("protocol", add_builtin);  // never destroyed: used until exit
  return *t;
}

}  // namespace

std::string to_string(Protocol p) { return std::string(p.name()); }

Status register_protocol(ProtocolInfo info) {
  if (info.max_id < 1) return Error{ErrorKind::invalid_argument, "a protocol's IDs must be 1..max_id with max_id >= 1"};
  if (!(info.range.min < info.range.max))
    return Error{ErrorKind::invalid_argument, "a protocol's device range must have min below max"};
  auto added = table().add(std::move(info));
  if (!added) return added.error();
  return Ok{};
}

Result<Protocol> find_protocol(std::string_view name) {
  auto info = table().get(name);
  if (!info) return info.error();
  return Protocol((*info)->name);
}

const ProtocolInfo& protocol_info(Protocol p) {
  // The table's own copy of the name is what a Protocol from find_protocol points to; the
  // built-in constants point to literals with the same text.
  const ProtocolInfo* info = table().find(p.name());
  if (!info) throw ArmctlError(ErrorKind::invalid_argument, fmt::format("unknown protocol '{}'", p.name()));
  return *info;
}

DeviceRange device_range(Protocol p) { return protocol_info(p).range; }

std::vector<Protocol> protocols() {
  std::vector<Protocol> out;
  for (const auto& n : table().names()) out.push_back(Protocol(protocol_info(Protocol(n)).name));
  return out;
}

}  // namespace armctl::arm
