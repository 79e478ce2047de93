#include "arm/scene_obstacle.hpp"

#include <fmt/core.h>

#include "arm/arm_kinematics.hpp"

namespace armctl::arm {

Result<std::function<bool(std::span<const double>)>> scene_obstacle(const ArmModel& model, Protocol protocol,
                                                                  scene::Scene scene) {
  std::vector<std::size_t> slot;  // per joint of the model, its device slot
  for (const JointModel& j : model.joints) {
    const DeviceMap* map = j.map(protocol);
    if (!map || map->id < 1)
      return Error{ErrorKind::invalid_config,
                   fmt::format("arm '{}': joint {} has no {} ID, so its simulator cannot place it in the scene",
                               model.name, j.name, to_string(protocol))};
    slot.push_back(std::size_t(map->id - 1));
  }
  auto world = scene_only_world(model, std::move(scene));
  if (!world) return world.error();
  return std::function<bool(std::span<const double>)>(
      [model, protocol, slot, world = std::move(world).value()](std::span<const double> device) {
        std::vector<double> d(slot.size(), 0.0);
        for (std::size_t i = 0; i < slot.size(); ++i) d[i] = slot[i] < device.size() ? device[slot[i]] : 0.0;
        return world->collides(model.from_device(protocol, d));
      });
}

}  // namespace armctl::arm
