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

}  // namespace armctl::motion::testing
