// The collision world's limits (docs/scene.md "Fence and reduced mode"): the fence for the
// tool point and, if asked, every moving link, and reduced mode's joint ranges. Checked like
// pairs of bodies, numbered after them, so that whatever asks about contacts (a motion's
// check, the look-ahead while it moves, the servo mode's braking, --avoid's search) asks
// about them too, and a limit already broken where a motion starts is skipped like a pair
// already touching there (the arm may move back).
#include <algorithm>

#include "scene/collision_item.hpp"
#include "scene/collision_world.hpp"

namespace armctl::scene {

const char* to_string(Limit limit) {
  switch (limit) {
    case Limit::none: return "collision";
    case Limit::fence: return "fence";
    case Limit::joint_range: return "joint range";
  }
  return "?";
}

namespace {

// How far `low`..`high` sticks out of the fence (0: inside).
double outside(const Fence& f, const Eigen::Vector3d& low, const Eigen::Vector3d& high) {
  return (f.low - low).cwiseMax(high - f.high).cwiseMax(0.0).norm();
}

}  // namespace

void CollisionWorld::add_limits() {
  if (scene_.fence && scene_.fence->on) {
    fence_ = scene_.fence;
    limits_.push_back({LimitItem::tool_in_fence, 0});
    if (fence_->links) limits_.push_back({LimitItem::links_in_fence, 0});
  }
  for (std::size_t r = 0; r < arm_.joint_ranges.size(); ++r) limits_.push_back({LimitItem::joint_range, r});
}

std::optional<Contact> CollisionWorld::limit_broken(std::size_t k, std::span<const double> joints, Placement& at) const {
  const LimitCheck& l = limits_[k];
  const Eigen::Vector3d tool = at.bodies[std::size_t(tool_body_)] * arm_.tool_frame.translation();
  switch (l.item) {
    case LimitItem::tool_in_fence:
      if (const double d = outside(*fence_, tool, tool); d > 0) return Contact{"the tool point", "the fence", d, tool, Limit::fence, {}, {}};
      return std::nullopt;
    case LimitItem::links_in_fence: {
      std::optional<Contact> worst;
      for (std::size_t i = 0; i < items_.size(); ++i) {
        const Item& item = items_[i];
        if (item.scene || item.body < 0 || !arm_.links->moves(item.body)) continue;
        complete(at, i);
        if (const double d = outside(*fence_, at.low[i], at.high[i]); d > 0 && (!worst || d > worst->depth))
          worst = Contact{item.label, "the fence", d, tool, Limit::fence, item.id, {}};
      }
      return worst;
    }
    case LimitItem::joint_range: {
      const JointRange& r = arm_.joint_ranges[l.range];
      const double q = r.joint < joints.size() ? joints[r.joint] : 0.0;
      if (const double d = std::max(r.lower - q, q - r.upper); d > 0) return Contact{r.name, r.words, d, tool, Limit::joint_range, {}, {}};
      return std::nullopt;
    }
  }
  return std::nullopt;
}

std::optional<Contact> CollisionWorld::limit_breach(std::span<const double> joints, Placement& at,
                                                    std::span<const int> skip) const {
  for (std::size_t k = 0; k < limits_.size(); ++k) {
    const int index = int(pairs_.size() + k);
    if (std::find(skip.begin(), skip.end(), index) != skip.end()) continue;
    if (auto c = limit_broken(k, joints, at)) return c;
  }
  return std::nullopt;
}

std::optional<double> CollisionWorld::fence_margin(Placement& at) const {
  if (!fence_) return std::nullopt;
  const Eigen::Vector3d tool = at.bodies[std::size_t(tool_body_)] * arm_.tool_frame.translation();
  return std::max(0.0, std::min((tool - fence_->low).minCoeff(), (fence_->high - tool).minCoeff()));
}

}  // namespace armctl::scene
