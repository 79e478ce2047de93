#include "program/program_flow.hpp"

#include <cmath>
#include <map>
#include <vector>

#include <fmt/core.h>

#include "core/source_place.hpp"
#include "motion/move_limits.hpp"

namespace armctl::program {

namespace {

// ---------------------------------------------------------------- names
class NameCheck {
 public:
  NameCheck(const Program& p, const files::PointsFile& points) : p_(p), points_(points) {}
  void run() {
    for (const auto& s : p_.subroutines) block(s.body);
    block(p_.main);
  }

 private:
  [[noreturn]] void fail(Place at, const std::string& m) const {
    throw ArmctlError(source_error(ErrorKind::invalid_config, {std::string(p_.source), at.line, at.column, m}));
  }
  void target(const Target& t) const {
    if (t.kind != TargetKind::point || points_.find(t.point)) return;
    std::string known;
    std::size_t n = 0;
    for (const auto& pt : points_.points) {
      if (n++ == 12) {
        known += ", ...";
        break;
      }
      known += (known.empty() ? "" : ", ") + pt.name;
    }
    fail(t.at, fmt::format("found point '{}', expected a point of the points file ({})", t.point,
                           points_.points.empty() ? std::string("it has no points") : "it has " + known));
  }
  void block(const Block& b) const {
    for (const auto& s : b) {
      if (s.kind == StatementKind::move) {
        target(s.target);
        if (s.via) target(*s.via);
      } else if (s.kind == StatementKind::call) {
        const Subroutine* sub = nullptr;
        for (const auto& d : p_.subroutines)
          if (d.name == s.name) sub = &d;
        if (!sub) {
          std::string names;
          for (const auto& d : p_.subroutines) names += (names.empty() ? "" : ", ") + d.name;
          fail(s.at, fmt::format("found CALL {}, expected a subroutine defined with DEF ({})", s.name,
                                 names.empty() ? std::string("the program defines none") : "defined: " + names));
        }
        if (sub->parameters.size() != s.arguments.size())
          fail(s.at, fmt::format("found {} argument{} to {}, expected {} (DEF {} at line {})", s.arguments.size(),
                                 s.arguments.size() == 1 ? "" : "s", s.name, sub->parameters.size(), s.name, sub->at.line));
      }
      block(s.body);
      block(s.otherwise);
    }
  }
  const Program& p_;
  const files::PointsFile& points_;
};

// ---------------------------------------------------------------- running
class Runner {
 public:
  Runner(const Program& p, const files::PointsFile& points, const FlowLimits& limits)
      : p_(p), points_(points), limits_(limits) {}

  Flow run() {
    frames_.emplace_back();
    block(p_.main);
    return std::move(flow_);
  }

 private:
  using Frame = std::map<std::string, Value, std::less<>>;

  [[noreturn]] void fail(Place at, const std::string& m) const {
    throw ArmctlError(source_error(ErrorKind::invalid_argument, {std::string(p_.source), at.line, at.column, m}));
  }

  // ---- expressions
  Value eval(const Expr& e) {
    switch (e.kind) {
      case ExprKind::number: return e.value;
      case ExprKind::variable: {
        if (auto it = frames_.back().find(e.name); it != frames_.back().end()) return it->second;
        if (frames_.size() > 1)
          if (auto it = frames_.front().find(e.name); it != frames_.front().end()) return it->second;
        fail(e.at, fmt::format("'{}' has no value here; give it one first (e.g. {} = 3)", e.name, e.name));
      }
      case ExprKind::unary: {
        const Value v = eval(*e.left);
        if (e.op == Operator::neg) return {-v.si, v.unit};
        if (v.unit != Unit::number) fail(e.at, fmt::format("NOT takes a condition (a plain number), found {}", describe(v.unit)));
        return {v.si == 0 ? 1.0 : 0.0, Unit::number};
      }
      case ExprKind::binary: return binary(e);
    }
    return {};
  }

