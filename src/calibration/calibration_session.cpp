#include "calibration/calibration_session.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include <fmt/core.h>

#include "calibration/arm_file_writer.hpp"
#include "arm/protocols.hpp"
#include "core/quantity.hpp"

namespace armctl::calibration {

namespace {

Error refuse(std::string m) { return Error{ErrorKind::invalid_argument, std::move(m)}; }

bool is_angle(const arm::JointModel& j) { return j.dimension == Dimension::angle; }

}  // namespace

CalibrationSession::CalibrationSession(arm::Arm& arm, ServoBus* servos, SessionOptions options)
    : arm_(arm), servos_(servos), options_(options) {}

Status CalibrationSession::check_joint(int joint) const {
  if (joint < 0 || joint >= model().joint_count())
    return refuse(fmt::format("no joint {} (arm '{}' has joints 1..{})", joint + 1, model().name, model().joint_count()));
  return Ok{};
}

Result<int> CalibrationSession::joint_named(const std::string& text) const {
  if (auto i = model().find_joint(text)) return *i;
  char* end = nullptr;
  const long n = std::strtol(text.c_str(), &end, 10);
  if (!text.empty() && end == text.c_str() + text.size() && n >= 1 && n <= model().joint_count()) return int(n - 1);
  std::string names;
  for (const auto& j : model().joints) names += (names.empty() ? "" : ", ") + j.name;
  return refuse(fmt::format("joint '{}': allowed a number 1..{} or a name ({})", text, model().joint_count(), names));
}

// ---- 1. find

Result<FindReport> CalibrationSession::find() {
  FindReport report;
  const arm::Protocol protocol = arm_.device().protocol();
  std::vector<double> all;
  if (!servos_) {
    // No bus underneath: the arm answers as a whole, or not at all.
    auto r = arm_.device().read_positions();
    if (!r) return r.error();
    all = *r;
  }
  for (int i = 0; i < model().joint_count(); ++i) {
    const arm::JointModel& j = model().joints[std::size_t(i)];
    const arm::DeviceMap* map = j.map(protocol);
    if (!map) continue;
    DeviceAnswer a{map->id, j.name, false, std::nullopt};
    if (servos_) {
      auto p = servos_->read_position(map->id);
      if (!p) return p.error();
      a.position = *p;
    } else {
      a.position = all[std::size_t(i)];
    }
    a.answers = a.position.has_value();
    if (!a.answers) report.silent.push_back(a.id);
    report.text += a.answers ? fmt::format("  {} (ID {}): answers, at {:.0f}\n", a.joint, a.id, *a.position)
                             : fmt::format("  {} (ID {}): NO ANSWER\n", a.joint, a.id);
    report.devices.push_back(std::move(a));
  }
  if (!report.silent.empty())
    report.text +=
        "  An ID without an answer has no servo, or it went to another servo, whose ID now has two\n"
        "  servos (their replies collide when they stand apart). Setting an ID reaches EVERY servo on the bus: unplug all but\n"
        "  the one servo, give it the ID of the place it is mounted in, plug the others back.\n";
  return report;
}

Status CalibrationSession::set_servo_id(int id) {
  if (!servos_) return Error{ErrorKind::unsupported, "this device has no servo IDs to set (a joint bus chooses joints by wire)"};
  bool known = false;
  for (const auto& j : model().joints)
    if (const arm::DeviceMap* m = j.map(arm_.device().protocol()); m && m->id == id) known = true;
  if (!known) return refuse(fmt::format("servo ID {}: the arm file has no joint with that ID", id));
  if (Status s = servos_->set_id_of_only_servo(id); !s) return s;
  auto p = servos_->read_position(id);
  if (!p) return p.error();
  if (!*p) return Error{ErrorKind::device, fmt::format("servo ID {} gives no answer after the ID was set: was exactly one servo connected?", id)};
  return Ok{};
}

// ---- 2. and 3. moves

Status CalibrationSession::move_by(int joint, double amount) {
  auto now = arm_.read();
  if (!now) return now.error();
  const arm::JointModel& j = model().joints[std::size_t(joint)];
  double target = now->positions[std::size_t(joint)] + amount;
  // The move must go positive to answer the question: near the upper end the user moves
  // the joint back first.
  if (target > j.limits.upper) return refuse(fmt::format("joint {} stands too near its upper limit to move positive; move it back first", j.name));
  std::vector<std::optional<double>> targets(std::size_t(model().joint_count()));
  targets[std::size_t(joint)] = target;
  if (Status s = arm_.move_joints(targets); !s) return s;
  auto w = arm_.wait();
  if (!w) return w.error();
  return Ok{};
}

Status CalibrationSession::wiggle(int joint, const std::function<void()>& at_far_end) {
  if (Status s = check_joint(joint); !s) return s;
  const double d = is_angle(model().joints[std::size_t(joint)]) ? options_.wiggle_angle : options_.wiggle_length;
  if (Status s = move_by(joint, d); !s) return s;
  if (at_far_end) at_far_end();
  return move_by(joint, -d);
}

Status CalibrationSession::answer_which(int joint, int moved) {
  if (Status s = check_joint(joint); !s) return s;
  if (Status s = check_joint(moved); !s) return s;
  if (joint == moved) return Ok{};
  const auto& a = model().joints[std::size_t(joint)];
  const auto& b = model().joints[std::size_t(moved)];
  return Error{ErrorKind::device,
               fmt::format("{} was moved but {} moved: the servo answering {}'s ID is mounted where {} belongs; "
                           "give each servo its place's ID (step find)",
                           a.name, b.name, a.name, b.name)};
}

Status CalibrationSession::nudge(int joint) {
  if (Status s = check_joint(joint); !s) return s;
  const double d = is_angle(model().joints[std::size_t(joint)]) ? options_.nudge_angle : options_.nudge_length;
  return move_by(joint, d);
}

Status CalibrationSession::answer_direction(int joint, bool went_as_shown) {
  if (Status s = check_joint(joint); !s) return s;
  joints_[joint].flip = direction_from_answer(model(), joint, went_as_shown).has_value();
  return Ok{};
}

// ---- 4. zero

Status CalibrationSession::release() { return arm_.set_torque(false); }
Status CalibrationSession::hold() { return arm_.set_torque(true); }

Result<double> CalibrationSession::read_joint(int joint) {
  if (Status s = check_joint(joint); !s) return s.error();
  auto r = arm_.read();
  if (!r) return r.error();
  return r->positions[std::size_t(joint)];
}

Result<ZeroResult> CalibrationSession::zero_here(int joint, double mark) {
  if (Status s = check_joint(joint); !s) return s.error();
  const arm::JointModel& j = model().joints[std::size_t(joint)];
  if (!std::isfinite(mark) || mark < j.urdf_lower || mark > j.urdf_upper)
    return refuse(fmt::format("joint {}: the mark's value must lie within its travel", j.name));
  auto r = arm_.read();
  if (!r) return r.error();
  JointAtMark at;
  at.joint = joint;
  at.reading = r->positions[std::size_t(joint)];
  at.device = r->device[std::size_t(joint)];
  at.mark = mark;
  const arm::Protocol protocol = arm_.device().protocol();
  const arm::DeviceMap* map = j.map(protocol);
  at.servo_offsets = options_.servo_offsets && servos_ != nullptr && map != nullptr;
  if (at.servo_offsets) {
    auto o = servos_->read_offset(map->id);
    if (!o) return o.error();
    at.servo_offset = *o;
  }
  auto step = zero_at_mark(model(), protocol, at);
  if (!step) return step.error();
  JointAnswers& a = joints_[joint];
  // new = sign * old + shift reads `mark` here, whichever order direction and zero come in.
  const double shift = mark - sign(joint) * at.reading;
  ZeroResult out;
  out.text = step->why;
  a.fit_correction = 0;
  if (step->kind == ZeroStep::Kind::servo_offset && step->servo_offset) {
    a.servo_offset = step->servo_offset->units;
    a.servo = step->servo_offset->servo;
    a.held_offset = at.servo_offset;
    a.offset_shift = shift;
    a.zero_shift.reset();
    out.kind = ZeroStep::Kind::servo_offset;
    out.servo_offset = *a.servo_offset;
  } else {
    // The joint bus's home (the joint's count 0 here) is not reached through the Arm API: the
    // file's zero moves instead, which reads the same.
    a.servo_offset.reset();
    a.zero_shift = shift;
    out.kind = ZeroStep::Kind::file_zero;
    out.shift = shift;
  }
  return out;
}

// ---- 5. 6. limits, gripper

Result<PositionRange> CalibrationSession::limits(int joint, double end_a, double end_b) {
  if (Status s = check_joint(joint); !s) return s.error();
  const arm::JointModel& j = model().joints[std::size_t(joint)];
  auto range = limits_from_ends(model(), joint, new_reading(joint, end_a), new_reading(joint, end_b));
  if (!range) return range.error();
  // Ends beyond the URDF's travel are cut to it (the file may not reach further).
  range->lower = std::max(range->lower, j.urdf_lower);
  range->upper = std::min(range->upper, j.urdf_upper);
  // What confirm would refuse is refused now, while the user still stands at the joint.
  if (range->lower > 0 || range->upper < 0 || range->lower >= range->upper)
    return refuse(fmt::format("joint {}: limits {} .. {} exclude its zero; move it to ends on both sides of its mark",
                              j.name, quantity_text(j.dimension, range->lower), quantity_text(j.dimension, range->upper)));
  joints_[joint].ends = std::make_pair(end_a, end_b);
  return *range;
}

Result<GripperPositions> CalibrationSession::gripper(double open, double closed) {
  int g = -1;
  for (int i = 0; i < model().joint_count(); ++i)
    if (model().joints[std::size_t(i)].role == arm::JointRole::gripper) g = i;
  if (g < 0) return refuse(fmt::format("arm '{}' has no gripper", model().name));
  auto p = gripper_from_readings(model(), new_reading(g, open), new_reading(g, closed));
  if (!p) return p.error();
  gripper_ = std::make_pair(open, closed);
  return *p;
}

// ---- 7. 8. points and fit

Result<TouchedPoint> CalibrationSession::touch(const NamedPoint& point) {
  auto r = arm_.read();
  if (!r) return r.error();
  TouchedPoint p;
  p.name = point.name;
  p.position = point.position;
  p.joints.assign(r->positions.begin(), r->positions.begin() + model().chain_joints());
  std::erase_if(touched_, [&](const TouchedPoint& t) { return t.name == p.name; });  // touched again
  touched_.push_back(p);
  return p;
}

std::vector<TouchedPoint> CalibrationSession::new_readings(const std::vector<TouchedPoint>& points) const {
  std::vector<TouchedPoint> out = points;
  for (TouchedPoint& p : out)
    for (std::size_t i = 0; i < p.joints.size(); ++i) p.joints[i] = new_reading(int(i), p.joints[i]);
  return out;
}

Result<ResidualReport> CalibrationSession::verify() const {
  if (touched_.empty()) return refuse("no points touched yet");
  // With pending lengths the model's chain is not the one to check on: the points go through
  // the chain with the lengths applied (the fit's model) instead.
  if (link_lengths_.empty()) return verify_points(model(), new_readings(touched_));
  auto chain = CalibrationChain::make(model());
  if (!chain) return chain.error();
  std::vector<Parameter> parameters;
  Eigen::VectorXd values(Eigen::Index(link_lengths_.size()));
  for (std::size_t k = 0; k < link_lengths_.size(); ++k) {
    parameters.push_back(length_parameter(link_lengths_[k].joint));
    values[Eigen::Index(k)] = link_lengths_[k].length - chain->length(link_lengths_[k].joint);
  }
  std::vector<PointResidual> res;
  for (const TouchedPoint& p : new_readings(touched_)) {
    const Eigen::VectorXd q = Eigen::Map<const Eigen::VectorXd>(p.joints.data(), Eigen::Index(p.joints.size()));
    const Eigen::Vector3d at = chain->tool_point(q, parameters, values);
    res.push_back({p.name, at - p.position, (at - p.position).norm()});
  }
  return residual_report(std::move(res));
}

Result<FitResult> CalibrationSession::fit() {
  // Earlier fits are undone first: the fit starts from the answers of the other steps.
  for (auto& [i, a] : joints_) a.fit_correction = 0;
  link_lengths_.clear();
  auto f = fit_kinematics(model(), new_readings(touched_));
  if (!f) return f.error();
  for (const ParameterEstimate& e : f->estimates) {
    if (e.parameter.kind == ParameterKind::zero)
      joints_[e.parameter.joint].fit_correction = e.correction;
    else
      link_lengths_.push_back({e.parameter.origin, e.length});
  }
  return *f;
}

// ---- the pending changes

double CalibrationSession::sign(int joint) const {
  auto it = joints_.find(joint);
  return it != joints_.end() && it->second.flip.value_or(false) ? -1.0 : 1.0;
}

// The zero shift of the new readings; for the readings of verify and the fit a servo offset
// counts as the file zero it replaces (what the arm reads once the servo holds its offset).
double CalibrationSession::shift(int joint, bool for_readings) const {
  auto it = joints_.find(joint);
  if (it == joints_.end()) return 0;
  const JointAnswers& a = it->second;
  double s = a.zero_shift.value_or(0) + a.fit_correction;
  if (a.servo_offset && (for_readings || a.fit_correction != 0)) s += a.offset_shift;
  return s;
}

// Limits a hand found beyond what the device can carry (a horn turned past the servo's
// 0..1000) are cut to it, in the new readings. A coupled pair is left to check_changes,
// which checks its corners.
void CalibrationSession::cut_to_devices(int joint, double zero_shift, PositionRange& range) const {
  for (const arm::Coupling& k : model().couplings)
    if (k.first == joint || k.second == joint) return;
  for (const auto& [name, map] : model().joints[std::size_t(joint)].devices) {
    const auto protocol = arm::find_protocol(name);
    if (!protocol) continue;
    const arm::DeviceRange d = arm::device_range(*protocol);
    const double x = sign(joint) * map.to_actuator(d.min) + zero_shift, y = sign(joint) * map.to_actuator(d.max) + zero_shift;
    range.lower = std::max(range.lower, std::min(x, y));
    range.upper = std::min(range.upper, std::max(x, y));
  }
}

void CalibrationSession::forget(int joint) { joints_.erase(joint); }

void CalibrationSession::forget_all() {
  joints_.clear();
  gripper_.reset();
  link_lengths_.clear();
  touched_.clear();
}

Result<CalibrationChanges> CalibrationSession::changes() const {
  CalibrationChanges c;
  for (const auto& [i, a] : joints_) {
    JointChange jc;
    jc.joint = model().joints[std::size_t(i)].name;
    jc.flip = a.flip.value_or(false);
    // A fit correcting a joint whose zero the servo was to take moves the file's zero instead.
    const bool offset = a.servo_offset && a.fit_correction == 0;
    jc.zero_shift = shift(i, false);
    const arm::JointModel& j = model().joints[std::size_t(i)];
    if (a.ends) {
      const double lo = sign(i) * a.ends->first + shift(i, true), hi = sign(i) * a.ends->second + shift(i, true);
      auto r = limits_from_ends(model(), i, lo, hi);
      if (!r) return r.error();
      jc.limits = *r;
    } else if (jc.flip || jc.zero_shift != 0) {
      // The old travel, flipped and shifted with the readings. A joint whose zero is an end of
      // its travel (the SCARA's Z at its lowest) keeps that end at its new zero: shifted
      // past it, the travel would exclude the zero.
      const double x = sign(i) * j.limits.lower + jc.zero_shift, y = sign(i) * j.limits.upper + jc.zero_shift;
      jc.limits = PositionRange{std::min({x, y, 0.0}), std::max({x, y, 0.0})};
    }
    if (jc.limits) {
      jc.limits->lower = std::max(jc.limits->lower, j.urdf_lower);
      jc.limits->upper = std::min(jc.limits->upper, j.urdf_upper);
      cut_to_devices(i, jc.zero_shift, *jc.limits);
    }
    if (offset) c.servo_offsets.push_back({jc.joint, a.servo, *a.servo_offset});
    if (jc.flip || jc.zero_shift != 0 || jc.limits) c.joints.push_back(std::move(jc));
  }
  if (gripper_) {
    int g = -1;
    for (int i = 0; i < model().joint_count(); ++i)
      if (model().joints[std::size_t(i)].role == arm::JointRole::gripper) g = i;
    auto p = gripper_from_readings(model(), new_reading(g, gripper_->first), new_reading(g, gripper_->second));
    if (!p) return p.error();
    c.gripper = *p;
  }
  c.link_lengths = link_lengths_;
  if (auto checked = check_changes(model(), c); !checked) return checked.error();
  return c;
}

std::string CalibrationSession::describe() const {
  auto c = changes();
  if (!c) return "the pending changes are refused: " + c.error().message + "\n";
  if (c->empty()) return "nothing to write\n";
  std::string out;
  for (const JointChange& j : c->joints) {
    const auto& m = model().joints[std::size_t(*model().find_joint(j.joint))];
    out += fmt::format("  {}:", j.joint);
    if (j.flip) out += " direction flipped;";
    if (j.zero_shift != 0) out += fmt::format(" zero moved by {};", format_quantity(m.dimension, j.zero_shift));
    if (j.limits)
      out += fmt::format(" limits {} .. {};", format_quantity(m.dimension, j.limits->lower), format_quantity(m.dimension, j.limits->upper));
    out.back() = '\n';
  }
  for (const ServoOffset& o : c->servo_offsets) {
    // ServoOffsetAdjust acts at once: a servo holding its position turns by the change.
    const int i = *model().find_joint(o.joint);
    const int turn = o.units - joints_.at(i).held_offset;
    const arm::JointModel& m = model().joints[std::size_t(i)];
    const double per_unit = std::abs(m.map(arm_.device().protocol())->device_per_unit());
    out += fmt::format("  {}: servo {} offset {} units (written to the servo, which turns by {} units, {}, if its "
                       "torque is on)\n",
                       o.joint, o.servo, o.units, turn, format_quantity(m.dimension, std::abs(turn) / per_unit));
  }
  if (c->gripper && model().gripper) {
    const Dimension d = model().joints[std::size_t(model().gripper->joint)].dimension;
    out += fmt::format("  gripper: open {}, closed {}\n", format_quantity(d, c->gripper->open), format_quantity(d, c->gripper->closed));
  }
  for (const auto& l : c->link_lengths) out += fmt::format("  link {}: {}\n", l.joint, format_quantity(Dimension::length, l.length));
  return out;
}

Result<arm::ArmModel> CalibrationSession::confirm() {
  auto c = changes();
  if (!c) return c.error();
  // Every servo's offset as it was, to put back if the file cannot be written.
  std::vector<std::pair<int, int>> before;
  auto put_back = [&] {
    for (auto [id, units] : before) {
      (void)servos_->adjust_offset(id, units);
      (void)servos_->save_offset(id);
    }
  };
  for (const ServoOffset& o : c->servo_offsets) {
    if (!servos_) return Error{ErrorKind::unsupported, "servo offsets pending but no servo bus to write them to"};
    auto old = servos_->read_offset(o.servo);
    if (!old) return old.error();
    before.emplace_back(o.servo, *old);
    Status s = servos_->adjust_offset(o.servo, o.units);
    if (s) s = servos_->save_offset(o.servo);
    auto back = s ? servos_->read_offset(o.servo) : Result<int>(s.error());
    if (!back || *back != o.units) {
      put_back();
      if (!back) return back.error();
      return Error{ErrorKind::device, fmt::format("servo {}: offset {} written but {} read back; the arm file was not written",
                                                  o.servo, o.units, *back)};
    }
  }
  auto written = write_calibration(model(), *c);
  if (!written) {
    put_back();
    return written.error();
  }
  // The answers and touched points were read in the old model's values: they go with it.
  forget_all();
  touched_.clear();
  // Every app drives with the new file from here on, and may calibrate again from it.
  if (auto used = arm_.use_model(*written); !used)
    return Error{used.error().kind, fmt::format("{} was written, but the arm goes on with the model it was opened with "
                                                "(open it again to drive with the new file): {}",
                                                written->file.string(), used.error().message)};
  return written;
}

}  // namespace armctl::calibration
