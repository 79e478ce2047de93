#include "scene/collision_world.hpp"
#include "scene/collision_item.hpp"

#include <algorithm>
#include <cmath>

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>
#include <fmt/format.h>

namespace armctl::scene {

CollisionWorld::~CollisionWorld() = default;

namespace {

std::shared_ptr<fcl::CollisionGeometryd> fcl_geometry(const motion::Shape& s) {
  switch (s.kind) {
    case motion::Shape::Kind::box: return std::make_shared<fcl::Boxd>(s.size.x(), s.size.y(), s.size.z());
    case motion::Shape::Kind::cylinder: return std::make_shared<fcl::Cylinderd>(s.size.x(), s.size.y());
    case motion::Shape::Kind::sphere: return std::make_shared<fcl::Sphered>(s.size.x());
    case motion::Shape::Kind::capsule: return std::make_shared<fcl::Capsuled>(s.size.x(), s.size.y());
  }
  return nullptr;
}

bool overlap(const Eigen::Vector3d& la, const Eigen::Vector3d& ha, const Eigen::Vector3d& lb, const Eigen::Vector3d& hb,
             double margin) {
  return (la.array() <= hb.array() + margin).all() && (lb.array() <= ha.array() + margin).all();
}

// The gap between two boxes (0 when they overlap): no two points of their contents are nearer.
double gap(const Eigen::Vector3d& la, const Eigen::Vector3d& ha, const Eigen::Vector3d& lb, const Eigen::Vector3d& hb) {
  const Eigen::Vector3d d = (la - hb).cwiseMax(lb - ha).cwiseMax(0.0);
  return d.norm();
}

}  // namespace

Result<std::shared_ptr<const CollisionWorld>> CollisionWorld::build(ArmBodies arm, Scene scene) {
  std::shared_ptr<CollisionWorld> w(new CollisionWorld());
  const motion::LinkBodies& links = *arm.links;
  const auto tool = links.find(arm.tool_link);
  if (!tool) return Error{ErrorKind::invalid_config, fmt::format("collision model: no link '{}' (the tool link)", arm.tool_link)};
  const std::size_t n_bodies = links.bodies.size();
  std::vector<std::vector<bool>> allowed(n_bodies, std::vector<bool>(n_bodies, false));
  for (const auto& [a, b] : arm.allowed) {
    const auto ia = links.find(a), ib = links.find(b);
    if (!ia || !ib) {
      return Error{ErrorKind::invalid_config,
                   fmt::format("collision model: allowed pair '{}' and '{}': no link '{}' in the URDF", a, b, ia ? b : a)};
    }
    allowed[std::size_t(*ia)][std::size_t(*ib)] = allowed[std::size_t(*ib)][std::size_t(*ia)] = true;
  }
  // Joined links: their shapes meet where the joint is.
  for (std::size_t i = 0; i < n_bodies; ++i) {
    if (const int p = links.bodies[i].parent; p >= 0) allowed[i][std::size_t(p)] = allowed[std::size_t(p)][i] = true;
  }
  for (std::size_t b = 0; b < n_bodies; ++b) {
    for (const auto& s : links.bodies[b].shapes) {
      w->items_.push_back(Item{fmt::format("link '{}'", links.bodies[b].name), int(b), s, fcl_geometry(s), false, {}, {}, {},
                               BodyId{BodyId::Kind::link, links.bodies[b].name}});
    }
  }
  const std::size_t n_links = w->items_.size();
  // Parts held by the tool hang from the tool link; what holds them never counts as a touch.
  const int holder = links.bodies[std::size_t(*tool)].parent;
  for (const auto& o : scene.objects) {
    Item item{describe(o), o.attached ? *tool : -1, o.shape, fcl_geometry(o.shape), true, {}, {}, {},
              BodyId{BodyId::Kind::object, o.name}};
    if (o.attached) {
      item.shape.pose = arm.tool_frame * o.shape.pose;
    } else {
      motion::world_bounds(o.shape, o.shape.pose, item.low, item.high);
    }
    w->items_.push_back(std::move(item));
  }
  auto holds = [&](int body) {
    return body == *tool || body == holder || (holder >= 0 && links.bodies[std::size_t(body)].parent == holder);
  };
  for (std::size_t i = 0; i < w->items_.size(); ++i) {
    for (std::size_t j = i + 1; j < w->items_.size(); ++j) {
      const Item &a = w->items_[i], &b = w->items_[j];
      const bool a_moves = a.body >= 0 && links.moves(a.body), b_moves = b.body >= 0 && links.moves(b.body);
      if (!a_moves && !b_moves) continue;  // nothing between them ever changes
      if (i < n_links && j < n_links) {
        if (a.body == b.body || allowed[std::size_t(a.body)][std::size_t(b.body)]) continue;
      } else if (b.scene && b.body >= 0 && i < n_links) {
        if (holds(a.body)) continue;  // a held part and what holds it
      } else if (a.scene && b.scene && a.body >= 0 && b.body >= 0) {
        continue;  // two held parts move together
      }
      w->pairs_.push_back(Pair{int(i), int(j), 0, 0});
    }
  }
  for (Item& item : w->items_) {
    item.radius = motion::bounding_radius(item.shape);
    for (int b = item.body; b >= 0; b = links.bodies[std::size_t(b)].parent)
      if (links.bodies[std::size_t(b)].joint >= 0 && std::size_t(links.bodies[std::size_t(b)].joint) < arm.joint_reach.size())
        item.chain.push_back(b);
  }
  auto not_in = [](const std::vector<int>& a, const std::vector<int>& b) {
    return int(std::count_if(a.begin(), a.end(), [&](int x) { return std::find(b.begin(), b.end(), x) == b.end(); }));
  };
  for (Pair& p : w->pairs_) {
    const auto &a = w->items_[std::size_t(p.first)].chain, &b = w->items_[std::size_t(p.second)].chain;
    p.first_own = not_in(a, b);
    p.second_own = not_in(b, a);
  }
  // How far a point of each item can be from each joint's axis: the links' offsets from the
  // joint's link down to the item's, each prismatic joint on the way at its longest, plus
  // the shape's own offset and size.
  const std::size_t n_joints = arm.joint_reach.size();
  w->reach_.assign(w->items_.size(), std::vector<double>(n_joints, 0.0));
  for (std::size_t i = 0; i < w->items_.size(); ++i) {
    const Item& item = w->items_[i];
    if (item.body < 0) continue;
    const double own = item.shape.pose.translation().norm() + motion::bounding_radius(item.shape);
    double along = own;
    for (int b = item.body; b >= 0; b = links.bodies[std::size_t(b)].parent) {
      const motion::LinkBody& body = links.bodies[std::size_t(b)];
      if (body.joint >= 0 && std::size_t(body.joint) < n_joints) {
        w->reach_[i][std::size_t(body.joint)] = body.prismatic ? 1.0 : along;
        if (body.prismatic) along += arm.joint_reach[std::size_t(body.joint)];
      }
      along += body.origin.translation().norm();
    }
  }
  w->arm_ = std::move(arm);
  w->scene_ = std::move(scene);
  w->tool_body_ = *tool;
  w->add_limits();
  return std::shared_ptr<const CollisionWorld>(std::move(w));
}

void CollisionWorld::place(std::span<const double> joints, Placement& at) const {
  arm_.links->poses(joints, at.bodies);
  const std::size_t n = items_.size();
  at.items.resize(n);
  at.centres.resize(n);
  at.low.resize(n);
  at.high.resize(n);
  at.placed.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const Item& item = items_[i];
    if (item.body < 0) {
      at.items[i] = item.shape.pose;
      at.centres[i] = item.shape.pose.translation();
      at.low[i] = item.low;
      at.high[i] = item.high;
      at.placed[i] = 1;
    } else {
      at.centres[i] = at.bodies[std::size_t(item.body)] * item.shape.pose.translation();
    }
  }
}