  // A chain "a + b + c ..." is a left-deep tree: walked down its left side and evaluated
  // back up by a loop, so that only nesting (parentheses, signs, NOT: at most
  // kExpressionMaxNesting) makes eval recurse.
  Value binary(const Expr& e) {
    std::vector<const Expr*> chain{&e};
    while (chain.back()->left->kind == ExprKind::binary) chain.push_back(chain.back()->left.get());
    Value a = eval(*chain.back()->left);
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) a = apply(**it, a, eval(*(*it)->right));
    return a;
  }

  Value apply(const Expr& e, const Value& a, const Value& b) {
    auto same = [&](const char* what) {
      if (a.unit != b.unit)
        fail(e.at, fmt::format("'{}' {} {} and {} ({} {} {}); both sides need the same kind of value", to_string(e.op),
                               what, describe(a.unit), describe(b.unit), format_value(a), to_string(e.op), format_value(b)));
    };
    auto dimensionless = [](Unit u) { return u == Unit::number || u == Unit::percent; };
    Value r;
    switch (e.op) {
      case Operator::add:
      case Operator::sub:
        same("adds");
        r = {e.op == Operator::add ? a.si + b.si : a.si - b.si, a.unit};
        break;
      case Operator::mul:
        if (!dimensionless(a.unit) && !dimensionless(b.unit))
          fail(e.at, fmt::format("'*' of {} by {}: one side must be a plain number or a percentage", describe(a.unit),
                                 describe(b.unit)));
        r = {a.si * b.si, a.unit == Unit::number ? b.unit : dimensionless(b.unit) ? a.unit : b.unit};
        if (a.unit == Unit::percent && b.unit != Unit::number) r.unit = b.unit;
        break;
      case Operator::div:
        if (b.si == 0) fail(e.at, fmt::format("division by zero ({} / {})", format_value(a), format_value(b)));
        if (a.unit == b.unit) r = {a.si / b.si, Unit::number};
        else if (dimensionless(b.unit)) r = {a.si / b.si, a.unit};
        else
          fail(e.at, fmt::format("'/' of {} by {}: divide by a plain number, a percentage or the same kind of value",
                                 describe(a.unit), describe(b.unit)));
        break;
      case Operator::lt: same("compares"); r = {a.si < b.si ? 1.0 : 0.0, Unit::number}; break;
      case Operator::le: same("compares"); r = {a.si <= b.si ? 1.0 : 0.0, Unit::number}; break;
      case Operator::gt: same("compares"); r = {a.si > b.si ? 1.0 : 0.0, Unit::number}; break;
      case Operator::ge: same("compares"); r = {a.si >= b.si ? 1.0 : 0.0, Unit::number}; break;
      case Operator::eq: same("compares"); r = {a.si == b.si ? 1.0 : 0.0, Unit::number}; break;
      case Operator::ne: same("compares"); r = {a.si != b.si ? 1.0 : 0.0, Unit::number}; break;
      case Operator::and_:
      case Operator::or_:
        if (a.unit != Unit::number || b.unit != Unit::number)
          fail(e.at, fmt::format("'{}' joins conditions (plain numbers), found {} and {}", to_string(e.op),
                                 describe(a.unit), describe(b.unit)));
        r = {(e.op == Operator::and_ ? (a.si != 0 && b.si != 0) : (a.si != 0 || b.si != 0)) ? 1.0 : 0.0, Unit::number};
        break;
      default: break;
    }
    if (!std::isfinite(r.si)) fail(e.at, fmt::format("'{}' overflows ({} {} {})", to_string(e.op), format_value(a), to_string(e.op), format_value(b)));
    return r;
  }

  // A value of kind `unit` in [lo, hi] (SI); `what` names the slot.
  double want(const Expr& e, Unit unit, const std::string& what, double lo, double hi, bool lo_open = false) {
    const Value v = eval(e);
    if (v.unit != unit)
      fail(e.at, fmt::format("{} takes {} (e.g. {}), found {} ({})", what, describe(unit), example(unit),
                             describe(v.unit), format_value(v)));
    if (!(lo_open ? v.si > lo : v.si >= lo) || v.si > hi)
      fail(e.at, fmt::format("{} is {}; allowed {}{} up to {}", what, format_value(v), lo_open ? "above " : "",
                             format_value({lo, unit}), format_value({hi, unit})));
    return v.si;
  }
  bool condition(const Expr& e, const char* what) {
    const Value v = eval(e);
    if (v.unit != Unit::number)
      fail(e.at, fmt::format("{} takes a condition (e.g. n < 3), found {} ({})", what, describe(v.unit), format_value(v)));
    return v.si != 0;
  }

