#include "arm/arm_families.hpp"

#include "core/named_registry.hpp"
#include "motion/scara_kinematics.hpp"
#include "motion/xarm_kinematics.hpp"

namespace armctl::arm {

namespace {

// The built-in families, registered here and nowhere else.
void add_builtin(NamedRegistry<ArmFamily>& table) {
  // The 5-joint xArm: its yaw is where the arm points, its pitch is free, and a position
  // alone is reached with the nearest orientation.
  ArmFamily xarm{"xarm", motion::make_xarm_kinematics, {true, true, true}};
  ArmFamily scara{"scara", motion::make_scara_kinematics, {}};
  table.add(std::move(xarm)).value();
  table.add(std::move(scara)).value();
}

NamedRegistry<ArmFamily>& table() {
  static auto* t = new NamedRegistry<ArmFamily>("arm family", add_builtin);  // never destroyed: used until exit
  return *t;
}

}  // namespace

Status register_arm_family(ArmFamily family) {
  if (!family.make) return Error{ErrorKind::invalid_argument, "an arm family needs a kinematics factory (make)"};
  auto added = table().add(std::move(family));
  if (!added) return added.error();
  return Ok{};
}

Result<const ArmFamily*> find_arm_family(std::string_view name) { return table().get(name); }

}  // namespace armctl::arm