void CollisionWorld::complete(Placement& at, std::size_t i) const {
  if (at.placed[i]) return;
  const Item& item = items_[i];
  at.items[i] = at.bodies[std::size_t(item.body)] * item.shape.pose;
  motion::world_bounds(item.shape, at.items[i], at.low[i], at.high[i]);
  at.placed[i] = 1;
}

void CollisionWorld::place_every_shape(std::span<const double> joints, Placement& at) const {
  place(joints, at);
  for (std::size_t i = 0; i < items_.size(); ++i) complete(at, i);
}

namespace {
bool skipped(std::span<const int> skip, std::size_t pair) {
  return !skip.empty() && std::find(skip.begin(), skip.end(), int(pair)) != skip.end();
}
}  // namespace

// Calls visit(pair index, result) for every checked pair not in `skip` whose shapes touch at
// `joints`, until it returns false. The bounding boxes first: FCL only for those that overlap.
template <typename Visit>
void CollisionWorld::each_touching(std::span<const double> joints, std::span<const int> skip, bool with_contact,
                                   Visit&& visit) const {
  // Per thread: a check runs millions of times and allocates nothing.
  thread_local Placement f;
  place_every_shape(joints, f);
  const fcl::CollisionRequestd request(1, with_contact);
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    const auto i = std::size_t(pairs_[k].first), j = std::size_t(pairs_[k].second);
    if (skipped(skip, k) || !overlap(f.low[i], f.high[i], f.low[j], f.high[j], 0)) continue;
    fcl::CollisionResultd result;
    if (fcl::collide(items_[i].geometry.get(), f.items[i], items_[j].geometry.get(), f.items[j], request, result) == 0) {
      continue;
    }
    if (!visit(k, result)) return;
  }
}

