#include "arm/bus_arm_device.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/core.h>
#include <fmt/ranges.h>

#include "devices/joint_bus/bus_connection.hpp"
#include "devices/joint_bus/joint_diagnostics.hpp"

namespace armctl::arm {

BusArmDevice::BusArmDevice(const ArmModel& model, joint_bus::BusMaster& master, transport::JointBusLink& link,
                           std::string description)
    : master_(master), link_(link), description_(std::move(description)) {
  for (const JointModel& j : model.joints) {
    if (!j.map(Protocol::joint_bus))
      throw ArmctlError(ErrorKind::invalid_argument, fmt::format("joint {} has no joint_bus mapping in the arm file", j.name));
    if (j.map(Protocol::joint_bus)->id > master.joint_count())
      throw ArmctlError(ErrorKind::invalid_argument,
                        fmt::format("joint {} is joint-bus joint {}, but {} has joints 1..{}", j.name, j.map(Protocol::joint_bus)->id,
                                    description_, master.joint_count()));
    numbers_.push_back(j.map(Protocol::joint_bus)->id);
    profiles_.push_back(joint_bus::as_quantized_by_joint({j.map(Protocol::joint_bus)->max_speed_cps, j.map(Protocol::joint_bus)->max_accel_cps2}));
  }
  // A drive transaction is 8 bytes (READY, COMMAND, DATA, STATUS) plus the turnarounds.
  transaction_ = wire_time(10, link.baud());
}

Status BusArmDevice::failed(const Error& e) const { return e; }

Result<std::vector<double>> BusArmDevice::read_positions() {
  std::vector<double> out;
  for (int n : numbers_) {
    auto p = master_.get_position(n);
    if (!p) return p.error();
    out.push_back(*p);
  }
  return out;
}

Result<double> BusArmDevice::read_joint(int joint) {
  if (joint < 0 || std::size_t(joint) >= numbers_.size())
    return Error{ErrorKind::invalid_argument, fmt::format("no joint {} to read (the arm has {})", joint, numbers_.size())};
  auto p = master_.get_position(numbers_[std::size_t(joint)]);
  if (!p) return p.error();
  return double(*p);
}

Status BusArmDevice::move(const std::vector<std::optional<double>>& targets, Duration duration) {
  auto now = read_positions();
  if (!now) return now.error();
  std::vector<joint_bus::PlanInput> inputs;
  std::vector<std::int16_t> clicks;
  std::vector<std::size_t> which;
  for (std::size_t i = 0; i < targets.size(); ++i) {
    if (!targets[i]) continue;
    const long c = std::lround(*targets[i]);
    if (c < -32768 || c > 32767)
      return Error{ErrorKind::invalid_argument, fmt::format("joint {}: {} clicks is outside -32768..32767", numbers_[i], c)};
    joint_bus::PlanInput in;
    in.joint = numbers_[i];
    in.distance = std::abs(double(c) - (*now)[i]);
    in.profile = profiles_[i];
    in.zone = 0;
    inputs.push_back(in);
    clicks.push_back(static_cast<std::int16_t>(c));
    which.push_back(i);
  }
  if (inputs.empty()) return Ok{};
  streamed_percent_.clear();
  const TimePoint start = link_.clock().now();
  const auto plan = joint_bus::plan_synchronized_move(inputs, duration, transaction_, transaction_ * 2);
  // Each joint gets set_speed and drive_to back to back, timed so that it starts when the
  // plan says (the slowest joint first); the plan's start delays make them arrive together.
  std::vector<std::size_t> order(inputs.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return plan.joints[a].start < plan.joints[b].start; });
  for (std::size_t k : order) {
    const TimePoint due = start + plan.joints[k].start - transaction_ * 2;
    if (due > link_.clock().now())
      if (auto s = idle(due - link_.clock().now()); !s) return failed(s.error());
    if (auto s = master_.set_speed(inputs[k].joint, static_cast<std::int16_t>(plan.joints[k].percent)); !s)
      return failed(s.error());
    if (auto d = master_.drive_to(inputs[k].joint, clicks[k]); !d) return failed(d.error());
  }
  return Ok{};
}

Status BusArmDevice::stop() {
  streamed_percent_.clear();
  std::optional<Error> first;
  for (int n : numbers_) {
    auto s = master_.set_speed(n, 0);
    if (!s && !first) first = s.error();  // tell every joint before reporting
  }
  if (first) return failed(*first);
  return Ok{};
}