  // ---- targets
  TargetValue target(const Target& t) {
    TargetValue v;
    if (t.kind == TargetKind::point) {
      const files::Point& p = *points_.find(t.point);  // check_names made sure
      v.label = p.name;
      v.joints = p.joints;
      v.position = p.position;
      v.roll = p.roll;
      v.pitch = p.pitch;
      v.yaw = p.yaw;
      v.elbow = p.elbow;
    } else if (t.kind == TargetKind::joints) {
      v.label = "joints(";
      for (const auto& e : t.joints) {
        const Value j = eval(*e);
        if (j.unit != Unit::angle && j.unit != Unit::length)
          fail(e->at, fmt::format("a joint value is an angle or a length (e.g. 30deg, 120mm), found {} ({})",
                                  describe(j.unit), format_value(j)));
        if (t.joints.size() > files::kPathFileMaxJoints)
          fail(e->at, fmt::format("at most {} joint values", files::kPathFileMaxJoints));
        v.joints.push_back({j.si, j.unit == Unit::angle ? Dimension::angle : Dimension::length});
        v.label += (v.label.size() > 7 ? ", " : "") + format_value(j);
      }
      v.label += ")";
    } else {
      v.label = "pose(";
      for (const auto& f : t.pose) {
        if (f.name == "elbow") {
          v.elbow = motion::parse_elbow(f.word);  // the parser let only elbow words through
          continue;
        }
        const bool length = f.name.size() == 1;
        const double x = want(*f.value, length ? Unit::length : Unit::angle, f.name, -1e3, 1e3);
        if (length) v.position[f.name[0] - 'x'] = x;
        else (f.name == "roll" ? v.roll : f.name == "pitch" ? v.pitch : v.yaw) = x;
        v.label += fmt::format("{}{}={}", v.label.size() > 5 ? ", " : "", f.name, format_value({x, length ? Unit::length : Unit::angle}));
      }
      v.label += ")";
    }
    if (t.offset_frame) {
      v.offset_frame = t.offset_frame;
      for (const auto& f : t.offset) v.offset[f.name[0] - 'x'] = want(*f.value, Unit::length, f.name, -10, 10);
      v.label += fmt::format(" + {}({}, {}, {} mm)", *t.offset_frame == OffsetFrame::tool ? "tool" : "base",
                             v.offset.x() * 1e3, v.offset.y() * 1e3, v.offset.z() * 1e3);
    }
    return v;
  }

  // ---- statements
  void emit(Action a) {
    if (flow_.actions.size() == limits_.actions)
      fail(a.at, fmt::format("the program performs more than {} moves, waits, gripper moves and prints; that is the most "
                             "one run may do (a loop that never ends?)",
                             limits_.actions));
    flow_.actions.push_back(std::move(a));
  }

  void block(const Block& b) {
    for (const auto& s : b) statement(s);
  }