bool CollisionWorld::collides(std::span<const double> joints, std::span<const int> skip) const {
  if (has_limits()) {
    thread_local Placement f;
    place(joints, f);
    if (limit_breach(joints, f, skip)) return true;
  }
  bool any = false;
  each_touching(joints, skip, false, [&](std::size_t, const fcl::CollisionResultd&) {
    any = true;
    return false;  // the first is enough
  });
  return any;
}

std::vector<int> CollisionWorld::touching(std::span<const double> joints) const {
  std::vector<int> out;
  each_touching(joints, {}, false, [&](std::size_t k, const fcl::CollisionResultd&) {
    out.push_back(int(k));
    return true;
  });
  if (has_limits()) {
    thread_local Placement f;
    place(joints, f);
    for (std::size_t k = 0; k < limits_.size(); ++k)
      if (limit_broken(k, joints, f)) out.push_back(int(pairs_.size() + k));
  }
  return out;
}

std::pair<std::string, std::string> CollisionWorld::pair_names(int pair) const {
  if (std::size_t(pair) >= pairs_.size()) {
    // A limit (touching's numbering): what breaks it and which.
    const LimitCheck& l = limits_[std::size_t(pair) - pairs_.size()];
    switch (l.item) {
      case LimitItem::tool_in_fence: return {"the tool point", "the fence"};
      case LimitItem::links_in_fence: return {"a link", "the fence"};
      case LimitItem::joint_range: return {arm_.joint_ranges[l.range].name, arm_.joint_ranges[l.range].words};
    }
  }
  const Pair& p = pairs_[std::size_t(pair)];
  return {items_[std::size_t(p.first)].label, items_[std::size_t(p.second)].label};
}

std::optional<Contact> CollisionWorld::contact(std::span<const double> joints, std::span<const int> skip) const {
  std::optional<Contact> deepest;
  each_touching(joints, skip, true, [&](std::size_t k, const fcl::CollisionResultd& result) {
    const fcl::Contactd& c = result.getContact(0);
    if (!deepest || c.penetration_depth > deepest->depth) {
      const Item &a = items_[std::size_t(pairs_[k].first)], &b = items_[std::size_t(pairs_[k].second)];
      deepest = Contact{a.label, b.label, c.penetration_depth, c.pos, Limit::none, a.id, b.id};
    }
    return true;
  });
  if (!deepest && has_limits()) {
    thread_local Placement f;
    place(joints, f);
    return limit_breach(joints, f, skip);
  }
  return deepest;
}

Clearance CollisionWorld::clearance(std::span<const double> joints, double below, std::span<const int> skip) const {
  thread_local Placement f;
  place_every_shape(joints, f);
  Clearance best;
  best.distance = std::min(below, kClearanceHorizon);
  fcl::DistanceRequestd request;
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    const int i = pairs_[k].first, j = pairs_[k].second;
    if (skipped(skip, k)) continue;
    // The boxes' gap is never more than the shapes' distance: farther than the best so far,
    // the pair cannot be nearer.
    if (gap(f.low[std::size_t(i)], f.high[std::size_t(i)], f.low[std::size_t(j)], f.high[std::size_t(j)]) >= best.distance) continue;
    fcl::DistanceResultd result;
    fcl::distance(items_[std::size_t(i)].geometry.get(), f.items[std::size_t(i)], items_[std::size_t(j)].geometry.get(),
                  f.items[std::size_t(j)], request, result);
    const double d = std::max(0.0, result.min_distance);
    if (d < best.distance) best = Clearance{d, items_[std::size_t(i)].label, items_[std::size_t(j)].label};
  }
  // The fence's faces are near things too (the servo mode slows toward them), unless the
  // tool point starts outside it.
  const int fence_index = int(pairs_.size());
  if (const auto margin = fence_margin(f); margin && *margin < best.distance && !skipped(skip, std::size_t(fence_index)))
    best = Clearance{*margin, "the tool point", "the fence"};
  return best;
}

