// One joint's jerk-limited profile between two states, the building block of trajectory.hpp.
//
// The family (docs/trajectories.md "Method"): a velocity change from (v0, a0) to a peak
// velocity vp with a = 0, a cruise at vp for tc >= 0, a velocity change from vp to vf with
// a = 0. Each velocity change is the fastest one the limits allow (jerk +-j, a plateau at
// +-amax if the change is large enough, jerk back), so a profile is fixed by vp and the
// duration it must take. Besides, when a0 != 0, "release" profiles that never pass a = 0
// on the way: jerk toward a = 0 for tau < |a0| / j, then at once the fastest change to vf
// (they have no cruise, so each is one duration). Pure arithmetic: no I/O, no allocation,
// no exceptions.
//
// The family is an inner approximation of the durations a joint can take. The exact set
// (docs/trajectories.md "Exact durations"): in exactly T the end state (vf, 0) can be reached
// with any displacement between the least and the most possible in T (the jerk-limited
// motions of duration T form a convex set), and those two extremal motions are members of
// the family or releases (bang-bang jerk +-+ or -+-). A duration the family lacks but that
// lies inside is built as the blend of the two extremal motions that lands on the target.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

namespace armctl::motion {

struct JerkLimits {
  double velocity = 1, acceleration = 1, jerk = 1;  // all > 0, finite
};

// Where a joint starts and where it must arrive (target acceleration is 0).
struct JerkTask {
  double position = 0, velocity = 0, acceleration = 0;
  double target_position = 0, target_velocity = 0;
};

// A piece of constant jerk: the state at its start and how long it lasts.
struct JerkSegment {
  double start = 0;  // s, from the start of its section
  double duration = 0;
  double position = 0, velocity = 0, acceleration = 0, jerk = 0;
};

// Seven for a member of the family; a blend of two extremal motions (seven pieces each) has
// at most thirteen. Unused trailing segments last 0 s and hold the end state.
inline constexpr int kProfileSegments = 13;
inline constexpr int kFamilySegments = 7;
using JerkSegments = std::array<JerkSegment, kProfileSegments>;

// The durations a joint can take to do its task within the family, as closed intervals
// (the last one unbounded), and how to build the profile for any one of them. Filled by
// `plan`; bounded storage, no heap.
class JerkPlan {
 public:
  // Samples of vp across [-vmax, vmax]: breakpoints where the family's shape changes,
  // points between them, the roots of "no cruise needed".
  static constexpr int kMaxSamples = 64;
  static constexpr int kMaxPoints = 2 * kMaxSamples;
  static constexpr int kMaxIntervals = kMaxPoints + 16;  // + a cruise at rest, releases

  void plan(const JerkTask& task, const JerkLimits& limits);
  double min_duration() const { return min_duration_; }
  // The smallest duration >= t this joint can take (t itself if it can): a duration the
  // family claims, or one between the extremal displacements (exact); past a blocked
  // interval, the family's next claimed duration is its end (every end of a blocked
  // interval is an extremal motion, and those are in the family).
  double next_possible(double t) const;
  // The profile of exactly `duration` (a value next_possible returned unchanged). False
  // if the plan found it had claimed a duration it cannot make: it has corrected itself
  // (next_possible tells anew) and `out` is unchanged.
  bool build(double duration, JerkSegments& out);

  // The motion that covers the most ground (direction +1) or the least (-1) in exactly
  // `duration`, as constant-jerk pieces from the start state, and its displacement. False
  // if `duration` is shorter than the fastest velocity change to the target velocity.
  struct Extremal {
    double durations[kFamilySegments], jerks[kFamilySegments];
    int count;
    double displacement;
  };
  bool extremal(double duration, double direction, Extremal& out) const;

