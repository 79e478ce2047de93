#include "motion/trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <fmt/format.h>

namespace armctl::motion {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

Error refuse(std::string message) {
  return Error{ErrorKind::invalid_argument, "trajectory: " + std::move(message)};
}

JerkLimits limits_of(const TrajectoryInput& in, int i) {
  return JerkLimits{in.max_velocity[i], in.max_acceleration[i], in.max_jerk[i]};
}

// A finite value no larger in magnitude than kMaxTrajectoryMagnitude.
bool in_range(double x) {
  return std::isfinite(x) && std::abs(x) <= kMaxTrajectoryMagnitude;
}

Status validate(const TrajectoryInput& in) {
  if (in.joints < 1 || in.joints > kMaxTrajectoryJoints)
    return refuse(fmt::format("joint count {} (allowed: 1..{})", in.joints, kMaxTrajectoryJoints));
  if (!std::isfinite(in.min_duration) || in.min_duration < 0 ||
      in.min_duration > kMaxTrajectoryMagnitude)
    return refuse(fmt::format("min_duration {} s (allowed: 0..{:g} s)", in.min_duration,
                              kMaxTrajectoryMagnitude));
  for (int i = 0; i < in.joints; ++i) {
    const struct {
      const char* name;
      double value;
    } limits[] = {{"max_velocity", in.max_velocity[i]},
                  {"max_acceleration", in.max_acceleration[i]},
                  {"max_jerk", in.max_jerk[i]}};
    for (const auto& l : limits)
      if (!std::isfinite(l.value) || l.value < kMinTrajectoryLimit ||
          l.value > kMaxTrajectoryMagnitude)
        return refuse(fmt::format("joint {}: {} {} (allowed: finite, {:g}..{:g})", i, l.name,
                                  l.value, kMinTrajectoryLimit, kMaxTrajectoryMagnitude));
    const struct {
      const char* name;
      double value;
    } values[] = {{"position", in.position[i]},
                  {"velocity", in.velocity[i]},
                  {"acceleration", in.acceleration[i]},
                  {"target_position", in.target_position[i]},
                  {"target_velocity", in.target_velocity[i]}};
    for (const auto& v : values)
      if (!in_range(v.value))
        return refuse(fmt::format("joint {}: {} {} (allowed: finite, magnitude at most {:g})", i,
                                  v.name, v.value, kMaxTrajectoryMagnitude));
    const double vmax = in.max_velocity[i], amax = in.max_acceleration[i], j = in.max_jerk[i];
    if (std::abs(in.velocity[i]) > vmax)
      return refuse(
          fmt::format("joint {}: velocity {} is beyond max_velocity {} (allowed: |velocity| <= {})",
                      i, in.velocity[i], vmax, vmax));
    if (std::abs(in.target_velocity[i]) > vmax)
      return refuse(fmt::format(
          "joint {}: target_velocity {} is beyond max_velocity {} (allowed: |target_velocity| "
          "<= {})",
          i, in.target_velocity[i], vmax, vmax));
    if (std::abs(in.acceleration[i]) > amax)
      return refuse(fmt::format(
          "joint {}: acceleration {} is beyond max_acceleration {} (allowed: |acceleration| "
          "<= {})",
          i, in.acceleration[i], amax, amax));
    const double a0 = in.acceleration[i];
    const double v_stop = in.velocity[i] + a0 * std::abs(a0) / (2 * j);
    if (std::abs(v_stop) > vmax)
      return refuse(fmt::format(
          "joint {}: velocity {} with acceleration {} must reach {} before the acceleration "
          "can be brought to 0 at max_jerk {} (allowed: |velocity + acceleration "
          "|acceleration| / (2 max_jerk)| <= max_velocity {})",
          i, in.velocity[i], a0, v_stop, j, vmax));
  }
  for (std::size_t k = 0; k < in.waypoints.size(); ++k)
    for (int i = 0; i < in.joints; ++i)
      if (!in_range(in.waypoints[k][i]))
        return refuse(fmt::format(
            "waypoint {}: joint {}: position {} (allowed: finite, magnitude at most {:g})", k, i,
            in.waypoints[k][i], kMaxTrajectoryMagnitude));
  return Ok{};
}

// The k-th point the trajectory passes: 0 the start, 1..waypoints the waypoints, then the target.
const JointArray& point(const TrajectoryInput& in, std::size_t k) {
  if (k == 0) return in.position;
  if (k <= in.waypoints.size()) return in.waypoints[k - 1];
  return in.target_position;
}

// Section k's average velocity per joint, over the rest-to-rest minimum time of its
// slowest joint: an estimate made before any profile exists.
JointArray section_average(const TrajectoryInput& in, std::size_t k) {
  const JointArray &from = point(in, k), &to = point(in, k + 1);
  double time = 0;
  for (int i = 0; i < in.joints; ++i)
    time = std::max(time, rest_to_rest_time(to[i] - from[i], limits_of(in, i)));
  JointArray average{};
  if (time > 0)
    for (int i = 0; i < in.joints; ++i) average[i] = (to[i] - from[i]) / time;
  return average;
}

JointArray waypoint_velocity(const TrajectoryInput& in, const JointArray& before,
                             const JointArray& after) {
  JointArray v{};
  for (int i = 0; i < in.joints; ++i) {
    const bool same_direction = (before[i] > 0 && after[i] > 0) || (before[i] < 0 && after[i] < 0);
    if (same_direction)
      v[i] = std::clamp(0.5 * (before[i] + after[i]), -in.max_velocity[i], in.max_velocity[i]);
  }
  return v;
}

// One section: each joint from its start state to its end state, all arriving together
// at the smallest duration >= `at_least` that every joint can make.
struct SectionTask {
  JointArray position{}, velocity{}, acceleration{}, target_position{}, target_velocity{};
};

// Phase synchronization: when every joint's start velocity, start acceleration and target
// velocity are the same multiples of its displacement (e.g. rest to rest), one profile of
// a path parameter from 0 to 1, under the tightest of the joints' limits scaled by their
// displacements, moves every joint along the straight line between start and target. Used
// when that profile can take the time-synchronized duration `t` (always when the joints
// share their limits' ratios, as on rest-to-rest moves with equal limits); `out` is then
// overwritten with each joint's scaled copy. False (out untouched) otherwise.
bool phase_synchronize(const TrajectoryInput& in, const SectionTask& task, double t,
                       std::array<JerkSegments, kMaxTrajectoryJoints>& out) {
  int ref = -1;
  double widest = 0;
  for (int i = 0; i < in.joints; ++i) {
    const double d = std::abs(task.target_position[i] - task.position[i]);
    if (d > widest) widest = d, ref = i;
  }
  if (ref < 0) return false;
  const double dr = task.target_position[ref] - task.position[ref];
  const double v0 = task.velocity[ref] / dr, a0 = task.acceleration[ref] / dr,
               vf = task.target_velocity[ref] / dr;
  JerkLimits limits{kInf, kInf, kInf};
  for (int i = 0; i < in.joints; ++i) {
    const double d = task.target_position[i] - task.position[i];
    // Collinear to the last bits: the scaled copy must start and end exactly on each joint's
    // states.
    const double tolerance = 4 * std::numeric_limits<double>::epsilon();
    if (std::abs(task.velocity[i] - v0 * d) > tolerance * in.max_velocity[i] ||
        std::abs(task.target_velocity[i] - vf * d) > tolerance * in.max_velocity[i] ||
        std::abs(task.acceleration[i] - a0 * d) > tolerance * in.max_acceleration[i])
      return false;
    if (d == 0) continue;
    limits.velocity = std::min(limits.velocity, in.max_velocity[i] / std::abs(d));
    limits.acceleration = std::min(limits.acceleration, in.max_acceleration[i] / std::abs(d));
    limits.jerk = std::min(limits.jerk, in.max_jerk[i] / std::abs(d));
  }
  // The path's start must keep its own velocity limit (a joint's validation does not imply it).
  if (std::abs(v0) > limits.velocity || std::abs(vf) > limits.velocity ||
      std::abs(a0) > limits.acceleration ||
      std::abs(v0 + a0 * std::abs(a0) / (2 * limits.jerk)) > limits.velocity)
    return false;
  JerkPlan path;
  path.plan(JerkTask{0, v0, a0, 1, vf}, limits);
  JerkSegments s;
  if (path.next_possible(t) != t || !path.build(t, s)) return false;
  for (int i = 0; i < in.joints; ++i) {
    const double d = task.target_position[i] - task.position[i];
    for (int k = 0; k < kProfileSegments; ++k) {
      JerkSegment g = s[k];
      g.position = task.position[i] + d * g.position;
      g.velocity *= d, g.acceleration *= d, g.jerk *= d;
      out[i][k] = g;
    }
  }
  return true;
}

// Plans every joint of a section and returns the smallest duration >= `at_least` that
// every joint can make, with each joint's profile for it in `out`.
double synchronize(const TrajectoryInput& in, const SectionTask& task, double at_least,
                   std::array<JerkPlan, kMaxTrajectoryJoints>& plans,
                   std::array<JerkSegments, kMaxTrajectoryJoints>& out) {
  double t0 = at_least;
  for (int i = 0; i < in.joints; ++i) {
    plans[i].plan(JerkTask{task.position[i], task.velocity[i], task.acceleration[i],
                           task.target_position[i], task.target_velocity[i]},
                  limits_of(in, i));
    t0 = std::max(t0, plans[i].min_duration());
  }
  for (;;) {
    // Move past every joint's blocked intervals; each joint's durations end in an unbounded
    // interval, so this ends.
    double t = t0;
    for (bool moved = true; moved;) {
      moved = false;
      for (int i = 0; i < in.joints; ++i) {
        const double next = plans[i].next_possible(t);
        if (next > t) t = next, moved = true;
      }
    }
    // A plan that claimed too much corrects itself; then look again.
    bool built = true;
    for (int i = 0; i < in.joints; ++i) built = plans[i].build(t, out[i]) && built;
    if (built) {
      if (in.joints > 1) phase_synchronize(in, task, t, out);
      return t;
    }
    for (int i = 0; i < in.joints; ++i)
      t0 = std::max(at_least, std::max(t0, plans[i].min_duration()));
  }
}

SectionTask section_task(const TrajectoryInput& in, std::size_t k, const JointArray& start_velocity,
                         const JointArray& end_velocity) {
  SectionTask s;
  s.position = point(in, k);
  s.target_position = point(in, k + 1);
  s.velocity = start_velocity;
  s.target_velocity = end_velocity;
  if (k == 0) s.acceleration = in.acceleration;
  return s;
}

}  // namespace