Status BusArmDevice::set_torque(bool on) {
  std::optional<Error> first;
  for (int n : numbers_) {
    auto s = master_.set_pid_state(n, on);
    if (!s && !first) first = s.error();
  }
  if (first) return failed(*first);
  return Ok{};
}

Status BusArmDevice::release(int joint) {
  if (joint < 0 || std::size_t(joint) >= numbers_.size())
    return Error{ErrorKind::invalid_argument, fmt::format("no joint {} to release (the arm has {})", joint, numbers_.size())};
  if (auto s = master_.set_pid_state(numbers_[std::size_t(joint)], false); !s) return failed(s.error());
  return Ok{};
}

Duration BusArmDevice::stream_period(bool with_read) const {
  const auto joints = static_cast<std::int64_t>(numbers_.size());
  return transaction_ * joints * (with_read ? 2 : 1);
}

Status BusArmDevice::stream(const std::vector<double>& targets, const std::vector<double>& velocities, Duration) {
  // The joint's ramp brakes so as to stop on its target: aimed at the point itself it would
  // lag by its braking distance v^2 / 2a. The target sent leads the point by that distance in
  // the direction of motion, and the speed cap is the point's speed (rounded up to a whole
  // percent, plus one), so the setpoint runs at the point's speed through it; at the end of
  // a motion the velocity is zero and the last target is the point itself.
  if (streamed_percent_.size() != numbers_.size()) {
    streamed_percent_.assign(numbers_.size(), -1);
    streamed_target_.assign(numbers_.size(), std::nullopt);
  }
  for (std::size_t i = 0; i < targets.size() && i < numbers_.size(); ++i) {
    const double v = i < velocities.size() ? velocities[i] : 0.0;
    const double a = std::max(1.0, profiles_[i].max_accel_cps2);
    const double lead = v * std::abs(v) / (2 * a);
    const long c = std::lround(targets[i] + lead);
    if (c < -32768 || c > 32767)
      return Error{ErrorKind::invalid_argument, fmt::format("joint {}: {} clicks is outside -32768..32767", numbers_[i], c)};
    const double top = std::max(1.0, profiles_[i].max_speed_cps);
    const int percent = std::clamp(static_cast<int>(std::ceil(std::abs(v) / top * 100.0)) + 1, 1, 100);
    if (percent != streamed_percent_[i]) {
      if (auto s = master_.set_speed(numbers_[i], static_cast<std::int16_t>(percent)); !s) return failed(s.error());
      streamed_percent_[i] = percent;
    }
    // A joint the motion leaves where it is (a gripper during a path) costs no transaction.
    if (v == 0 && streamed_target_[i] == c) continue;
    if (auto d = master_.drive_to(numbers_[i], static_cast<std::int16_t>(c)); !d) return failed(d.error());
    streamed_target_[i] = c;
  }
  return Ok{};
}

Status BusArmDevice::idle(Duration d) {
  // A link that fails while nothing is asked (a simulated arm's socket closed) throws from
  // read_byte; the caller gets the error as it gets a failed transaction's.
  return catch_error([&]() -> Status {
    joint_bus::idle(link_, d);
    return Ok{};
  });
}

DeviceHealth BusArmDevice::health() {
  DeviceHealth h;
  for (int j = 1; j <= master_.joint_count(); ++j) {
    auto d = master_.read_diagnostics(j);
    if (!d) continue;  // legacy firmware has no diagnostics; a dead joint shows in the reads
    if (d->faults != 0) h.faults.push_back(fmt::format("joint {}: {}", j, joint_bus::describe_faults(d->faults)));
  }
  return h;
}

Status BusArmDevice::clear_faults() {
  std::vector<std::string> failed;
  for (int j = 1; j <= master_.joint_count(); ++j) {
    auto cleared = master_.clear_faults(j);
    if (cleared) continue;
    const joint_bus::JointFailure* f = joint_bus::joint_failure(cleared.error());
    // The original firmware does not know clear_faults: it holds no faults to clear.
    if (f != nullptr && f->kind == joint_bus::FailureKind::unknown_command) continue;
    failed.push_back(cleared.error().message);
  }
  if (failed.empty()) return Ok{};
  return Error{ErrorKind::device, fmt::format("faults not cleared: {} (the other joints were)", fmt::join(failed, "; "))};
}

}  // namespace armctl::arm
