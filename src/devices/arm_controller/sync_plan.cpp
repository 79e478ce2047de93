#include "devices/arm_controller/sync_plan.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace armctl::arm_controller {

namespace {

Duration seconds(double s) { return Duration{static_cast<std::int64_t>(std::llround(s * 1e9))}; }
double to_seconds(Duration d) { return std::chrono::duration<double>(d).count(); }

}  // namespace

JointProfile as_quantized_by_joint(JointProfile p) {
  // top speed: Q8 clicks per tick = (cps * 32 + 62) / 125; acceleration: Q8 clicks per
  // tick^2 = (cps2 * 32 + 62500) / 125000, at least 1.
  const double top_q8 = std::floor((p.max_speed_cps * 32 + 62) / 125);
  const double accel_q8 = std::max(1.0, std::floor((p.max_accel_cps2 * 32 + 62500) / 125000));
  return JointProfile{top_q8 * 1000.0 / 256.0, accel_q8 * 1e6 / 256.0};
}

double move_seconds(double distance, int percent, const JointProfile& profile) {
  if (distance <= 0) return 0;
  const double v = profile.max_speed_cps * std::clamp(percent, 1, 100) / 100.0;
  const double a = profile.max_accel_cps2;
  if (distance <= v * v / a) return 2.0 * std::sqrt(distance / a);  // never reaches v
  return distance / v + v / a;
}

SyncPlan plan_synchronized_move(std::span<const PlanInput> inputs, Duration wanted, Duration setup,
                                Duration transaction) {
  const std::size_t n = inputs.size();
  SyncPlan plan;
  plan.joints.resize(n);
  if (n == 0) {
    plan.total = wanted;
    return plan;
  }
  std::vector<double> fastest(n);
  for (std::size_t i = 0; i < n; ++i) fastest[i] = move_seconds(inputs[i].distance, 100, inputs[i].profile);

  // The joint that needs longest gets the first bus slot.
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](auto a, auto b) { return fastest[a] > fastest[b]; });

  const double t_setup = to_seconds(setup);
  const double t_txn = to_seconds(transaction);
  double total = to_seconds(wanted);
  for (std::size_t slot = 0; slot < n; ++slot)
    total = std::max(total, t_setup + double(slot) * t_txn + fastest[order[slot]]);

  std::vector<double> placed;  // start instants already taken
  for (std::size_t slot = 0; slot < n; ++slot) {
    const std::size_t i = order[slot];
    const PlanInput& in = inputs[i];
    const double earliest = t_setup + double(slot) * t_txn;
    const double available = total - earliest;
    // Slowest percentage that fits (gentlest on the mechanics), but fast enough to cross
    // the zone in kZoneCrossing.
    const int floor_percent = std::clamp(
        int(std::ceil(100.0 * in.zone / (to_seconds(kZoneCrossing) * in.profile.max_speed_cps))), 1, 100);
    int lowest = 100;
    for (int p = floor_percent; p <= 100; ++p) {
      if (move_seconds(in.distance, p, in.profile) <= available + 1e-9) {
        lowest = p;
        break;
      }
    }
    int chosen = lowest;
    // Prefer a percentage whose start does not collide with another joint's drive_to.
    for (int p = lowest; p <= 100; ++p) {
      const double start = total - move_seconds(in.distance, p, in.profile);
      bool clear = std::all_of(placed.begin(), placed.end(),
                               [&](double s) { return std::abs(s - start) >= t_txn; });
      if (clear) {
        chosen = p;
        break;
      }
    }
    const double duration = move_seconds(in.distance, chosen, in.profile);
    const double start = std::max(earliest, total - duration);
    placed.push_back(start);
    plan.joints[i] = PlannedJoint{in.joint, chosen, seconds(start), seconds(duration)};
  }
  plan.total = seconds(total);
  return plan;
}

}  // namespace armctl::arm_controller