double rest_to_rest_time(double distance, const JerkLimits& limits) {
  const double d = std::abs(distance), vmax = limits.velocity, amax = limits.acceleration,
               j = limits.jerk;
  if (d == 0) return 0;
  // Time of one velocity change from 0 to v: triangular in acceleration below amax^2/j.
  auto change = [&](double v) {
    return v * j >= amax * amax ? v / amax + amax / j : 2 * std::sqrt(v / j);
  };
  const double to_vmax = change(vmax);
  if (d >= vmax * to_vmax) return to_vmax + d / vmax;  // two changes cover vmax * to_vmax
  // No cruise: d = vp * change(vp). Triangular: d = 2 vp^1.5 / sqrt(j).
  const double vp = std::cbrt(d * d * j / 4);
  if (vp * j <= amax * amax) return 2 * change(vp);
  // Trapezoidal: d = vp^2 / amax + vp amax / j.
  const double b = amax / j;
  const double vq = amax / 2 * (-b + std::sqrt(b * b + 4 * d / amax));
  return 2 * change(vq);
}

void waypoint_velocities(const TrajectoryInput& in, std::span<JointArray> out) {
  const std::size_t n = std::min(out.size(), in.waypoints.size());
  if (n == 0) return;
  JointArray before = section_average(in, 0);
  for (std::size_t k = 0; k < n; ++k) {
    const JointArray after = section_average(in, k + 1);
    out[k] = waypoint_velocity(in, before, after);
    before = after;
  }
}

