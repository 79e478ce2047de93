// Random trajectory cases and the checks every one must pass, shared by trajectory_test
// (100,000 cases) and trajectory_million_test (1,000,000).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "motion/trajectory.hpp"

namespace armctl::motion::testing {

// Tolerances: the final state (absolute, positions of order 1..10), the limits (relative).
inline constexpr double kFinalTolerance = 1e-8;
inline constexpr double kLimitTolerance = 1e-9;

// Random joints 1..7; limits log-uniform over three decades each; a start state inside the
// limits (velocity, acceleration, and the velocity the acceleration carries it to);
// targets up to a few stopping distances away. One case in eight starts at rest, one in
// eight ends at rest, one in sixteen starts on its target.
class RandomCases {
 public:
  explicit RandomCases(std::uint64_t seed) : rng_(seed) {}

  // `joints` 0: a random count 1..7.
  TrajectoryInput next(int joints = 0) {
    TrajectoryInput in;
    in.joints =
        joints > 0 ? joints : std::uniform_int_distribution<int>(1, kMaxTrajectoryJoints)(rng_);
    const bool from_rest = pick(8), to_rest = pick(8);
    for (int i = 0; i < in.joints; ++i) {
      const double vmax = log_uniform(0.05, 50), amax = log_uniform(0.1, 100),
                   jmax = log_uniform(0.2, 1000);
      in.max_velocity[i] = vmax, in.max_acceleration[i] = amax, in.max_jerk[i] = jmax;
      in.position[i] = uniform(-5, 5);
      if (!from_rest) {
        in.velocity[i] = pick(10) ? (pick(2) ? vmax : -vmax) : uniform(-vmax, vmax);
        in.acceleration[i] = pick(10) ? 0 : uniform(-amax, amax);
        // Keep v + a|a|/(2j) inside the limit: shrink a until it is.
        const double room = vmax - in.velocity[i] * (in.acceleration[i] > 0 ? 1 : -1);
        const double a_allowed = 0.999999 * std::sqrt(std::max(0.0, 2 * jmax * room));
        in.acceleration[i] = std::clamp(in.acceleration[i], -a_allowed, a_allowed);
      }
      const double reach = std::max(0.1, vmax * vmax / amax + vmax * amax / jmax);
      in.target_position[i] =
          pick(16) ? in.position[i] : in.position[i] + uniform(-3, 3) * std::min(reach, 10.0);
      in.target_velocity[i] = to_rest || pick(4) ? 0 : uniform(-vmax, vmax);
    }
    return in;
  }

 private:
  bool pick(int one_in) { return std::uniform_int_distribution<int>(0, one_in - 1)(rng_) == 0; }
  double uniform(double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng_);
  }
  double log_uniform(double lo, double hi) { return std::exp(uniform(std::log(lo), std::log(hi))); }
  std::mt19937_64 rng_;
};

inline std::string describe(const TrajectoryInput& in) {
  std::string s = "joints " + std::to_string(in.joints);
  for (int i = 0; i < in.joints; ++i) {
    char line[400];
    std::snprintf(line, sizeof line,
                  "\n  joint %d: p0 %.17g v0 %.17g a0 %.17g -> p %.17g v %.17g; limits v %.17g a "
                  "%.17g j %.17g",
                  i, in.position[i], in.velocity[i], in.acceleration[i], in.target_position[i],
                  in.target_velocity[i], in.max_velocity[i], in.max_acceleration[i],
                  in.max_jerk[i]);
    s += line;
  }
  return s;
}

