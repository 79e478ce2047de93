#include "motion/jerk_profile.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace armctl::motion {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kEps = std::numeric_limits<double>::epsilon();

// Interior samples between two neighbouring breakpoints of the family's shape. The
// family's functions are smooth between breakpoints but not monotone; these catch the
// roots of "no cruise needed" that lie between breakpoints and tighten the durations known
// possible (docs/trajectories.md "Blocked intervals").
constexpr int kSamplesBetween = 1;

// A root of f between x0 and x1, where f0 and f1 have opposite signs: regula falsi with the
// Illinois modification, bisecting whenever the bracket fails to halve, to the last bits
// of x or until |f| <= f_tolerance (f's own rounding).
template <typename F>
double bracketed_root(F f, double x0, double f0, double x1, double f1, double f_tolerance) {
  double width = std::abs(x1 - x0);
  int side = 0;
  for (int i = 0; i < 200; ++i) {
    const double scale = std::max(std::abs(x0), std::abs(x1));
    if (std::abs(x1 - x0) <= 2 * kEps * scale || std::abs(x1 - x0) < 1e-300) break;
    double x = (x0 * f1 - x1 * f0) / (f1 - f0);
    const bool slow = (i % 3 == 2) && std::abs(x1 - x0) > 0.5 * width;
    if (slow) width = std::abs(x1 - x0);
    if (slow || !(x > std::min(x0, x1) && x < std::max(x0, x1))) x = 0.5 * (x0 + x1);
    const double fx = f(x);
    if (std::abs(fx) <= f_tolerance) return x;
    if ((fx > 0) == (f1 > 0)) {
      x1 = x, f1 = fx;
      if (side == -1) f0 /= 2;
      side = -1;
    } else {
      x0 = x, f0 = fx;
      if (side == 1) f1 /= 2;
      side = 1;
    }
  }
  return std::abs(f0) < std::abs(f1) ? x0 : x1;
}

int sign(double x) {
  return (x > 0) - (x < 0);
}

}  // namespace

double JerkPlan::rounding() const {
  // A distance this small is below what the displacements' arithmetic resolves.
  const double scale = std::abs(task_.target_position - task_.position) + std::abs(task_.position) +
                       limits_.velocity * (limits_.velocity / limits_.acceleration +
                                           limits_.acceleration / limits_.jerk);
  return 4 * kEps * scale;
}

JerkPlan::Point JerkPlan::evaluate(double vp) const {
  const VelocityChange first =
      velocity_change(task_.velocity, task_.acceleration, vp, limits_, inv_jerk_, inv_acceleration_);
  // The last change starts and ends at a = 0: symmetric, its mean velocity is the midpoint.
  const double dv = std::abs(task_.target_velocity - vp), amax = limits_.acceleration,
               j = limits_.jerk;
  const double last =
      dv * j > amax * amax ? dv * inv_acceleration_ + amax * inv_jerk_ : 2 * std::sqrt(dv * inv_jerk_);
  Point p;
  p.vp = vp;
  p.ramps = first.duration + last;
  p.remaining = (task_.target_position - task_.position) - first.displacement -
                (vp + task_.target_velocity) / 2 * last;
  if (vp != 0)
    p.duration = p.ramps + p.remaining / vp;
  else
    p.duration = p.remaining == 0 ? p.ramps : kInf;
  return p;
}

double JerkPlan::root_of_remaining(const Point& x, const Point& y) const {
  return bracketed_root([this](double vp) { return evaluate(vp).remaining; }, x.vp, x.remaining,
                        y.vp, y.remaining, rounding());
}

double JerkPlan::vp_for_duration(const Point& x, const Point& y, double duration) const {
  if (duration == x.duration) return x.vp;
  if (duration == y.duration) return y.vp;
  // vp (T - ramps) - remaining: vp times the duration missing, finite at vp = 0.
  auto f = [&](const Point& p) { return p.vp * (duration - p.ramps) - p.remaining; };
  const double fx = f(x), fy = f(y);
  if (fx == 0) return x.vp;
  if (fy == 0) return y.vp;
  if (sign(fx) == sign(fy)) return std::abs(fx) < std::abs(fy) ? x.vp : y.vp;  // rounding at an end
  return bracketed_root([&](double vp) { return f(evaluate(vp)); }, x.vp, fx, y.vp, fy, rounding());
}