Status calculate_trajectory(const TrajectoryInput& in, Trajectory& out) {
  if (Status s = validate(in); !s) return s;
  const std::size_t count = in.waypoints.size() + 1;
  std::array<JerkPlan, kMaxTrajectoryJoints> plans;

  // Sections are independent once the waypoint velocities are chosen (acceleration 0 at
  // every waypoint), so each is synchronized on its own; a min_duration longer than their
  // sum stretches every section in proportion.
  auto run = [&](double stretch) {
    double total = 0;
    JointArray start_velocity = in.velocity;
    JointArray before = count > 1 ? section_average(in, 0) : JointArray{};
    for (std::size_t k = 0; k < count; ++k) {
      JointArray end_velocity = in.target_velocity, after{};
      if (k + 1 < count) {
        after = section_average(in, k + 1);
        end_velocity = waypoint_velocity(in, before, after);
      }
      const SectionTask task = section_task(in, k, start_velocity, end_velocity);
      Trajectory::Section& section = out.sections_[k];
      const double at_least = count == 1 ? in.min_duration : stretch * section.end;
      const double t = synchronize(in, task, at_least, plans, section.joints);
      section.start = total;
      section.end = t;  // the first pass keeps each section's own minimum here
      total += t;
      start_velocity = end_velocity;
      before = after;
    }
    return total;
  };

  // Storage first (the only allocation), then nothing can fail.
  if (out.sections_.size() < count) out.sections_.resize(count);
  for (std::size_t k = 0; k < count; ++k) out.sections_[k].end = 0;
  // Each section is planned once; only a min_duration beyond the sections' sum needs a
  // second pass, stretching them (a stretch of 1 would only repeat the first pass).
  const double fastest = run(1);
  if (count > 1 && in.min_duration > fastest && fastest > 0) run(in.min_duration / fastest);
  for (std::size_t k = 0; k < count; ++k) out.sections_[k].end += out.sections_[k].start;
  out.joints_ = in.joints;
  out.section_count_ = static_cast<int>(count);
  return Ok{};
}

