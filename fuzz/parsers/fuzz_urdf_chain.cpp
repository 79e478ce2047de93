// The URDF chain reader (motion/urdf_chain.hpp) and the kinematic families' shape checks on
// arbitrary text (the seed corpus starts from the shipped URDFs). The reader must refuse
// with invalid_config or return a chain whose every value is usable: finite origins, unit
// axes, finite limits with lower < upper. A chain a family accepts must then solve its own
// forward kinematics: IK of the pose at the limits' middle returns only solutions inside
// the limits that reach that pose. The text for viewers (motion/urdf_for_viewers.hpp, a
// link length and capsules rewritten) must be refused the same way or read back as a URDF
// without capsules whose chain has that length.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <sanitizer/lsan_interface.h>

#include "core/error.hpp"
#include "motion/kinematics.hpp"
#include "motion/scara_kinematics.hpp"
#include "motion/urdf_capsules.hpp"
#include "motion/urdf_chain.hpp"
#include "motion/urdf_for_viewers.hpp"
#include "motion/urdf_model.hpp"
#include "motion/xarm_kinematics.hpp"

namespace {

using namespace armctl::motion;

[[noreturn]] void broken(const char* what) {
  std::fprintf(stderr, "fuzz_urdf_chain: %s\n", what);
  std::abort();
}

void check(bool ok, const char* what) {
  if (!ok) broken(what);
}

void check_chain(const UrdfChain& c) {
  for (const auto& j : c.joints) {
    check(!j.name.empty(), "joint named");
    check(std::abs(j.axis.norm() - 1) < 1e-9, "unit axis");
    check(j.from_previous.matrix().allFinite(), "finite origin");
    check(std::isfinite(j.limits.lower) && std::isfinite(j.limits.upper) && j.limits.lower < j.limits.upper,
          "limits finite, lower < upper");
  }
  check(c.tip_from_last.matrix().allFinite(), "finite tip");
}

void check_kinematics(const Kinematics& k, const std::vector<PositionLimits>& limits) {
  JointVector mid(k.joint_count());
  for (int i = 0; i < mid.size(); ++i) mid[i] = 0.5 * (limits[std::size_t(i)].lower + limits[std::size_t(i)].upper);
  const Pose p = k.forward(mid);
  if (!p.position.allFinite() || p.position.norm() > 100) return;  // not an arm's size: no promise
  auto s = k.inverse(IkRequest{p}, mid);
  if (!s.ok()) {
    check(s.error().kind == armctl::ErrorKind::invalid_argument, "IK error kind invalid_argument");
    return;
  }
  for (const auto& sol : *s) {
    for (int i = 0; i < mid.size(); ++i) {
      check(sol.joints[i] >= limits[std::size_t(i)].lower && sol.joints[i] <= limits[std::size_t(i)].upper,
            "IK solution inside the limits");
    }
    const Pose back = k.forward(sol.joints);
    check((back.position - p.position).norm() < 1e-6, "IK solution reaches the pose");
  }
}

// The chain's first joint with an offset made 1.5 times as long in the text for viewers.
void check_viewer_text(const std::string& text, const UrdfChain& chain) {
  std::vector<OriginLength> lengths;
  for (const auto& j : chain.joints)
    if (j.origin_xyz.norm() > 1e-3 && j.origin_xyz.norm() < 10) {
      lengths.push_back({j.name, 1.5 * j.origin_xyz.norm()});
      break;
    }
  __lsan_disable();
  auto viewer = urdf_for_viewers(text, lengths);
  __lsan_enable();
  if (!viewer.ok()) {
    check(viewer.error().kind == armctl::ErrorKind::invalid_config, "viewer text error kind invalid_config");
    return;
  }
  __lsan_disable();
  std::vector<UrdfCapsule> capsules;
  auto again = parse_urdf_model(*viewer, &capsules);
  auto back = read_urdf_chain(*viewer, "base_link", "tool");
  __lsan_enable();
  check(again.ok() && back.ok(), "the text for viewers reads back");
  check(capsules.empty(), "no capsule left for viewers");
  for (std::size_t i = 0; i < back->joints.size() && i < chain.joints.size(); ++i)
    if (!lengths.empty() && back->joints[i].name == lengths[0].joint)
      check(std::abs(back->joints[i].origin_xyz.norm() - lengths[0].length) < 1e-6 * (1 + lengths[0].length),
            "the length written for viewers");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  // urdfdom leaks the links of a URDF whose joints form a loop (its links hold each other
  // by shared_ptr); that is urdfdom's, not the reader's, so it is not reported.
  __lsan_disable();
  auto chain = read_urdf_chain(text, "base_link", "tool");
  __lsan_enable();
  if (!chain.ok()) {
    check(chain.error().kind == armctl::ErrorKind::invalid_config, "error kind invalid_config");
    check(!chain.error().message.empty(), "error says why");
    return 0;
  }
  check_chain(*chain);
  check_viewer_text(text, *chain);
  const auto limits = urdf_position_limits(*chain);
  for (auto make : {make_scara_kinematics, make_xarm_kinematics}) {
    auto k = make(*chain, limits);
    if (!k.ok()) {
      check(k.error().kind == armctl::ErrorKind::invalid_config, "shape error kind invalid_config");
      continue;
    }
    check_kinematics(**k, limits);
  }
  return 0;
}