int JerkPlan::add_hidden_crossings(Point* samples, int m) const {
  // `remaining` may cross 0 and come back between two samples (a bump the samples miss):
  // where |remaining| has a local minimum at a sample and the parabola through it and its
  // neighbours comes at least halfway to 0, look once at the parabola's vertex; a value of
  // the other sign there becomes a sample, so that its two roots get bracketed. (A bump
  // still missed costs at most optimality: a duration claimed wrongly is caught in build.)
  Point found[kMaxSamples];
  int f = 0;
  for (int i = 1; i + 1 < m && f < kMaxSamples - m; ++i) {
    const double r = samples[i].remaining;
    const double left = samples[i - 1].remaining, right = samples[i + 1].remaining;
    if (r == 0 || sign(left) != sign(r) || sign(right) != sign(r)) continue;
    if (std::abs(left) < std::abs(r) || std::abs(right) < std::abs(r)) continue;
    // y = b x + c x^2 through the neighbours (x from sample i, y from r); vertex at
    // -b / (2c), value r - b^2 / (4c).
    const double x0 = samples[i - 1].vp - samples[i].vp, x2 = samples[i + 1].vp - samples[i].vp;
    const double y0 = left - r, y2 = right - r;
    const double det = x0 * x2 * (x2 - x0);
    const double c = (y2 * x0 - y0 * x2) / det, b = (y0 * x2 * x2 - y2 * x0 * x0) / det;
    if (c == 0) continue;
    const double low = r - b * b / (4 * c);
    if (sign(low) == sign(r) && std::abs(low) > 0.5 * std::abs(r)) continue;
    const double vertex = samples[i].vp - b / (2 * c);
    if (vertex > samples[i - 1].vp && vertex < samples[i + 1].vp) {
      const Point p = evaluate(vertex);
      if (sign(p.remaining) == -sign(r)) found[f++] = p;
    }
  }
  // Merge the finds in (both lists sorted by vp).
  for (int k = 0; k < f; ++k) {
    int at = m++;
    while (at > 0 && samples[at - 1].vp > found[k].vp) samples[at] = samples[at - 1], --at;
    samples[at] = found[k];
  }
  return m;
}

void JerkPlan::plan(const JerkTask& task, const JerkLimits& limits) {
  task_ = task;
  limits_ = limits;
  inv_jerk_ = 1 / limits.jerk;
  inv_acceleration_ = 1 / limits.acceleration;
  point_count_ = 0;
  interval_count_ = 0;
  const double vmax = limits.velocity, amax = limits.acceleration, j = limits.jerk;
  const double v0 = task.velocity, a0 = task.acceleration, vf = task.target_velocity;

  // At rest on the target: stays there for any duration.
  if (task.target_position == task.position && v0 == 0 && a0 == 0 && vf == 0) {
    samples_[0] = points_[0] = Point{0, 0, 0, 0};
    sample_count_ = point_count_ = 1;
    release_count_ = 0;
    intervals_[0] = Interval{0, kInf, 0, -1};
    interval_count_ = 1;
    min_duration_ = 0;
    return;
  }

  // Breakpoints of the family's shape in vp: 0 (the cruise's direction), where either
  // change vanishes and turns round (v_stop, vf: the durations have a square-root kink
  // there, and short profiles sit close to it) and where either change starts to need a
  // plateau at amax.
  double breaks[10];
  int n = 0;
  const double v_stop = v0 + a0 * std::abs(a0) / (2 * j);
  const double reach_first = (amax * amax - a0 * a0 / 2) / j;
  const double reach_last = amax * amax / j;
  const double candidates[] = {0,  v_stop,          v0 + reach_first, v0 - reach_first,
                               vf, vf + reach_last, vf - reach_last};
  breaks[n++] = -vmax;
  for (double c : candidates)
    if (c > -vmax && c < vmax) breaks[n++] = c;
  breaks[n++] = vmax;
  for (int i = 1; i < n; ++i)  // insertion sort: a handful of values
    for (int k = i; k > 0 && breaks[k] < breaks[k - 1]; --k) std::swap(breaks[k], breaks[k - 1]);

  Point* samples = samples_;
  int m = 0;
  for (int i = 0; i < n; ++i) {
    if (i > 0 && breaks[i] == breaks[i - 1]) continue;
    if (i > 0) {
      const double lo = breaks[i - 1], hi = breaks[i];
      for (int k = 1; k <= kSamplesBetween; ++k)
        samples[m++] = evaluate(lo + (hi - lo) * k / (kSamplesBetween + 1));
    }
    samples[m++] = evaluate(breaks[i]);
  }
  sample_count_ = add_hidden_crossings(samples, m);
  plan_releases();
  derive();
}

