// The brute force for the time-optimality checks of the trajectory generator: a numeric
// optimum that knows nothing of its profile family (docs/trajectories.md "Optimality check").
//
// The brute force: a time-optimal jerk-limited profile is bang-bang in jerk with at most
// seven segments, jerk (s, 0, -s, 0, -s, 0, s) ("up-down-down-up") or (s, 0, -s, 0, s, 0,
// -s) ("up-down-up-down"), s = +-1, where a zero-jerk segment is a plateau at |a| = amax
// (segments 1 and 5) or a cruise at |v| = vmax with a = 0 (segment 3). For every sign,
// pattern and set of plateaus, the unknown durations and the conditions (final a, v, p;
// each plateau's level; for up-down-up-down without a cruise, a = 0 at the turn; for
// up-down-down-up without a cruise, the two -s segments are one, with no condition on
// where a crosses 0) form a square nonlinear system, solved by damped Newton from 30
// random starts; every solution with durations >= 0 that keeps |a| <= amax and
// |v| <= vmax is a feasible profile, and the shortest is the optimum.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "motion/trajectory.hpp"
#include "trajectory_random_cases.hpp"

namespace armctl::motion::testing {

struct Problem {  // normalized: amax = jerk = 1
  double vmax, v0, a0, d, vf;
};

constexpr std::size_t kMaxUnknowns = 7;
using Vec = std::array<double, kMaxUnknowns>;  // unknowns or residuals, the first n used

struct Structure {
  double s;        // sign of the first jerk
  bool down_down;  // up-down-down-up, else up-down-up-down
  bool plateau1, cruise, plateau5;
  double cruise_sign;
};

// Durations of the seven segments from the unknowns.
inline std::array<double, 7> durations(const Structure& st, const Vec& x) {
  std::array<double, 7> t{};
  std::size_t k = 0;
  t[0] = x[k++];
  if (st.plateau1) t[1] = x[k++];
  t[2] = x[k++];
  if (st.cruise) t[3] = x[k++];
  if (st.cruise || !st.down_down) t[4] = x[k++];
  if (st.plateau5) t[5] = x[k++];
  t[6] = x[k++];
  return t;
}

inline std::size_t unknowns(const Structure& st) {
  return 3 + st.plateau1 + st.cruise + (st.cruise || !st.down_down) + st.plateau5;
}

inline std::array<double, 7> jerks(const Structure& st) {
  const double s = st.s, third = st.down_down ? -s : s;
  return {s, 0, -s, 0, third, 0, -third};
}

// Residuals of the structure's conditions for durations t.
inline Vec residuals(const Problem& pr, const Structure& st, const std::array<double, 7>& t) {
  const auto jk = jerks(st);
  double p = 0, v = pr.v0, a = pr.a0;
  std::array<double, 7> a_after{}, v_after{};
  for (int k = 0; k < 7; ++k) {
    const double dt = t[k], j = jk[k];
    p += dt * (v + dt * (a / 2 + dt * j / 6));
    v += dt * (a + dt * j / 2);
    a += dt * j;
    a_after[k] = a, v_after[k] = v;
  }
  Vec r{a, v - pr.vf, p - pr.d};
  std::size_t n = 3;
  if (st.plateau1) r[n++] = a_after[0] - st.s;
  if (st.cruise) {
    r[n++] = a_after[2];
    r[n++] = v_after[2] - st.cruise_sign * pr.vmax;
  } else if (!st.down_down) {
    r[n++] = a_after[2];
  }
  if (st.plateau5) r[n++] = a_after[4] - jk[4];  // the level the jerk before it reached
  return r;
}

inline double norm(const Vec& r) {  // unused entries stay 0
  double n = 0;
  for (double x : r) n += x * x;
  return std::sqrt(n);
}

// Whether durations t (all >= 0) keep |a| <= 1 and |v| <= vmax, analytically per segment.
inline bool feasible(const Problem& pr, const Structure& st, const std::array<double, 7>& t) {
  const auto jk = jerks(st);
  double v = pr.v0, a = pr.a0;
  for (int k = 0; k < 7; ++k) {
    if (t[k] < 0) return false;
    const double dt = t[k], j = jk[k];
    const double v1 = v + dt * (a + dt * j / 2), a1 = a + dt * j;
    double vpeak = std::max(std::abs(v), std::abs(v1));
    if (j != 0 && -a / j > 0 && -a / j < dt) vpeak = std::max(vpeak, std::abs(v - a * a / (2 * j)));
    if (std::abs(a1) > 1 + 1e-9 || vpeak > pr.vmax * (1 + 1e-9)) return false;
    v = v1, a = a1;
  }
  return true;
}

constexpr int kStarts = 30;

// The shortest feasible profile over every structure, in normalized time.
inline double brute_force_min_time(const Problem& pr, std::mt19937_64& rng) {
  if (pr.d == 0 && pr.v0 == pr.vf && pr.a0 == 0) return 0;  // already there: no segment at all
  double best = INFINITY;
  const double scale = 1 + pr.vmax + std::abs(pr.d) / pr.vmax + std::abs(pr.v0) + std::abs(pr.vf);
  std::uniform_real_distribution<double> start(0, 1);
  // A solution must meet its conditions to 1e-12 of the magnitudes involved (positions run
  // to about vmax times the time scale): looser lets it end off the target and "win".
  const double tolerance = 1e-12 * (1 + pr.vmax) * scale;
  for (double s : {1.0, -1.0})
    for (bool dd : {true, false})
      for (int mask = 0; mask < 8; ++mask)
        for (double cs : {1.0, -1.0}) {
          Structure st{s, dd, bool(mask & 1), bool(mask & 2), bool(mask & 4), cs};
          if (!st.cruise && cs < 0) continue;
          const std::size_t n = unknowns(st);
          for (int attempt = 0; attempt < kStarts; ++attempt) {
            Vec x{};
            for (std::size_t c = 0; c < n; ++c) x[c] = scale * start(rng) * start(rng);
            auto r = residuals(pr, st, durations(st, x));
            for (int it = 0; it < 60 && norm(r) > 1e-3 * tolerance; ++it) {
              // Jacobian by central differences; Gaussian elimination with pivoting.
              std::array<std::array<double, kMaxUnknowns + 1>, kMaxUnknowns> jac{};
              for (std::size_t c = 0; c < n; ++c) {
                const double h = 1e-7 * std::max(1.0, std::abs(x[c]));
                auto xp = x, xm = x;
                xp[c] += h, xm[c] -= h;
                const auto rp = residuals(pr, st, durations(st, xp)),
                           rm = residuals(pr, st, durations(st, xm));
                for (std::size_t row = 0; row < n; ++row)
                  jac[row][c] = (rp[row] - rm[row]) / (2 * h);
              }
              for (std::size_t row = 0; row < n; ++row) jac[row][n] = -r[row];
              bool singular = false;
              for (std::size_t c = 0; c < n && !singular; ++c) {
                std::size_t piv = c;
                for (std::size_t row = c + 1; row < n; ++row)
                  if (std::abs(jac[row][c]) > std::abs(jac[piv][c])) piv = row;
                if (std::abs(jac[piv][c]) < 1e-14) singular = true;
                std::swap(jac[c], jac[piv]);
                for (std::size_t row = 0; row < n && !singular; ++row) {
                  if (row == c) continue;
                  const double f = jac[row][c] / jac[c][c];
                  for (std::size_t k = c; k <= n; ++k) jac[row][k] -= f * jac[c][k];
                }
              }
              if (singular) break;
              // Damped step: halve until the residual falls.
              double step = 1;
              bool better = false;
              for (int h = 0; h < 30 && !better; ++h, step /= 2) {
                auto xn = x;
                for (std::size_t c = 0; c < n; ++c) xn[c] += step * jac[c][n] / jac[c][c];
                auto rn = residuals(pr, st, durations(st, xn));
                if (norm(rn) < norm(r)) x = xn, r = rn, better = true;
              }
              if (!better) break;
            }
            if (norm(r) > tolerance) continue;
            auto t = durations(st, x);
            bool nonneg = true;
            for (double& ti : t) {  // durations of unused segments are 0
              if (ti < -1e-9) nonneg = false;
              ti = std::max(0.0, ti);
            }
            if (!nonneg || !feasible(pr, st, t)) continue;
            double total = 0;
            for (double ti : t) total += ti;
            best = std::min(best, total);
          }
        }
  return best;
}

// One joint's optimum in seconds, by the brute force.
inline double optimum(const TrajectoryInput& in, int i, std::mt19937_64& rng) {
  const double amax = in.max_acceleration[i], j = in.max_jerk[i];
  const double tu = amax / j, vu = amax * amax / j, pu = vu * tu;  // normalizing units
  const Problem pr{in.max_velocity[i] / vu, in.velocity[i] / vu, in.acceleration[i] / amax,
                   (in.target_position[i] - in.position[i]) / pu, in.target_velocity[i] / vu};
  return brute_force_min_time(pr, rng) * tu;
}

inline double ours(const TrajectoryInput& in) {
  Trajectory t;
  EXPECT_TRUE(calculate_trajectory(in, t).ok());
  return t.duration();
}

struct Tally {  // differences from the brute force beyond 1e-6 s fail the test
  int cases = 0, worse = 0, better = 0;
  double worst = 0;
  void add(double mine, double best, const TrajectoryInput& in) {
    ++cases;
    worst = std::max(worst, std::abs(mine - best));
    if (mine > best + 1e-6) {
      ++worse;
      if (worse <= 3)
        ADD_FAILURE() << "slower than the optimum: " << mine << " s vs " << best << " s\n"
                      << describe(in);
    }
    if (mine < best - 1e-6) {
      ++better;
      if (better <= 3)
        ADD_FAILURE() << "faster than the brute force found: " << mine << " s vs " << best << " s\n"
                      << describe(in);
    }
  }
};

// `count` random single joints: our minimum duration against the brute force's.
inline void check_one_joint_optimality(std::uint64_t seed, int count) {
  RandomCases cases(seed);
  std::mt19937_64 rng(seed + 1);
  Tally tally;
  for (int c = 0; c < count; ++c) {
    const TrajectoryInput in = cases.next(1);
    tally.add(ours(in), optimum(in, 0, rng), in);
  }
  std::printf("one joint: %d cases, largest difference %.3g s\n", tally.cases, tally.worst);
}

inline void check_two_joint_optimality(std::uint64_t seed, int count) {
  // Joint 0 anything, joint 1 rest to rest (it can take any duration above its minimum):
  // the pair takes the slower joint's optimum when that is joint 0's, at least it otherwise.
  RandomCases cases(seed);
  std::mt19937_64 rng(seed + 1);
  Tally tally;
  int lower_bound_only = 0;
  for (int c = 0; c < count; ++c) {
    TrajectoryInput in = cases.next(2);
    in.velocity[1] = in.acceleration[1] = in.target_velocity[1] = 0;
    const double best0 = optimum(in, 0, rng), best1 = optimum(in, 1, rng), mine = ours(in);
    if (best1 <= best0) {
      tally.add(mine, best0, in);
    } else {
      ++lower_bound_only;
      EXPECT_GE(mine, best1 - 1e-6) << describe(in);
    }
  }
  std::printf(
      "two joints: %d cases at the slower optimum, largest difference %.3g s; %d checked as a "
      "lower bound\n",
      tally.cases, tally.worst, lower_bound_only);
}


// ---------------------------------------------------------------------------------------
// Synchronized optimality: which durations a joint can take at all, independently of the
// generator's profile family (docs/trajectories.md "Optimality check").
//
// The jerk-limited motions of exactly T from a start state to (vf, 0) form a convex set
// (linear dynamics, convex limits), so the positions they reach form an interval
// [least(T), most(T)] and T is possible iff the target lies in it. The most ground in T is
// bang-bang jerk +, -, + (Pontryagin, with plateaus at the limits): it follows the most
// eager upward motion U (jerk +j, a plateau at amax, jerk -j to arrive at vmax with a = 0,
// a cruise there) until a switch time sigma, then the fastest change to (vf, 0). Its
// duration sigma + change(U(sigma)) does not decrease with sigma, so bisection on sigma
// finds the one of duration T. The least ground is the same mirrored. Nothing here shares
// code with the generator.

struct Limits1 {
  double v, a, j;
};

// The fastest change from (v, a) to (vf, 0), |a| <= amax: its duration and displacement.
inline void fastest_change(double v, double a, double vf, const Limits1& l, double& time,
                           double& distance) {
  const double stop = v + a * std::abs(a) / (2 * l.j);
  const double s = vf >= stop ? 1 : -1;
  const double u = s * v, b = s * a, w = s * vf;
  double peak = std::sqrt(std::max(0.0, l.j * (w - u) + b * b / 2)), hold = 0;
  if (peak > l.a) {
    peak = l.a;
    hold = std::max(0.0, (w - u - (2 * l.a * l.a - b * b) / (2 * l.j)) / l.a);
  }
  const double t[3] = {std::max(0.0, (peak - b) / l.j), hold, peak / l.j};
  const double jerk[3] = {l.j, 0, -l.j};
  double p = 0, vv = u, aa = b;
  for (int k = 0; k < 3; ++k) {
    if (k == 1) aa = peak;
    p += t[k] * (vv + t[k] * (aa / 2 + t[k] * jerk[k] / 6));
    vv += t[k] * (aa + t[k] * jerk[k] / 2);
    aa += t[k] * jerk[k];
  }
  time = t[0] + t[1] + t[2];
  distance = s * p;
}

// The state after sigma on the most eager upward motion from (v0, a0).
inline void eager_up(double v0, double a0, const Limits1& l, double sigma, double& p, double& v,
                     double& a) {
  // Jerk +j until a reaches min(amax, a_turn), a_turn being where jerking back at once
  // arrives exactly at vmax: v + a^2 / (2j) = vmax.
  const double a_turn = std::sqrt(std::max(0.0, l.j * (l.v - v0) + a0 * a0 / 2));
  const double a_top = std::min(l.a, a_turn);
  double t[4], jerk[4] = {l.j, 0, -l.j, 0};
  t[0] = std::max(0.0, (a_top - a0) / l.j);
  const double v1 = v0 + t[0] * (a0 + t[0] * l.j / 2);
  t[1] = a_top < a_turn ? std::max(0.0, (l.v - a_top * a_top / (2 * l.j) - v1) / a_top) : 0;
  t[2] = a_top / l.j;
  t[3] = INFINITY;
  p = 0, v = v0, a = a0;
  double left = sigma;
  for (int k = 0; k < 4 && left > 0; ++k) {
    const double dt = std::min(left, t[k]);
    if (k == 1) a = a_top;
    if (k == 3) v = l.v, a = 0;
    p += dt * (v + dt * (a / 2 + dt * jerk[k] / 6));
    v += dt * (a + dt * jerk[k] / 2);
    a += dt * jerk[k];
    left -= dt;
  }
}

// The most ground in exactly T from (v0, a0) to (vf, 0); false if T is too short for the
// velocity change alone.
inline bool most_ground(double v0, double a0, double vf, const Limits1& l, double T, double& most) {
  auto at = [&](double sigma, double& distance) {
    double p, v, a, time, d;
    eager_up(v0, a0, l, sigma, p, v, a);
    fastest_change(v, a, vf, l, time, d);
    distance = p + d;
    return sigma + time;
  };
  double d0;
  if (at(0, d0) > T * (1 + 1e-12) + 1e-15) return false;
  double lo = 0, hi = T;
  for (int i = 0; i < 200 && hi - lo > 1e-15 * std::max(1.0, T); ++i) {
    const double mid = 0.5 * (lo + hi);
    double d;
    (at(mid, d) <= T ? lo : hi) = mid;
  }
  at(lo, most);
  return true;
}

// Whether joint i can arrive in exactly T (any jerk-limited motion), to a relative
// `slack` of the ground it must cover.
inline bool joint_can_take(const TrajectoryInput& in, int i, double T, double slack) {
  const Limits1 l{in.max_velocity[i], in.max_acceleration[i], in.max_jerk[i]};
  const double v0 = in.velocity[i], a0 = in.acceleration[i], vf = in.target_velocity[i];
  const double d = in.target_position[i] - in.position[i];
  double most, least;
  if (!most_ground(v0, a0, vf, l, T, most) || !most_ground(-v0, -a0, -vf, l, T, least)) return false;
  least = -least;
  const double tolerance = slack * (std::abs(d) + l.v * T + l.v * l.a / l.j);
  return least - tolerance <= d && d <= most + tolerance;
}

// `count` random synchronized cases of 2..7 joints: the generator's trajectory passes every
// check of trajectory_random_cases.hpp (so its duration is possible), the independent test
// above agrees that every joint can take it, and no duration 1e-6 s shorter, nor any of
// `grid` evenly spaced shorter ones, is possible for every joint.
inline void check_synchronized_optimality(std::uint64_t seed, int count, int grid) {
  RandomCases cases(seed);
  std::mt19937_64 pick(seed + 1);
  Trajectory traj;
  int failures = 0, bad = 0, disagree = 0, shorter_possible = 0, blended = 0;
  long joint_checks = 0;
  for (int c = 0; c < count && failures < 5; ++c) {
    const TrajectoryInput in = cases.next(std::uniform_int_distribution<int>(2, 7)(pick));
    if (!calculate_trajectory(in, traj).ok()) {
      ++failures, ADD_FAILURE() << "refused\n" << describe(in);
      continue;
    }
    const double T = traj.duration();
    if (const std::string why = check_trajectory(in, traj); !why.empty()) {
      ++bad, ++failures;
      ADD_FAILURE() << why << "\n" << describe(in);
      continue;
    }
    // A blend of two extremal motions (jerk_profile.hpp) is the only profile with more
    // than seven segments.
    bool blend = false;
    for (int i = 0; i < in.joints; ++i) blend = blend || traj.segments(0, i)[kFamilySegments].duration > 0;
    blended += blend;
    for (int i = 0; i < in.joints; ++i)
      if (++joint_checks, !joint_can_take(in, i, T, 1e-9)) {
        ++disagree, ++failures;
        ADD_FAILURE() << "the independent test says joint " << i << " cannot take " << T << " s\n"
                      << describe(in);
        break;
      }
    // Shorter durations: some joint must be unable to take each. The joint that refused the
    // last one is asked first (usually the same joint refuses them all).
    int first = 0;
    for (int g = 0; g <= grid; ++g) {
      const double t = g == 0 ? T - 1e-6 : (T - 1e-6) * g / (grid + 1);
      if (t <= 0) continue;
      bool all = true;
      for (int k = 0; k < in.joints && all; ++k) {
        const int i = (first + k) % in.joints;
        ++joint_checks;
        if (!joint_can_take(in, i, t, -1e-12)) all = false, first = i;
      }
      if (all) {
        ++shorter_possible, ++failures;
        ADD_FAILURE() << "every joint can take " << t << " s, shorter than " << T << " s\n"
                      << describe(in);
        break;
      }
    }
  }
  std::printf(
      "synchronized: %d cases of 2..7 joints (%d with a blended profile), %d failing the "
      "checks, %d where a joint could not take the duration, %d with a shorter duration "
      "possible (%ld joint tests)\n",
      count, blended, bad, disagree, shorter_possible, joint_checks);
}

}  // namespace armctl::motion::testing
