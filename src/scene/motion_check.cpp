#include "scene/motion_check.hpp"

#include <algorithm>
#include <limits>

namespace armctl::scene {

namespace {

// FCL's distance between primitives is exact to well below this; taken off each measured
// distance so that a pair skipped as apart surely is.
constexpr double kDistanceTolerance = 1e-6;  // m
// How much further beyond a limit it started beyond a motion may go between two checks
// without a refusal: rounding, not motion (m for the fence, rad for a joint range).
constexpr double kBeyondTolerance = 1e-6;

}  // namespace

LimitsBeyond::LimitsBeyond(const CollisionWorld& world, std::span<const int> skip) : world_(&world) {
  for (int index : skip)
    if (std::size_t(index) >= world.pairs_checked()) limits_.emplace_back(index, std::numeric_limits<double>::infinity());
}

std::optional<Contact> LimitsBeyond::deeper(std::span<const double> joints, CollisionWorld::Placement& at, bool update) {
  std::optional<Contact> out;
  for (auto& [index, least] : limits_) {
    auto c = world_->limit_at(index, joints, at);
    const double depth = c ? c->depth : 0.0;
    if (depth > least + kBeyondTolerance && !out) {
      // (The depth says how far beyond it; the words say why a limit already broken is refused.)
      c->second += ", further beyond it than the motion has been since it started";
      out = std::move(c);
    }
    if (update) least = std::min(least, depth);
  }
  return out;
}

MotionCheck check_motion(const CollisionWorld& world, double duration,
                         const std::function<void(double, std::vector<double>&)>& sample, double resolution) {
  MotionCheck out;
  std::vector<double> q0, q1, mid;
  sample(0, q0);
  const std::size_t n_pairs = world.pairs_checked();
  // apart[p]: how far apart pair p's bodies are at least, now (0 at first: they may touch).
  // A check asks FCL only where that says nothing: contact where it is used up, distance
  // where it is below the best so far.
  std::vector<double> apart(n_pairs, 0.0);
  const std::vector<int> skip = world.touching(q0);
  for (int pair : skip) {
    // Named by body: two shapes of one link touching the same body are one pair for people.
    auto names = world.pair_names(pair);
    auto& list = std::size_t(pair) < n_pairs ? out.started_touching : out.started_beyond;
    if (std::find(list.begin(), list.end(), names) == list.end()) list.push_back(std::move(names));
  }
  // Pairs touching at the start are never asked; limits broken there may not get deeper.
  std::vector<bool> asked(n_pairs, true);
  for (int pair : skip)
    if (std::size_t(pair) < n_pairs) asked[std::size_t(pair)] = false;
  LimitsBeyond beyond(world, skip);

  auto check = [&](double t, const std::vector<double>& q, CollisionWorld::Placement& at) {
    ++out.checks;
    // The fence and reduced mode's joint ranges: cheap, asked at every check.
    auto broken = world.limit_breach(q, at, skip);
    if (!broken && !beyond.empty()) broken = beyond.deeper(q, at, true);
    if (broken) {
      out.contact = std::move(broken);
      out.at = t;
      out.joints = q;
      return false;
    }
    for (std::size_t p = 0; p < n_pairs; ++p) {
      if (!asked[p] || apart[p] > 0) continue;
      ++out.queries;
      if (world.pair_touches(int(p), at)) {
        out.contact = world.contact(q, skip);
        if (!out.contact) out.contact = Contact{};  // (a touch the deeper query does not see twice)
        out.at = t;
        out.joints = q;
        return false;
      }
    }
    for (std::size_t p = 0; p < n_pairs; ++p) {
      if (!asked[p] || apart[p] >= out.clearance.distance) continue;
      // The boxes' gap is never more than the shapes' distance: at or beyond the best so
      // far, the pair cannot be nearer, and the gap is the pair's new bound.
      if (const double gap = world.pair_gap(int(p), at); gap >= out.clearance.distance) {
        apart[p] = std::max(apart[p], gap);
        continue;
      }
      ++out.queries;
      const double d = world.pair_distance(int(p), at);
      apart[p] = d - kDistanceTolerance;
      if (d < out.clearance.distance) {
        auto [first, second] = world.pair_names(int(p));
        out.clearance = Clearance{d, std::move(first), std::move(second)};
        out.at = t;
        out.joints = q;
      }
    }
    return true;
  };

  CollisionWorld::Placement at0, at1;
  world.place(q0, at0);
  if (!check(0, q0, at0) || !(duration > 0)) return out;
  // Steps halve until the bound on how far any point moves is within the resolution, and
  // grow towards 90 % of it again (at most doubling). The bound is over both halves of the
  // step (each joint's travel to the middle and on to the end), so that a joint turning back
  // within it is seen; the arm's geometry at the step's start holds for all of it (pad).
  const double pad = 2 * resolution;
  std::vector<double> closing, travel;
  double t = 0, h = std::min(duration, 0.01);
  while (t < duration) {
    const double t1 = std::min(duration, t + h);
    sample(0.5 * (t + t1), mid);
    sample(t1, q1);
    travel.resize(q0.size());
    for (std::size_t j = 0; j < q0.size(); ++j) travel[j] = std::abs(mid[j] - q0[j]) + std::abs(q1[j] - mid[j]);
    const double moved = world.step_displacement_bound(at0, travel, pad, &closing);
    if (moved > resolution && h > 1e-6) {
      h *= 0.5;
      continue;
    }
    for (std::size_t p = 0; p < n_pairs; ++p) apart[p] -= closing[p];
    world.place(q1, at1);
    if (!check(t1, q1, at1)) return out;
    t = t1;
    std::swap(q0, q1);
    std::swap(at0, at1);
    h *= moved > 0 ? std::clamp(0.9 * resolution / moved, 0.5, 2.0) : 2.0;
  }
  return out;
}

}  // namespace armctl::scene