bool JerkPlan::refine(double vp) {
  if (sample_count_ >= kMaxSamples) return false;
  int at = sample_count_++;
  while (at > 0 && samples_[at - 1].vp > vp) samples_[at] = samples_[at - 1], --at;
  samples_[at] = evaluate(vp);
  derive();
  return true;
}

void JerkPlan::derive() {
  const Point* samples = samples_;
  const int m = sample_count_;
  point_count_ = 0;
  interval_count_ = 0;

  // Points: the samples with the roots of `remaining` (profiles with no cruise) between.
  for (int i = 0; i < m; ++i) {
    if (i > 0 && sign(samples[i - 1].remaining) * sign(samples[i].remaining) < 0) {
      Point r = evaluate(root_of_remaining(samples[i - 1], samples[i]));
      r.remaining = 0;  // the cruise is dropped: what is left is rounding
      r.duration = r.ramps;
      points_[point_count_++] = r;
    }
    points_[point_count_++] = samples[i];
  }

  // Durations possible: on each stretch between neighbouring points where the cruise runs
  // forward (vp and remaining of one sign), the duration is continuous, so every value
  // between its ends' durations is taken. A root flanked by impossible stretches on both
  // sides is a single possible duration.
  auto add = [this](double lo, double hi, int a, int b) {
    intervals_[interval_count_++] = Interval{lo, hi, a, b};
  };
  for (int i = 0; i + 1 < point_count_; ++i) {
    const Point &x = points_[i], &y = points_[i + 1];
    const int side = sign(x.vp + y.vp);
    int rem = x.remaining != 0 ? sign(x.remaining) : sign(y.remaining);
    if (x.vp == 0 || y.vp == 0) {
      const Point& at_zero = x.vp == 0 ? x : y;
      if (at_zero.remaining == 0) continue;  // the limit at vp -> 0 is not at_zero's duration
      rem = sign(at_zero.remaining);
    } else if (rem == 0) {
      rem = sign(evaluate(0.5 * (x.vp + y.vp)).remaining);
    }
    if (side * rem > 0)
      add(std::min(x.duration, y.duration), std::max(x.duration, y.duration), i, i + 1);
    else if (x.remaining == 0 && x.vp != 0)
      add(x.duration, x.duration, i, i);
  }
  const Point& last = points_[point_count_ - 1];
  if (last.remaining == 0) add(last.duration, last.duration, point_count_ - 1, point_count_ - 1);
  // Exactly at rest after the first change and before the last: any cruise at vp = 0.
  for (int i = 0; i < point_count_; ++i)
    if (points_[i].vp == 0 && points_[i].remaining == 0)
      add(points_[i].ramps, kInf, i, kCruiseAtRest);
  for (int i = 0; i < release_count_; ++i)
    add(releases_[i].duration, releases_[i].duration, i, kRelease);

  min_duration_ = kInf;
  for (int i = 0; i < interval_count_; ++i)
    min_duration_ = std::min(min_duration_, intervals_[i].lo);
}

