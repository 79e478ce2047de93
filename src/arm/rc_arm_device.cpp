#include "arm/rc_arm_device.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/core.h>
#include <fmt/ranges.h>

#include "devices/joint_bus/joint_diagnostics.hpp"

namespace armctl::arm {

RcArmDevice::RcArmDevice(const ArmModel& model, robot_commands::Client& client) : client_(client) {
  for (const JointModel& j : model.joints) {
    if (!j.map(Protocol::robot_commands))
      throw ArmctlError(ErrorKind::invalid_argument,
                        fmt::format("joint {} has no robot_commands mapping in the arm file", j.name));
    servos_.push_back(static_cast<std::uint8_t>(j.map(Protocol::robot_commands)->id));
  }
}

std::string RcArmDevice::description() const { return client_.link().describe(); }

// A servo reads back its shaft, commanded + offset (client.hpp held_offsets): less the
// offset, a reading is in the frame moves are commanded in, whatever offset the servo holds
// (one the calibration wizard wrote as the joint's zero, or one set with the maker's tool).
Result<std::vector<double>> RcArmDevice::read_positions() {
  auto offsets = client_.held_offsets(servos_);  // known before the read (read the first time)
  if (!offsets) return offsets.error();
  auto read = client_.position_request_pending() ? client_.collect_positions() : client_.read_positions(servos_);
  if (!read) return read.error();
  return commanded_frame(*read, *offsets);
}

std::optional<Duration> RcArmDevice::read_request_time() const {
  return client_.link().frame_time(5 + servos_.size());  // header 2, length, command, count, ids
}

Status RcArmDevice::request_read() {
  // The offsets known first (a ServoOffsetRead the first time): only moves go out while the
  // reply comes back.
  if (auto offsets = client_.held_offsets(servos_); !offsets) return offsets.error();
  return client_.request_positions(servos_);
}

Result<std::vector<double>> RcArmDevice::commanded_frame(const std::vector<rc::ServoPosition>& read,
                                                          const std::vector<int>& offsets) const {
  std::vector<double> out(servos_.size());
  for (std::size_t i = 0; i < servos_.size(); ++i) {
    bool found = false;
    for (const auto& p : read)
      if (p.servo == servos_[i]) {
        out[i] = p.position - offsets[i];
        found = true;
      }
    if (!found)
      return Error{ErrorKind::protocol,
                   fmt::format("{} did not report servo {} in its position reply", description(), int(servos_[i]))};
  }
  return out;
}

Status RcArmDevice::move(const std::vector<std::optional<double>>& targets, Duration duration) {
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(duration).count();
  if (ms < 0 || ms > rc::kMoveTimeMaxMs)
    return Error{ErrorKind::invalid_argument,
                 fmt::format("a Robot Commands move takes 0..30 s; this one would take {:.1f} s (move a shorter "
                             "distance or faster)", std::chrono::duration<double>(duration).count())};
  std::vector<rc::ServoTarget> out;
  for (std::size_t i = 0; i < targets.size(); ++i) {
    if (!targets[i]) continue;
    const long p = std::lround(*targets[i]);
    if (p < 0 || p > 1000)
      return Error{ErrorKind::invalid_argument,
                   fmt::format("servo {}: position {} is outside 0..1000", int(servos_[i]), p)};
    out.push_back(rc::ServoTarget{servos_[i], static_cast<std::uint16_t>(p)});
  }
  if (out.empty()) return Ok{};
  return client_.move(out, static_cast<std::uint16_t>(ms));
}

Status RcArmDevice::hold_where_they_stand() {
  // Not a requested read's reply: that one may be from before the arm was stopped.
  if (client_.position_request_pending()) (void)client_.collect_positions();
  auto now = read_positions();
  if (!now) return now.error();
  std::vector<std::optional<double>> hold(now->begin(), now->end());
  for (auto& h : hold) h = std::clamp(*h, 0.0, 1000.0);  // read-back can lie past 0..1000
  return move(hold, Duration{0});
}

Status RcArmDevice::stop() {
  if (auto s = client_.stop_group(); !s) return s;
  // A board may stop only group playback on GroupStop: the hold stops a plain move too.
  return hold_where_they_stand();
}

Status RcArmDevice::set_torque(bool on) {
  if (!on) return client_.servos_off(servos_);
  return hold_where_they_stand();  // any move restores a servo's torque
}

Status RcArmDevice::release(int joint) {
  if (joint < 0 || std::size_t(joint) >= servos_.size())
    return Error{ErrorKind::invalid_argument, fmt::format("no joint {} to release (the arm has {})", joint, servos_.size())};
  return client_.servos_off({servos_[std::size_t(joint)]});
}

// Serial-form sizes: header 2, length, command, count, then per servo (protocol spec).
Duration RcArmDevice::stream_period(bool with_read) const {
  const std::size_t n = servos_.size();
  Duration d = client_.link().frame_time(7 + 3 * n);  // MultiServoMove: + time (2), id + position (3 each)
  if (with_read) d += client_.link().frame_time(5 + n) + client_.link().frame_time(5 + 3 * n);
  return d;
}

Duration RcArmDevice::stream_latency() const { return client_.link().frame_time(7 + 3 * servos_.size()); }

Status RcArmDevice::stream(const std::vector<double>& targets, const std::vector<double>&, Duration in) {
  // A bus servo interpolates linearly to each point over the time it is given, so the
  // velocities need not be sent: consecutive short moves make the same path.
  std::vector<rc::ServoTarget> out;
  for (std::size_t i = 0; i < targets.size() && i < servos_.size(); ++i) {
    const long p = std::lround(targets[i]);
    if (p < 0 || p > 1000)
      return Error{ErrorKind::invalid_argument,
                   fmt::format("servo {}: position {} is outside 0..1000", int(servos_[i]), p)};
    out.push_back(rc::ServoTarget{servos_[i], static_cast<std::uint16_t>(p)});
  }
  const auto ms = std::clamp<long long>(std::llround(std::chrono::duration<double, std::milli>(in).count()), 0,
                                        rc::kMoveTimeMaxMs);
  return client_.move(out, static_cast<std::uint16_t>(ms));
}

Status RcArmDevice::idle(Duration d) {
  auto pumped = client_.pump_events(client_.clock().now() + d);  // notifications are kept
  if (!pumped) return pumped.error();
  return Ok{};
}

DeviceHealth RcArmDevice::health() {
  DeviceHealth h;
  if (auto mv = client_.battery_millivolts()) h.battery_volts = *mv / 1000.0;
  for (std::uint8_t servo : servos_) {
    auto report = client_.read_joint_faults(servo);
    // Not answered (a board without the extension) or unreadable: left out, as the
    // battery is; the rest would only cost more timeouts.
    if (!report || !*report) break;
    if (auto line = describe_joint_faults(**report)) h.faults.push_back(*line);
  }
  return h;
}

Status RcArmDevice::clear_faults() {
  std::vector<std::string> failed;
  for (std::uint8_t servo : servos_) {
    auto reply = client_.clear_joint_faults(servo);
    if (!reply) return reply.error().prefixed(fmt::format("clearing servo {}'s faults: ", servo));
    if (!*reply) return Ok{};  // a board without armctl's extension holds no joint faults
    if (!(*reply)->cleared())
      failed.push_back(fmt::format("servo {} (its joint answered STATUS {}{})", servo, (*reply)->status,
                                   (*reply)->status == joint_bus::status_no_answer ? ": no answer" : ""));
  }
  if (failed.empty()) return Ok{};
  return Error{ErrorKind::device, fmt::format("faults not cleared on {}; the others were", fmt::join(failed, ", "))};
}

std::optional<std::string> describe_joint_faults(const rc::JointFaultReport& r) {
  std::vector<std::string> parts;
  if (!r.answering) parts.push_back(fmt::format("not answering (last bus failure {})", r.last_failure));
  const std::uint16_t held = r.words_read ? r.words[0] : 0;
  if (held != 0) parts.push_back(fmt::format("{} (bridge off until clear-faults)", joint_bus::describe_faults(held)));
  if (r.behind_ramp) parts.push_back("fell behind its move's ramp (the move was stopped)");
  else if (!r.following && held == 0) parts.push_back("not following its move");
  if (parts.empty()) return std::nullopt;
  std::string out = fmt::format("servo {}: {}", r.servo, parts.front());
  for (std::size_t i = 1; i < parts.size(); ++i) out += ", " + parts[i];
  return out;
}

}  // namespace armctl::arm