  void statement(const Statement& s) {
    if (++flow_.statements > limits_.statements)
      fail(s.at, fmt::format("the program runs more than {} statements; that is the most one run may run", limits_.statements));
    switch (s.kind) {
      case StatementKind::move: return move(s);
      case StatementKind::wait: {
        Action a{ActionKind::wait, s.at, {}, want(*s.value, Unit::time, "WAIT", 0, 3600), 0, {}};
        return emit(std::move(a));
      }
      case StatementKind::gripper: {
        Action a{ActionKind::gripper, s.at, {}, 0, 0, {}};
        a.closed_fraction = s.gripper == GripperAction::open ? 0 : s.gripper == GripperAction::close ? 1
                            : want(*s.value, Unit::percent, "GRIPPER", 0, 1);
        return emit(std::move(a));
      }
      case StatementKind::print: {
        Action a{ActionKind::print, s.at, {}, 0, 0, {}};
        for (const auto& item : s.print) a.text += item.text ? *item.text : format_value(eval(*item.value));
        return emit(std::move(a));
      }
      case StatementKind::assign: {
        const Value v = eval(*s.value);
        if (frames_.size() > 1 && !frames_.back().contains(s.name) && frames_.front().contains(s.name))
          frames_.front()[s.name] = v;
        else
          frames_.back()[s.name] = v;
        return;
      }
      case StatementKind::if_:
        if (condition(*s.value, "IF")) block(s.body);
        else block(s.otherwise);
        return;
      case StatementKind::loop: {
        const double n = want(*s.value, Unit::number, "LOOP's count", 0, double(limits_.loop_iterations));
        if (n != std::floor(n)) fail(s.value->at, fmt::format("LOOP's count is {}; it must be a whole number", n));
        for (std::size_t i = 0; i < std::size_t(n); ++i) block(s.body);
        return;
      }
      case StatementKind::while_: {
        std::size_t i = 0;
        while (condition(*s.value, "WHILE")) {
          if (i++ == limits_.loop_iterations)
            fail(s.at, fmt::format("the WHILE ran {} times and its condition still holds; a loop may run at most {} "
                                   "times (the check runs the flow to plan every move)",
                                   limits_.loop_iterations, limits_.loop_iterations));
          block(s.body);
        }
        return;
      }
      case StatementKind::call: {
        const Subroutine* sub = nullptr;
        for (const auto& d : p_.subroutines)
          if (d.name == s.name) sub = &d;
        if (frames_.size() > limits_.call_depth)
          fail(s.at, fmt::format("subroutines call one another more than {} deep (a CALL that never ends?)", limits_.call_depth));
        Frame locals;
        for (std::size_t i = 0; i < s.arguments.size(); ++i) locals[sub->parameters[i]] = eval(*s.arguments[i]);
        frames_.push_back(std::move(locals));
        block(sub->body);
        frames_.pop_back();
        return;
      }
      case StatementKind::override_:
        override_ = want(*s.value, Unit::percent, "OVERRIDE", motion::kMinSpeedFraction, motion::kMaxSpeedFraction);
        return;
    }
  }

  void move(const Statement& s) {
    Action a{ActionKind::move, s.at, {}, 0, 0, {}};
    MoveAction& m = a.move;
    m.kind = s.move;
    if (s.via) m.via = target(*s.via);
    m.target = target(s.target);
    m.override_fraction = override_;
    for (const auto& o : s.options) {
      const std::string what = fmt::format("{}'s {}", to_string(s.move), o.name);
      // The ranges every app takes (motion/move_limits.hpp).
      if (s.move == MoveKind::ptp) {
        const double f = want(*o.value, Unit::percent, what, motion::kMinSpeedFraction, motion::kMaxSpeedFraction);
        (o.name == "speed" ? m.speed : m.acceleration) = f;
      } else if (o.name == "speed") {
        m.speed = want(*o.value, Unit::speed, what, motion::kMinToolSpeed, motion::kMaxToolSpeed);
      } else if (o.name == "accel") {
        m.acceleration = want(*o.value, Unit::acceleration, what, 0, 100, true);
      } else if (o.name == "angular_speed") {
        m.angular_speed =
            want(*o.value, Unit::angular_speed, what, motion::kMinToolAngularSpeed, motion::kMaxToolAngularSpeed);
      } else {
        m.zone = want(*o.value, Unit::length, what, 0, 1);
      }
    }
    emit(std::move(a));
  }

  const Program& p_;
  const files::PointsFile& points_;
  FlowLimits limits_;
  Flow flow_;
  std::vector<Frame> frames_;
  double override_ = 1;
};

}  // namespace

Status check_names(const Program& program, const files::PointsFile& points) {
  return catch_error([&]() -> Status {
    NameCheck(program, points).run();
    return Ok{};
  });
}

Result<Flow> run_flow(const Program& program, const files::PointsFile& points, const FlowLimits& limits) {
  if (auto ok = check_names(program, points); !ok) return ok.error();
  return catch_error([&]() -> Result<Flow> { return Runner(program, points, limits).run(); });
}

}  // namespace armctl::program