JerkPlan::Release JerkPlan::release(double tau, double& remaining) const {
  const double a0 = task_.acceleration, j = a0 > 0 ? -limits_.jerk : limits_.jerk;
  const JerkSegment start{0, tau, 0, task_.velocity, a0, j};
  const JerkState s = advance(start, tau);
  const VelocityChange c =
      velocity_change(s.velocity, s.acceleration, task_.target_velocity, limits_, inv_jerk_, inv_acceleration_);
  remaining = (task_.target_position - task_.position) - s.position - c.displacement;
  return Release{tau, tau + c.duration};
}

void JerkPlan::plan_releases() {
  release_count_ = 0;
  if (task_.acceleration == 0) return;
  // The ends are members of the vp family (tau = 0: vp = vf; tau = |a0| / j: vp = v_stop);
  // the roots between are profiles it lacks.
  const double full = std::abs(task_.acceleration) / limits_.jerk;
  double prev_tau = 0, prev_rem = 0;
  release(0, prev_rem);
  for (int k = 1; k <= kReleaseSamples; ++k) {
    const double tau = full * k / kReleaseSamples;
    double rem = 0;
    release(tau, rem);
    if (sign(prev_rem) * sign(rem) < 0 || (rem == 0 && k < kReleaseSamples)) {
      const double root = rem == 0 ? tau
                                   : bracketed_root(
                                         [this](double t) {
                                           double r = 0;
                                           release(t, r);
                                           return r;
                                         },
                                         prev_tau, prev_rem, tau, rem, rounding());
      double ignored = 0;
      releases_[release_count_++] = release(root, ignored);
    }
    prev_tau = tau, prev_rem = rem;
  }
}

double JerkPlan::next_possible(double t) const {
  double next = kInf;
  for (int i = 0; i < interval_count_; ++i) {
    const Interval& in = intervals_[i];
    if (in.lo <= t && t <= in.hi) return t;
    if (in.lo > t) next = std::min(next, in.lo);
  }
  // Not in the family: possible all the same when the target lies between the extremal
  // displacements. Otherwise t is in a blocked interval, whose end is the duration of an
  // extremal motion that lands on the target, a family member: `next`.
  if (t > min_duration_ && between_extremals(t)) return t;
  return next;
}

bool JerkPlan::extremal(double duration, double direction, Extremal& out) const {
  // Worked for the most ground; the least is the same mirrored (v, a, jerk negated).
  const double s = direction, T = duration, vmax = limits_.velocity;
  const double v0 = s * task_.velocity, a0 = s * task_.acceleration, vf = s * task_.target_velocity;
  auto change = [this](double v, double a, double to) {
    return velocity_change(v, a, to, limits_, inv_jerk_, inv_acceleration_);
  };
  auto ramps = [&](double vp) { return change(v0, a0, vp).duration + change(vp, 0, vf).duration; };
  out.count = 0;
  auto push = [&](double d, double j) {
    out.durations[out.count] = d, out.jerks[out.count] = s * j, ++out.count;
  };
  // Pontryagin: the most ground in a fixed time is jerk +, -, + with the limits' plateaus
  // between. Where the acceleration passes 0 the velocity peaks at vp >= max(v_stop, vf):
  // the fastest change to vp, a cruise only at vmax, the fastest change down to vf; the
  // duration grows with vp. Below that (only when braking toward vf < v_stop) the
  // acceleration never reaches 0: a release for tau, then the fastest change to vf, the
  // duration growing with tau (its derivative is 2 + 2 a / a_peak >= 0).
  auto peak = [&](double vp, double cruise) {
    const VelocityChange f = change(v0, a0, vp), l = change(vp, 0, vf);
    push(f.ramp_up, f.jerk), push(f.hold, 0), push(f.ramp_down, -f.jerk), push(cruise, 0);
    push(l.ramp_up, l.jerk), push(l.hold, 0), push(l.ramp_down, -l.jerk);
    out.displacement = s * (f.displacement + l.displacement + vp * cruise);
  };
  const double top = ramps(vmax);
  if (T >= top) {
    peak(vmax, T - top);
    return true;
  }
  const double v_stop = v0 + a0 * std::abs(a0) * 0.5 * inv_jerk_, low = std::max(v_stop, vf);
  const double at_low = ramps(low);
  if (T >= at_low) {
    const double vp = bracketed_root([&](double v) { return ramps(v) - T; }, low, at_low - T, vmax,
                                     top - T, 0);
    peak(vp, 0);
    return true;
  }
  if (a0 >= 0) return false;
  auto release_of = [&](double tau) {
    const JerkState st = advance(JerkSegment{0, tau, 0, v0, a0, limits_.jerk}, tau);
    return change(st.velocity, st.acceleration, vf);
  };
  const double at_zero = release_of(0).duration;
  if (T < at_zero) return false;
  const double full = -a0 * inv_jerk_;
  const double tau = bracketed_root([&](double x) { return x + release_of(x).duration - T; }, 0,
                                    at_zero - T, full, at_low - T, 0);
  const JerkState st = advance(JerkSegment{0, tau, 0, v0, a0, limits_.jerk}, tau);
  const VelocityChange c = change(st.velocity, st.acceleration, vf);
  push(tau, limits_.jerk), push(c.ramp_up, c.jerk), push(c.hold, 0), push(c.ramp_down, -c.jerk);
  out.displacement = s * (st.position + c.displacement);
  return true;
}