double CollisionWorld::displacement_bound(std::span<const double> from, std::span<const double> to) const {
  double worst = 0;
  const std::size_t n = std::min({from.size(), to.size(), arm_.joint_reach.size()});
  for (const auto& reach : reach_) {
    double d = 0;
    for (std::size_t j = 0; j < n; ++j) d += reach[j] * std::abs(to[j] - from[j]);
    worst = std::max(worst, d);
  }
  return worst;
}

bool CollisionWorld::pair_touches(int pair, Placement& at) const {
  const auto i = std::size_t(pairs_[std::size_t(pair)].first), j = std::size_t(pairs_[std::size_t(pair)].second);
  complete(at, i);
  complete(at, j);
  if (!overlap(at.low[i], at.high[i], at.low[j], at.high[j], 0)) return false;
  const fcl::CollisionRequestd request(1, false);
  fcl::CollisionResultd result;
  return fcl::collide(items_[i].geometry.get(), at.items[i], items_[j].geometry.get(), at.items[j], request, result) > 0;
}

double CollisionWorld::pair_gap(int pair, Placement& at) const {
  const auto i = std::size_t(pairs_[std::size_t(pair)].first), j = std::size_t(pairs_[std::size_t(pair)].second);
  complete(at, i);
  complete(at, j);
  return gap(at.low[i], at.high[i], at.low[j], at.high[j]);
}

double CollisionWorld::pair_distance(int pair, Placement& at) const {
  const auto i = std::size_t(pairs_[std::size_t(pair)].first), j = std::size_t(pairs_[std::size_t(pair)].second);
  complete(at, i);
  complete(at, j);
  const fcl::DistanceRequestd request;
  fcl::DistanceResultd result;
  fcl::distance(items_[i].geometry.get(), at.items[i], items_[j].geometry.get(), at.items[j], request, result);
  return std::max(0.0, result.min_distance);
}

double CollisionWorld::step_displacement_bound(const Placement& at, std::span<const double> travel, double pad,
                                               std::vector<double>* closing) const {
  const motion::LinkBodies& links = *arm_.links;
  const std::size_t n = std::min(travel.size(), arm_.joint_reach.size());
  auto dq = [&](int body) {
    const int j = links.bodies[std::size_t(body)].joint;
    return std::size_t(j) < n ? std::abs(travel[std::size_t(j)]) : 0.0;
  };
  // Each moving link's axis in the base frame, once: the items below share them.
  thread_local std::vector<Eigen::Vector3d> axes;
  axes.resize(links.bodies.size());
  for (std::size_t b = 0; b < links.bodies.size(); ++b)
    if (links.bodies[b].joint >= 0 && !links.bodies[b].prismatic) axes[b] = at.bodies[b].linear() * links.bodies[b].axis;
  // Per item, how far its points move for the first k links of its chain (its own link up):
  // two bounds, each summed over the joints: from the geometry at `from` (local) and from the
  // farthest the item can ever be from each axis (reach_). The smaller one holds.
  thread_local std::vector<double> local, far;
  thread_local std::vector<std::size_t> offset;
  local.clear();
  far.clear();
  offset.resize(items_.size());
  double worst = 0;
  for (std::size_t i = 0; i < items_.size(); ++i) {
    const Item& item = items_[i];
    offset[i] = local.size();
    double l = 0, f = 0;
    local.push_back(0);
    far.push_back(0);
    const Eigen::Vector3d& centre = at.centres[i];
    for (const int b : item.chain) {
      const motion::LinkBody& body = links.bodies[std::size_t(b)];
      const double d = dq(b);
      if (body.prismatic) {
        l += d;
        f += d;
      } else if (d > 0) {
        // The joint's axis passes through its link's origin (URDF: the joint frame is the child's).
        l += d * (axes[std::size_t(b)].cross(centre - at.bodies[std::size_t(b)].translation()).norm() + item.radius + pad);
        f += d * reach_[i][std::size_t(body.joint)];
      }
      local.push_back(l);
      far.push_back(f);
    }
    worst = std::max(worst, std::min(l, f));
  }
  if (closing) {
    closing->resize(pairs_.size());
    auto moved = [&](int item, int own) {
      const std::size_t k = offset[std::size_t(item)] + std::size_t(own);
      return std::min(local[k], far[k]);
    };
    for (std::size_t k = 0; k < pairs_.size(); ++k) {
      const Pair& p = pairs_[k];
      (*closing)[k] = moved(p.first, p.first_own) + moved(p.second, p.second_own);
    }
  }
  return worst;
}

}  // namespace armctl::scene
