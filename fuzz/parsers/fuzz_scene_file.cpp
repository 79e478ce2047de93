// Arbitrary text into the scene-file parser (scene/scene.hpp), and what it accepts into a
// collision world of the xArm, checked at its zero and at a bent pose: never a crash; every
// error names the file and is invalid_config; anything accepted has named objects with
// finite, positive sizes, a fence with a size, reduced ranges with lower below upper (which
// the xArm takes, or refuses as invalid_config), and survives a write/read round trip.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "arm/arm_model.hpp"
#include "arm/reduced_mode.hpp"
#include "scene/collision_world.hpp"
#include "scene/scene.hpp"

namespace {

void check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "fuzz_scene_file: %s\n", what);
    std::abort();
  }
}

const armctl::arm::ArmModel& xarm() {
  static const armctl::arm::ArmModel m =
      armctl::arm::load_arm_model(std::string(ARMCTL_SOURCE_DIR) + "/config/xarm.arm.json").value();
  return m;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace armctl::scene;
  std::string_view text(reinterpret_cast<const char*>(data), size);
  auto s = parse_scene(text, "fuzz");
  if (!s) {
    check(s.error().message.rfind("fuzz:", 0) == 0, "an error that does not name the file");
    check(s.error().kind == armctl::ErrorKind::invalid_config, "an error of another kind");
    return 0;
  }
  for (const auto& o : s->objects) {
    check(!o.name.empty(), "an object without a name");
    check(o.shape.size.allFinite() && o.shape.size.x() > 0, "a size that is not finite and positive");
    check(o.shape.pose.matrix().allFinite(), "a pose that is not finite");
  }
  if (s->fence) check((s->fence->low.array() < s->fence->high.array()).all(), "a fence without a size");
  if (s->reduced) {
    check(s->reduced->tool_speed || !s->reduced->joints.empty(), "a reduced mode that sets nothing");
    if (s->reduced->tool_speed) check(*s->reduced->tool_speed > 0, "a tool speed cap that is not positive");
    for (const auto& j : s->reduced->joints) check(j.lower < j.upper, "a reduced range whose lower is not below upper");
  }
  auto again = parse_scene(scene_json(*s), "again");
  check(again.ok(), "what it wrote does not read back");
  check(again->objects.size() == s->objects.size(), "the round trip changed the objects");
  check(again->fence.has_value() == s->fence.has_value() && again->reduced.has_value() == s->reduced.has_value(),
        "the round trip changed the limits");
  const auto& m = xarm();
  ArmBodies a;
  if (s->reduced) {
    auto limits = armctl::arm::reduced_limits(m, *s->reduced);
    if (limits) a.joint_ranges = limits->joint_ranges;
    else check(limits.error().kind == armctl::ErrorKind::invalid_config, "a reduced range refused as another kind");
  }
  a.links = m.bodies;
  a.allowed = m.allowed_collisions;
  a.tool_link = m.tool_link;
  for (const auto& j : m.joints) a.joint_reach.push_back(std::fabs(j.limits.upper));
  auto world = CollisionWorld::build(a, *s);
  check(world.ok(), "an accepted scene the xArm's world refuses");
  const std::vector<double> zero(m.joints.size(), 0.0), bent{0.5, 1.2, 1.0, 0.8, 0.3, 0.0};
  for (const auto* q : {&zero, &bent}) {
    (void)(*world)->collides(*q);
    (void)(*world)->contact(*q);
    check(std::isfinite((*world)->clearance(*q).distance), "a clearance that is not finite");
  }
  return 0;
}