bool JerkPlan::between_extremals(double duration) const {
  Extremal most, least;
  if (!extremal(duration, 1, most) || !extremal(duration, -1, least)) return false;
  const double d = task_.target_position - task_.position, r = rounding();
  return least.displacement - r <= d && d <= most.displacement + r;
}

void JerkPlan::fill(const double* durations, const double* jerks, int count,
                    JerkSegments& out) const {
  JerkSegment s;
  s.position = task_.position;
  s.velocity = task_.velocity;
  s.acceleration = task_.acceleration;
  double start = 0;
  for (int k = 0; k < kProfileSegments; ++k) {
    s.start = start;
    s.duration = k < count ? durations[k] : 0;
    s.jerk = k < count ? jerks[k] : 0;
    out[k] = s;
    const JerkState next = advance(s, s.duration);
    s.position = next.position, s.velocity = next.velocity, s.acceleration = next.acceleration;
    start += s.duration;
  }
}

bool JerkPlan::build_blend(double duration, JerkSegments& out) const {
  // Any mix (1 - w) least + w most of two motions of duration T is one (jerk, a, v within
  // the limits: they are convex constraints), ending at (vf, 0) and at the mix of their
  // displacements: w puts it on the target. Its pieces are the union of both motions'.
  Extremal most, least;
  if (!extremal(duration, 1, most) || !extremal(duration, -1, least)) return false;
  const double d = task_.target_position - task_.position;
  const double span = most.displacement - least.displacement;
  const double w = span > 0 ? std::clamp((d - least.displacement) / span, 0.0, 1.0) : 0.5;
  // Each motion's switching times, the last forced to T (the roots leave it a few ulps off).
  double ends[2][kFamilySegments];
  const Extremal* both[2] = {&least, &most};
  for (int m = 0; m < 2; ++m) {
    double t = 0;
    for (int k = 0; k < both[m]->count; ++k) ends[m][k] = t += both[m]->durations[k];
    ends[m][both[m]->count - 1] = duration;
  }
  double durations[kProfileSegments], jerks[kProfileSegments];
  int n = 0, i = 0, k = 0;
  double t = 0;
  while (n < kProfileSegments && t < duration) {
    // Skip pieces of 0 s; the next switch of either motion ends this piece.
    while (i < least.count - 1 && ends[0][i] <= t) ++i;
    while (k < most.count - 1 && ends[1][k] <= t) ++k;
    const double end = std::min({ends[0][i], ends[1][k], duration});
    durations[n] = end - t;
    jerks[n] = (1 - w) * least.jerks[i] + w * most.jerks[k];
    ++n;
    t = end;
  }
  fill(durations, jerks, n, out);
  return true;
}