 private:
  struct Point {
    double vp, remaining, ramps, duration;  // remaining: distance left for the cruise
  };
  struct Interval {
    double lo, hi;
    // Points whose durations bracket the interval; b == kCruiseAtRest: a cruise at vp = 0
    // after point a; b == kRelease: release profile a.
    int a, b;
  };
  static constexpr int kCruiseAtRest = -1, kRelease = -2;
  static constexpr int kReleaseSamples = 4;
  struct Release {
    double tau, duration;
  };
  // Release for tau: what the fastest change to vf leaves to cover, and the duration.
  Release release(double tau, double& remaining) const;
  void plan_releases();
  Release releases_[kReleaseSamples + 1];
  int release_count_ = 0;
  Point evaluate(double vp) const;
  double rounding() const;
  int add_hidden_crossings(Point* samples, int count) const;
  void derive();           // points, intervals and min_duration from the samples and releases
  bool refine(double vp);  // one more sample, then derive
  double root_of_remaining(const Point& x, const Point& y) const;
  double vp_for_duration(const Point& x, const Point& y, double duration) const;
  bool between_extremals(double duration) const;
  bool build_blend(double duration, JerkSegments& out) const;
  void fill(const double* durations, const double* jerks, int count, JerkSegments& out) const;

  JerkTask task_{};
  JerkLimits limits_{};
  double inv_jerk_ = 1, inv_acceleration_ = 1;  // of limits_, for velocity_change
  // Left uninitialized: plan() fills what it uses (a trajectory plans 7 of these per section).
  Point samples_[kMaxSamples];
  int sample_count_ = 0;
  Point points_[kMaxPoints];
  int point_count_ = 0;
  Interval intervals_[kMaxIntervals];
  int interval_count_ = 0;
  double min_duration_ = 0;
};

// The fastest velocity change from (v0, a0) to (v1, 0), as up to three segments: jerk
// toward v1, a plateau at +-amax, jerk back to a = 0. Requires |a0| <= amax.
struct VelocityChange {
  double jerk = 0;  // signed jerk of the first segment (the last has -jerk)
  double ramp_up = 0, hold = 0, ramp_down = 0;  // s
  double duration = 0, displacement = 0;
};

// Inline: the plan evaluates it some fifty times per joint. `inv_jerk` and `inv_acceleration`
// are 1 / limits.jerk and 1 / limits.acceleration: a plan computes them once (divisions
// each time cost some 7 % of a 7-joint trajectory).
[[gnu::always_inline]] inline VelocityChange velocity_change(double v0, double a0, double v1, const JerkLimits& limits,
                                                             double inv_jerk, double inv_acceleration) {
  const double j = limits.jerk, amax = limits.acceleration;
  // Bringing a to 0 at once ends at v_stop: above it the change starts with jerk +j, below
  // it with -j. Mirrored so that it is always +j.
  const double v_stop = v0 + a0 * std::abs(a0) * 0.5 * inv_jerk;
  const double s = v1 >= v_stop ? 1.0 : -1.0;
  const double u0 = s * v0, b0 = s * a0, dv = s * v1 - u0;
  // Peak acceleration ap of a triangle: dv = (2 ap^2 - b0^2) / (2j); a plateau at amax if
  // that would exceed it.
  double ap = std::sqrt(std::max(0.0, dv * j + b0 * b0 / 2));
  double hold = 0;
  if (ap > amax) {
    ap = amax;
    hold = std::max(0.0, (dv - (2 * amax * amax - b0 * b0) * 0.5 * inv_jerk) * inv_acceleration);
  }
  VelocityChange c;
  c.jerk = s * j;
  c.ramp_up = std::max(0.0, (ap - b0) * inv_jerk);
  c.hold = hold;
  c.ramp_down = ap * inv_jerk;
  c.duration = c.ramp_up + c.hold + c.ramp_down;
  double p = 0, u = u0;
  const double t1 = c.ramp_up, t3 = c.ramp_down;
  p += t1 * (u + t1 * (b0 / 2 + t1 * j / 6));
  u += t1 * (b0 + t1 * j / 2);
  p += hold * (u + hold * ap / 2);
  u += hold * ap;
  p += t3 * (u + t3 * (ap / 2 - t3 * j / 6));
  c.displacement = s * p;
  return c;
}

// The state after `dt` of constant jerk from a segment's start state.
struct JerkState {
  double position = 0, velocity = 0, acceleration = 0;
};
inline JerkState advance(const JerkSegment& s, double dt) {
  return {s.position + dt * (s.velocity + dt * (s.acceleration / 2 + dt * s.jerk / 6)),
          s.velocity + dt * (s.acceleration + dt * s.jerk / 2), s.acceleration + dt * s.jerk};
}

}  // namespace armctl::motion