// Every check on one calculated trajectory; the first failure's description, or empty.
inline std::string check_trajectory(const TrajectoryInput& in, const Trajectory& traj) {
  char why[300];
  const double total = traj.duration();
  if (!std::isfinite(total) || total < 0) return "duration not finite";
  if (traj.duration() < in.min_duration) return "shorter than min_duration";
  double section_start = 0;
  for (int k = 0; k < traj.sections(); ++k) {
    const double length = traj.section_end(k) - section_start;
    for (int i = 0; i < in.joints; ++i) {
      const auto segs = traj.segments(k, i);
      const double vmax = in.max_velocity[i], amax = in.max_acceleration[i], jmax = in.max_jerk[i];
      double t = 0;
      for (std::size_t s = 0; s < segs.size(); ++s) {
        const JerkSegment& g = segs[s];
        if (!(g.duration >= 0) || !std::isfinite(g.duration))
          return "negative or non-finite segment";
        if (std::abs(g.start - t) > 1e-12 * std::max(1.0, total))
          return "segments not back to back";
        t += g.duration;
        if (g.duration > 0 && std::abs(g.jerk) > jmax * (1 + kLimitTolerance))
          return "jerk above its limit";
        // The segment's analytic extrema: |a| at its ends, |v| at its ends or where a = 0.
        const JerkState end = advance(g, g.duration);
        double vpeak = std::max(std::abs(g.velocity), std::abs(end.velocity));
        if (g.jerk != 0) {
          const double tp = -g.acceleration / g.jerk;
          if (tp > 0 && tp < g.duration) vpeak = std::max(vpeak, std::abs(advance(g, tp).velocity));
        }
        if (vpeak > vmax * (1 + kLimitTolerance)) {
          std::snprintf(why, sizeof why, "section %d joint %d segment %zu: |v| %.17g above %.17g",
                        k, i, s, vpeak, vmax);
          return why;
        }
        const double apeak = std::max(std::abs(g.acceleration), std::abs(end.acceleration));
        if (apeak > amax * (1 + kLimitTolerance)) {
          std::snprintf(why, sizeof why, "section %d joint %d segment %zu: |a| %.17g above %.17g",
                        k, i, s, apeak, amax);
          return why;
        }
        // Continuity: this segment's end is the next one's start.
        if (s + 1 < segs.size()) {
          const JerkSegment& n = segs[s + 1];
          const double scale = std::max({1.0, std::abs(end.position)});
          if (std::abs(n.position - end.position) > 1e-12 * scale ||
              std::abs(n.velocity - end.velocity) > 1e-9 * vmax ||
              std::abs(n.acceleration - end.acceleration) > 1e-9 * amax) {
            std::snprintf(why, sizeof why,
                          "section %d joint %d: jump after segment %zu (p %.3g v %.3g a %.3g)", k,
                          i, s, n.position - end.position, n.velocity - end.velocity,
                          n.acceleration - end.acceleration);
            return why;
          }
        }
      }
      if (std::abs(t - length) > 1e-9 * std::max(1.0, length)) {
        std::snprintf(why, sizeof why, "section %d joint %d ends at %.17g, not at %.17g", k, i, t,
                      length);
        return why;
      }
    }
    section_start = traj.section_end(k);
  }
  // The target, reached by every joint at duration(), and the waypoints at their sections' ends.
  const TrajectoryState last = traj.at(total);
  for (int i = 0; i < in.joints; ++i) {
    if (std::abs(last.position[i] - in.target_position[i]) > kFinalTolerance ||
        std::abs(last.velocity[i] - in.target_velocity[i]) > kFinalTolerance ||
        std::abs(last.acceleration[i]) > kFinalTolerance) {
      std::snprintf(
          why, sizeof why, "joint %d ends at p %.17g v %.17g a %.17g (error p %.3g v %.3g)", i,
          last.position[i], last.velocity[i], last.acceleration[i],
          last.position[i] - in.target_position[i], last.velocity[i] - in.target_velocity[i]);
      return why;
    }
  }
  for (std::size_t k = 0; k < in.waypoints.size(); ++k) {
    const TrajectoryState w = traj.at(traj.section_end(int(k)));
    for (int i = 0; i < in.joints; ++i)
      if (std::abs(w.position[i] - in.waypoints[k][i]) > kFinalTolerance) return "waypoint missed";
  }
  return {};
}

// Runs `count` random cases; fails with the first few bad cases described.
inline void run_random_cases(std::uint64_t seed, int count) {
  RandomCases cases(seed);
  Trajectory traj;
  int failures = 0;
  for (int c = 0; c < count; ++c) {
    const TrajectoryInput in = cases.next();
    const Status s = calculate_trajectory(in, traj);
    if (!s.ok()) {
      ADD_FAILURE() << "case " << c << " refused: " << s.error().message << "\n" << describe(in);
    } else {
      const std::string why = check_trajectory(in, traj);
      if (why.empty()) continue;
      ADD_FAILURE() << "case " << c << ": " << why << "\n" << describe(in);
    }
    if (++failures >= 5) return;
  }
}

}  // namespace armctl::motion::testing