bool JerkPlan::build(double duration, JerkSegments& out) {
  const Interval* chosen = nullptr;
  for (int i = 0; i < interval_count_ && !chosen; ++i)
    if (intervals_[i].lo <= duration && duration <= intervals_[i].hi) chosen = &intervals_[i];
  // Outside the family: the blend (next_possible said the duration lies between the
  // extremal displacements, so it succeeds; were it not to, a cruise at rest as before).
  if (!chosen && build_blend(duration, out)) return true;
  double vp = 0;
  double durations[kFamilySegments], jerks[kFamilySegments];
  if (chosen && chosen->b == kRelease) {
    // The release as the first segment, then the change to vf in the last three.
    const double tau = releases_[chosen->a].tau, a0 = task_.acceleration;
    const double j = a0 > 0 ? -limits_.jerk : limits_.jerk;
    const JerkState s = advance(JerkSegment{0, tau, 0, task_.velocity, a0, j}, tau);
    const VelocityChange last =
        velocity_change(s.velocity, s.acceleration, task_.target_velocity, limits_, inv_jerk_, inv_acceleration_);
    const double d[] = {tau, 0, 0, 0, last.ramp_up, last.hold, last.ramp_down};
    const double jk[] = {j, 0, 0, 0, last.jerk, 0, -last.jerk};
    std::copy(d, d + kFamilySegments, durations);
    std::copy(jk, jk + kFamilySegments, jerks);
    vp = s.velocity;
  } else {
    if (chosen && chosen->b >= 0)
      vp = vp_for_duration(points_[chosen->a], points_[chosen->b], duration);
    else if (chosen)
      vp = points_[chosen->a].vp;
    const VelocityChange first = velocity_change(task_.velocity, task_.acceleration, vp, limits_, inv_jerk_, inv_acceleration_);
    const VelocityChange last = velocity_change(vp, 0, task_.target_velocity, limits_, inv_jerk_, inv_acceleration_);
    const double cruise = std::max(0.0, duration - first.duration - last.duration);
    // The samples missed a stretch where no cruise fits (remaining of the wrong sign):
    // vp lies in it; sampled there, the next plan knows.
    if (duration - first.duration - last.duration < -1e-12 * std::max(1.0, duration) && refine(vp))
      return false;
    const double d[] = {first.ramp_up, first.hold, first.ramp_down, cruise,
                        last.ramp_up,  last.hold,  last.ramp_down};
    const double jk[] = {first.jerk, 0, -first.jerk, 0, last.jerk, 0, -last.jerk};
    std::copy(d, d + kFamilySegments, durations);
    std::copy(jk, jk + kFamilySegments, jerks);
  }
  const bool released = chosen && chosen->b == kRelease;
  JerkSegment s;
  s.position = task_.position;
  s.velocity = task_.velocity;
  s.acceleration = task_.acceleration;
  double start = 0;
  for (int k = 0; k < kFamilySegments; ++k) {
    s.start = start;
    s.duration = durations[k];
    s.jerk = jerks[k];
    // Plateaus and the cruise hold what the ramp before them reached exactly.
    if ((k == 1 || k == 5) && durations[k] > 0)
      s.acceleration = sign(jerks[k - 1]) * limits_.acceleration;
    if (k == 3 && !released) s.velocity = vp, s.acceleration = 0;
    if (k == 4 && !released) s.acceleration = 0;
    out[k] = s;
    const JerkState next = advance(s, s.duration);
    s.position = next.position;
    s.velocity = next.velocity;
    s.acceleration = next.acceleration;
    start += s.duration;
  }
  // The unused segments: 0 s at the end state.
  s.start = start, s.duration = 0, s.jerk = 0;
  for (int k = kFamilySegments; k < kProfileSegments; ++k) out[k] = s;
  return true;
}

}  // namespace armctl::motion
