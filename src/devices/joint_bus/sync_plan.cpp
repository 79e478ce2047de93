#include "devices/joint_bus/sync_plan.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "portable/fixed_point.hpp"

namespace armctl::joint_bus {

namespace {

Duration seconds(double s) { return Duration{static_cast<std::int64_t>(std::llround(s * 1e9))}; }
double to_seconds(Duration d) { return std::chrono::duration<double>(d).count(); }

}  // namespace

JointProfile as_quantized_by_joint(JointProfile p) {
  // Converted as the joint converts them (portable/fixed_point.hpp), the acceleration at
  // least 1 as its ramp takes it (portable/setpoint_ramp.cpp).
  const double top_q8 = speed_q8_per_tick(static_cast<std::uint32_t>(p.max_speed_cps));
  const double accel_q8 = std::max(1u, accel_q8_per_tick2(static_cast<std::uint32_t>(p.max_accel_cps2)));
  return JointProfile{top_q8 * 1000.0 / 256.0, accel_q8 * 1e6 / 256.0};
}

double move_seconds(double distance, int percent, const JointProfile& profile) {
  if (distance <= 0) return 0;
  const double v = profile.max_speed_cps * std::clamp(percent, 1, 100) / 100.0;
  const double a = profile.max_accel_cps2;
  if (distance <= v * v / a) return 2.0 * std::sqrt(distance / a);  // never reaches v
  return distance / v + v / a;
}

std::optional<Duration> moving_arrival(const MovingStart& start, std::int32_t target_q8, Duration drive,
                                       Duration speed, int percent, std::optional<int> switch_percent,
                                       Duration switch_at, Duration give_up) {
  constexpr Duration kTick = std::chrono::milliseconds(1);
  joint_bus::SetpointRamp ramp = start.ramp;
  std::int32_t target = start.old_target_q8;
  bool driven = false, sped = false, switched = !switch_percent;
  // A command taking effect at c is seen by the ticks after c (as in the joint: the tick
  // at c itself has already run when the command's DATA word arrives).
  for (Duration t = start.at + kTick; t <= give_up + kTick; t += kTick) {
    if (!driven && drive < t) target = target_q8, driven = true;
    if (!sped && speed < t) ramp.set_speed_percent(static_cast<std::uint8_t>(percent)), sped = true;
    if (!switched && switch_at < t)
      ramp.set_speed_percent(static_cast<std::uint8_t>(*switch_percent)), switched = true;
    ramp.step(target);
    if (driven && sped && ramp.velocity_q8() == 0 && ramp.setpoint_q8() == target_q8) return t;
  }
  return std::nullopt;
}

namespace {

// The smallest percentage at or above `floor_percent` whose arrival is at or before `total`
// (100 if none); `arrival` is the arrival for a percentage, nothing if later than `total`.
template <typename Arrival>
int slowest_in_time(int floor_percent, Arrival arrival) {
  if (arrival(floor_percent)) return floor_percent;
  int late = floor_percent, ok = 100;  // arrival(late) too late; ok assumed in time
  while (ok - late > 1) {
    const int mid = (late + ok) / 2;
    (arrival(mid) ? ok : late) = mid;
  }
  return ok;
}

int zone_floor_percent(const PlanInput& in) {
  return std::clamp(int(std::ceil(100.0 * in.zone / (to_seconds(kZoneCrossing) * in.profile.max_speed_cps))), 1,
                    100);
}

// Early by less than this, a moving joint does without the extra set_speed (bus time is
// scarce while a host streams moves; a few ms is far inside the stated tolerance).
constexpr Duration kSwitchWorthwhile = std::chrono::milliseconds(3);
// A joint whose fastest arrival is this close to the move's end sets its pace.
constexpr Duration kPaceSetter = std::chrono::milliseconds(5);

// A moving joint: drive_to at `drive`, set_speed one transaction later; the slowest whole
// percentage that arrives by `total`, then a switch one percent slower part-way so that it
// arrives at `total` to the tick.
PlannedJoint plan_moving_joint(const PlanInput& in, Duration drive, Duration speed, Duration total) {
  const MovingStart& m = *in.moving;
  auto in_time = [&](int p) { return moving_arrival(m, in.target_q8, drive, speed, p, std::nullopt, {}, total); };
  // No zone floor here: it keeps a joint starting from rest from creeping into its zone,
  // but a joint already moving slowly would be made to rush ahead and wait (stop-and-go).
  const Duration far = total + std::chrono::seconds(120);
  // The joint that sets the pace of a move longer than asked runs flat out: its arrival
  // hardly depends on the speed limit (it is limited by acceleration), and a lower one
  // would keep a joint that has fallen behind a streamed target from ever catching up.
  const bool pace_setter =
      moving_arrival(m, in.target_q8, drive, speed, 100, std::nullopt, {}, far).value_or(far) + kPaceSetter > total;
  const int p = pace_setter ? 100 : slowest_in_time(1, in_time);
  PlannedJoint out{in.joint, p, drive, {}, true, speed, std::nullopt, {}};
  const Duration arrival = moving_arrival(m, in.target_q8, drive, speed, p, std::nullopt, {}, far).value_or(far);
  if (!pace_setter && p > 1 && arrival + kSwitchWorthwhile < total) {
    // Switching to p-1 at `speed` arrives late, switching at `arrival` arrives as p: the
    // later the switch, the earlier the arrival. Find the earliest switch still in time.
    std::int64_t lo = 0, hi = (arrival - speed) / std::chrono::milliseconds(1) + 1;  // ms after `speed`
    auto with_switch = [&](std::int64_t k) {
      return moving_arrival(m, in.target_q8, drive, speed, p, p - 1, speed + std::chrono::milliseconds(k), far)
          .value_or(far);
    };
    if (with_switch(lo) > total) {
      while (hi - lo > 1) {
        const std::int64_t mid = (lo + hi) / 2;
        (with_switch(mid) > total ? lo : hi) = mid;
      }
      // hi: in time; lo: just late. Take whichever ends nearer the instant asked for.
      const Duration at_hi = with_switch(hi), at_lo = with_switch(lo);
      const std::int64_t k = (total - at_hi) <= (at_lo - total) ? hi : lo;
      out.switch_percent = p - 1;
      out.switch_at = speed + std::chrono::milliseconds(k);
      out.duration = with_switch(k) - drive;
      return out;
    }
  }
  out.duration = arrival - drive;
  return out;
}

}  // namespace

SyncPlan plan_synchronized_move(std::span<const PlanInput> inputs, Duration wanted, Duration setup,
                                Duration transaction) {
  const std::size_t n = inputs.size();
  SyncPlan plan;
  plan.joints.resize(n);
  if (n == 0) {
    plan.total = wanted;
    return plan;
  }
  const double t_setup = to_seconds(setup);
  const double t_txn = to_seconds(transaction);
  const Duration one_txn = transaction / 2;
  // The m moving joints take the first m slots (2m transactions): first all their
  // drive_to's, one transaction apart, so every new target is in force as soon as the bus
  // allows, then their set_speed's.
  const auto m = static_cast<std::size_t>(
      std::count_if(inputs.begin(), inputs.end(), [](const PlanInput& in) { return in.moving.has_value(); }));
  auto moving_drive = [&](std::size_t k) { return seconds(t_setup) - one_txn + one_txn * static_cast<int>(k); };
  auto moving_speed = [&](std::size_t k) { return moving_drive(m + k); };

  // Moving joints get the first bus slots (every transaction they wait they run on toward
  // the old target); among each kind, the joint that needs longest goes first.
  std::vector<double> fastest(n);  // moving: arrival from slot 0; at rest: profile time
  const Duration give_up = wanted + std::chrono::seconds(120);
  for (std::size_t i = 0; i < n; ++i) {
    const PlanInput& in = inputs[i];
    if (in.moving) {
      const Duration d0 = moving_drive(0);
      fastest[i] = to_seconds(
          moving_arrival(*in.moving, in.target_q8, d0, moving_speed(0), 100, std::nullopt, {}, give_up).value_or(give_up));
    } else {
      fastest[i] = move_seconds(in.distance, 100, in.profile);
    }
  }
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](auto a, auto b) {
    if (inputs[a].moving.has_value() != inputs[b].moving.has_value()) return inputs[a].moving.has_value();
    return fastest[a] > fastest[b];
  });

  double total = to_seconds(wanted);
  for (std::size_t slot = 0; slot < n; ++slot) {
    const std::size_t i = order[slot];
    if (inputs[i].moving) {
      const PlanInput& in = inputs[i];
      const Duration d = moving_drive(slot);
      total = std::max(total, to_seconds(moving_arrival(*in.moving, in.target_q8, d, moving_speed(slot), 100,
                                                        std::nullopt, {}, give_up)
                                             .value_or(give_up)));
    } else
      total = std::max(total, t_setup + double(slot) * t_txn + fastest[i]);
  }
  const Duration total_d = seconds(total);

  std::vector<double> placed;  // drive instants already taken
  for (std::size_t slot = 0; slot < n; ++slot) {
    const std::size_t i = order[slot];
    const PlanInput& in = inputs[i];
    if (in.moving) {
      plan.joints[i] = plan_moving_joint(in, moving_drive(slot), moving_speed(slot), total_d);
      placed.push_back(to_seconds(plan.joints[i].start));
      continue;
    }
    const double earliest = t_setup + double(slot) * t_txn;
    const double available = total - earliest;
    // Slowest percentage that fits (gentlest on the mechanics), but fast enough to cross
    // the zone in kZoneCrossing.
    const int floor_percent = zone_floor_percent(in);
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
  // A moving joint's arrival may be a tick past the instant asked (its ramp moves in whole
  // ticks): the plan's total is the latest arrival.
  Duration latest = total_d;
  for (std::size_t i = 0; i < n; ++i)
    if (inputs[i].moving) latest = std::max(latest, plan.joints[i].start + plan.joints[i].duration);
  plan.total = std::max(total_d, std::min(latest, total_d + std::chrono::milliseconds(1)));
  return plan;
}

}  // namespace armctl::joint_bus
