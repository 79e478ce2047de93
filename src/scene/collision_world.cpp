#include "scene/collision_world.hpp"

#include <algorithm>
#include <cmath>

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>
#include <fmt/format.h>

namespace armctl::scene {

struct CollisionWorld::Item {
  std::string label;
  int body = -1;         // the link it moves with; -1: fixed in the base frame
  motion::Shape shape;   // its pose in the link's frame (or the base frame)
  std::shared_ptr<fcl::CollisionGeometryd> geometry;
  bool scene = false;    // a scene object (fixed or held), not a link
  Eigen::Vector3d low = Eigen::Vector3d::Zero(), high = Eigen::Vector3d::Zero();  // fixed ones: bounds
};

struct CollisionWorld::Frames {
  std::vector<Eigen::Isometry3d> bodies, items;
  std::vector<Eigen::Vector3d> low, high;
};

CollisionWorld::~CollisionWorld() = default;

namespace {

std::shared_ptr<fcl::CollisionGeometryd> fcl_geometry(const motion::Shape& s) {
  switch (s.kind) {
    case motion::Shape::Kind::box: return std::make_shared<fcl::Boxd>(s.size.x(), s.size.y(), s.size.z());
    case motion::Shape::Kind::cylinder: return std::make_shared<fcl::Cylinderd>(s.size.x(), s.size.y());
    case motion::Shape::Kind::sphere: return std::make_shared<fcl::Sphered>(s.size.x());
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
      w->items_.push_back(Item{fmt::format("link '{}'", links.bodies[b].name), int(b), s, fcl_geometry(s), false, {}, {}});
    }
  }
  const std::size_t n_links = w->items_.size();
  // Parts held by the tool hang from the tool link; what holds them never counts as a touch.
  const int holder = links.bodies[std::size_t(*tool)].parent;
  for (const auto& o : scene.objects) {
    Item item{describe(o), o.attached ? *tool : -1, o.shape, fcl_geometry(o.shape), true, {}, {}};
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
      w->pairs_.emplace_back(int(i), int(j));
    }
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
  return std::shared_ptr<const CollisionWorld>(std::move(w));
}

void CollisionWorld::place(std::span<const double> joints, Frames& f) const {
  arm_.links->poses(joints, f.bodies);
  f.items.resize(items_.size());
  f.low.resize(items_.size());
  f.high.resize(items_.size());
  for (std::size_t i = 0; i < items_.size(); ++i) {
    const Item& item = items_[i];
    if (item.body < 0) {
      f.items[i] = item.shape.pose;
      f.low[i] = item.low;
      f.high[i] = item.high;
    } else {
      f.items[i] = f.bodies[std::size_t(item.body)] * item.shape.pose;
      motion::world_bounds(item.shape, f.items[i], f.low[i], f.high[i]);
    }
  }
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
  thread_local Frames f;
  place(joints, f);
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
  return out;
}

std::pair<std::string, std::string> CollisionWorld::pair_names(int pair) const {
  const auto [i, j] = pairs_[std::size_t(pair)];
  return {items_[std::size_t(i)].label, items_[std::size_t(j)].label};
}

std::optional<Contact> CollisionWorld::contact(std::span<const double> joints, std::span<const int> skip) const {
  std::optional<Contact> deepest;
  each_touching(joints, skip, true, [&](std::size_t k, const fcl::CollisionResultd& result) {
    const fcl::Contactd& c = result.getContact(0);
    if (!deepest || c.penetration_depth > deepest->depth) {
      const auto [i, j] = pairs_[k];
      deepest = Contact{items_[std::size_t(i)].label, items_[std::size_t(j)].label, c.penetration_depth, c.pos};
    }
    return true;
  });
  return deepest;
}

Clearance CollisionWorld::clearance(std::span<const double> joints, double below, std::span<const int> skip) const {
  thread_local Frames f;
  place(joints, f);
  Clearance best;
  best.distance = std::min(below, kClearanceHorizon);
  fcl::DistanceRequestd request;
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    const auto [i, j] = pairs_[k];
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

double CollisionWorld::step_displacement_bound(std::span<const double> from, std::span<const double> to, double pad) const {
  const motion::LinkBodies& links = *arm_.links;
  thread_local std::vector<Eigen::Isometry3d> poses;
  links.poses(from, poses);
  const std::size_t n = std::min({from.size(), to.size(), arm_.joint_reach.size()});
  double worst = 0;
  for (const Item& item : items_) {
    if (item.body < 0) continue;
    const Eigen::Vector3d centre = poses[std::size_t(item.body)] * item.shape.pose.translation();
    const double own = motion::bounding_radius(item.shape);
    double d = 0;
    for (int b = item.body; b >= 0; b = links.bodies[std::size_t(b)].parent) {
      const motion::LinkBody& body = links.bodies[std::size_t(b)];
      if (body.joint < 0 || std::size_t(body.joint) >= n) continue;
      const double dq = std::abs(to[std::size_t(body.joint)] - from[std::size_t(body.joint)]);
      if (body.prismatic) {
        d += dq;
        continue;
      }
      // The joint's axis passes through its link's origin (URDF: the joint frame is the child's).
      const Eigen::Vector3d axis = poses[std::size_t(b)].linear() * body.axis;
      const double r = axis.cross(centre - poses[std::size_t(b)].translation()).norm() + own + pad;
      d += dq * r;
    }
    worst = std::max(worst, d);
  }
  return std::min(worst, displacement_bound(from, to));
}

MotionCheck check_motion(const CollisionWorld& world, double duration,
                         const std::function<void(double, std::vector<double>&)>& sample, double resolution) {
  MotionCheck out;
  std::vector<double> q0, q1, mid;
  sample(0, q0);
  const std::vector<int> skip = world.touching(q0);
  for (int pair : skip) {
    // Named by body: two shapes of one link touching the same body are one pair for people.
    auto names = world.pair_names(pair);
    if (std::find(out.started_touching.begin(), out.started_touching.end(), names) == out.started_touching.end()) {
      out.started_touching.push_back(std::move(names));
    }
  }
  auto check = [&](double t, const std::vector<double>& q) {
    ++out.checks;
    if (world.collides(q, skip)) {
      out.contact = world.contact(q, skip);
      if (!out.contact) out.contact = Contact{};  // (a touch the deeper query does not see twice)
      out.at = t;
      out.joints = q;
      return false;
    }
    const Clearance c = world.clearance(q, out.clearance.distance, skip);
    if (c.distance < out.clearance.distance) {
      out.clearance = c;
      out.at = t;
      out.joints = q;
    }
    return true;
  };
  if (!check(0, q0) || !(duration > 0)) return out;
  // Steps halve until the bound on how far any point moves (over both halves of the step,
  // so that a joint turning back within it is seen) is within the resolution, and double
  // again when well within it.
  double t = 0, h = std::min(duration, 0.01);
  while (t < duration) {
    const double t1 = std::min(duration, t + h);
    sample(0.5 * (t + t1), mid);
    sample(t1, q1);
    const double moved = world.step_displacement_bound(q0, mid, 2 * resolution) +
                         world.step_displacement_bound(mid, q1, 2 * resolution);
    if (moved > resolution && h > 1e-6) {
      h *= 0.5;
      continue;
    }
    if (!check(t1, q1)) return out;
    t = t1;
    std::swap(q0, q1);
    if (moved < 0.25 * resolution) h *= 2;
  }
  return out;
}

}  // namespace armctl::scene