double Trajectory::duration() const {
  return section_count_ ? sections_[section_count_ - 1].end : 0;
}

double Trajectory::section_end(int k) const {
  return sections_[std::clamp(k, 0, section_count_ - 1)].end;
}

double Trajectory::section_start(int k) const {
  return sections_[std::clamp(k, 0, section_count_ - 1)].start;
}

std::span<const JerkSegment> Trajectory::segments(int section, int joint) const {
  if (section < 0 || section >= section_count_ || joint < 0 || joint >= joints_) return {};
  return sections_[section].joints[joint];
}

TrajectoryState Trajectory::at(double t) const {
  TrajectoryState state;
  if (section_count_ == 0) return state;
  t = std::clamp(t, 0.0, duration());
  // The first section that ends at or after t.
  const auto end = sections_.begin() + section_count_;
  auto it = std::lower_bound(sections_.begin(), end, t,
                             [](const Section& s, double x) { return s.end < x; });
  if (it == end) --it;
  const double local = t - it->start;
  for (int i = 0; i < joints_; ++i) {
    const JerkSegments& segs = it->joints[i];
    int k = kProfileSegments - 1;
    while (k > 0 && segs[k].start > local) --k;
    const JerkState s = advance(segs[k], local - segs[k].start);
    state.position[i] = s.position;
    state.velocity[i] = s.velocity;
    state.acceleration[i] = s.acceleration;
    state.jerk[i] = segs[k].jerk;
  }
  return state;
}

TrajectoryExtrema Trajectory::extrema() const {
  TrajectoryExtrema e;
  for (int i = 0; i < joints_; ++i) e.min_position[i] = kInf, e.max_position[i] = -kInf;
  auto position = [](int i, double p, TrajectoryExtrema& x) {
    x.min_position[i] = std::min(x.min_position[i], p);
    x.max_position[i] = std::max(x.max_position[i], p);
  };
  for (int k = 0; k < section_count_; ++k) {
    for (int i = 0; i < joints_; ++i) {
      for (const JerkSegment& s : sections_[k].joints[i]) {
        const JerkState end = advance(s, s.duration);
        e.max_abs_jerk[i] = std::max(e.max_abs_jerk[i], s.duration > 0 ? std::abs(s.jerk) : 0.0);
        e.max_abs_acceleration[i] = std::max(
            {e.max_abs_acceleration[i], std::abs(s.acceleration), std::abs(end.acceleration)});
        double vmax = std::max(std::abs(s.velocity), std::abs(end.velocity));
        // The velocity peaks inside where a = 0.
        if (s.jerk != 0) {
          const double tp = -s.acceleration / s.jerk;
          if (tp > 0 && tp < s.duration) vmax = std::max(vmax, std::abs(advance(s, tp).velocity));
        }
        e.max_abs_velocity[i] = std::max(e.max_abs_velocity[i], vmax);
        position(i, s.position, e);
        position(i, end.position, e);
        // The position turns inside where v = 0: jerk/2 t^2 + a t + v = 0.
        const double qa = s.jerk / 2, qb = s.acceleration, qc = s.velocity;
        double roots[2];
        int n = 0;
        if (qa != 0) {
          const double disc = qb * qb - 4 * qa * qc;
          if (disc >= 0) {
            const double q = -0.5 * (qb + std::copysign(std::sqrt(disc), qb));
            if (q != 0)
              roots[n++] = q / qa, roots[n++] = qc / q;
            else
              roots[n++] = 0;
          }
        } else if (qb != 0) {
          roots[n++] = -qc / qb;
        }
        for (int r = 0; r < n; ++r)
          if (roots[r] > 0 && roots[r] < s.duration) position(i, advance(s, roots[r]).position, e);
      }
    }
  }
  return e;
}

}  // namespace armctl::motion
