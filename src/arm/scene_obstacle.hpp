// What a simulated arm meets (`armctl sim xarm --scene`, `armctl sim scara --scene`): the
// scene as a question the simulators ask every step about their own positions, so that an
// arm driven into an object by anything that skips armctl's checks (a raw Robot Commands
// client, a host without the scene) stops at contact. The scene only: the arm's links never
// against each other (their shapes are the planner's conservative ones).
#pragma once

#include <functional>
#include <span>

#include "arm/arm_model.hpp"
#include "arm/protocols.hpp"
#include "core/error.hpp"
#include "scene/scene.hpp"

namespace armctl::arm {

// Whether the arm touches something of `scene` with its joints at these device positions:
// one per device slot, the joint whose `protocol` ID is i + 1 at index i (xArm servos 1..6,
// joint-bus lines 1..7). Errors: a joint without a mapping for `protocol`, an arm without
// collision shapes (invalid_config).
Result<std::function<bool(std::span<const double>)>> scene_obstacle(const ArmModel& model, Protocol protocol,
                                                                  scene::Scene scene);

}  // namespace armctl::arm
