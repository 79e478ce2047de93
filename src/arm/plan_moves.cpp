#include "arm/plan_moves.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/core.h>

#include "arm/tool_speed.hpp"
#include "core/quantity.hpp"
#include "motion/move_limits.hpp"
#include "scene/motion_check.hpp"

namespace armctl::arm {

namespace {

// A LIN from a singular start first takes the tool this far along the line (m).
constexpr double kLeadIn = 0.03;
// Reduced mode's tool speed cap: a PTP is stretched by this much more than the peak found
// over the cap, at most this many times; a motion is over the cap beyond this fraction
// (the sampled peak of a path timed at the cap lands on it within rounding).
constexpr double kToolSpeedMargin = 0.02;
constexpr int kToolSpeedRounds = 8;
constexpr double kToolSpeedTolerance = 0.01;

// Thrown inside the planner, caught by plan_moves.
struct Refused {
  Error error;
  MoveRefusal moves;
};

class Planner {
 public:
  Planner(const ArmKinematics& kinematics, std::vector<double> from, std::span<const Move> moves,
          const PlanOptions& options)
      : kin_(kinematics), model_(kinematics.model()), moves_(moves), options_(options), state_(std::move(from)) {}

  Plan plan() {
    Plan out;
    out.start = state_;
    for (std::size_t k = 0; k < moves_.size();) {
      const Move& m = moves_[k];
      if (std::holds_alternative<CartesianMove>(m.what)) {
        std::size_t end = k + 1;
        if (options_.blend)
          while (end < moves_.size() && std::holds_alternative<CartesianMove>(moves_[end].what)) ++end;
        cartesian(k, end);
        k = end;
        continue;
      }
      if (const auto* p = std::get_if<PtpMove>(&m.what)) ptp(k, *p);
      else if (const auto* t = std::get_if<TrajectoryMove>(&m.what)) trajectory(k, *t);
      else if (const auto* w = std::get_if<WaitMove>(&m.what)) wait(k, *w);
      else message(k, std::get<MessageMove>(m.what));
      ++k;
    }
    if (kin_.reduced() && kin_.reduced()->tool_speed) check_tool_speed(*kin_.reduced()->tool_speed);
    if (kin_.collisions()) out.clearance = check_collisions(*kin_.collisions(), out.start);
    for (const auto& p : pieces_) {
      out.duration += p.duration();
      out.moves += p.moves;
    }
    out.pieces = std::move(pieces_);
    return out;
  }

 private:
  // Every motion checked against the arm's collision world (docs/scene.md) before anything
  // moves; the first contact refuses the plan naming the two bodies, the piece, how far into
  // it and the tool point there. The smallest clearance along all of them otherwise.
  scene::Clearance check_collisions(const scene::CollisionWorld& world, const std::vector<double>& start) {
    scene::Clearance least;
    std::vector<double> from = start;
    for (PlannedPiece& p : pieces_) {
      scene::MotionCheck check;
      if (p.kind == PieceKind::motion) {
        // A motion's sample writes every joint into vectors sized by the caller.
        std::vector<double> v(from.size()), a(from.size());
        check = scene::check_motion(world, p.motion.duration, [&](double t, std::vector<double>& q) {
          q.resize(from.size());
          p.motion.sample(t, q, v, a);
        });
      } else if (p.kind == PieceKind::board_move) {
        // The board turns every joint at once along a straight line in joint space.
        check = scene::check_motion(world, 1.0, [&](double t, std::vector<double>& q) {
          q.resize(from.size());
          for (std::size_t i = 0; i < q.size(); ++i) q[i] = from[i] + t * (p.end[i] - from[i]);
        });
      } else {
        continue;
      }
      const double duration = p.kind == PieceKind::motion ? p.motion.duration : 1.0;
      if (check.contact && check.contact->limit != scene::Limit::none) refuse_limit(p, duration, check);
      if (check.contact) {
        CollisionDetail d;
        d.contact = *check.contact;
        d.first_move = p.first_move;
        d.last_move = p.last_move;
        d.line = p.first_line;
        d.fraction = duration > 0 ? check.at / duration : 0;
        d.joints = check.joints;
        d.tool_point = kin_.pose_at(check.joints).position;
        // Without the piece's label: callers name the moves a refusal is about (MoveRefusal).
        const std::string message = fmt::format(
            "would collide {:.0f}% into the motion, tool point at ({:.1f}, {:.1f}, {:.1f}) mm: {} with {}, {:.1f} mm deep",
            100 * d.fraction, d.tool_point.x() * 1e3, d.tool_point.y() * 1e3, d.tool_point.z() * 1e3, d.contact.first,
            d.contact.second, d.contact.depth * 1e3);
        refuse(p.first_move, p.last_move, Error{ErrorKind::invalid_argument, message, d});
      }
      if (check.clearance.distance < least.distance) least = check.clearance;
      if (!check.started_touching.empty()) {
        // Each pair of bodies once already (check_motion names them by body, not by shape).
        std::string pairs;
        for (const auto& [a, b] : check.started_touching) pairs += (pairs.empty() ? "" : ", ") + a + " with " + b;
        p.note += (p.note.empty() ? "" : "; ") +
                  fmt::format("{}: starts where {} already touch (not checked along it, so that the arm can move out)", p.label, pairs);
      }
      for (const auto& [what, limit] : check.started_beyond)
        p.note += (p.note.empty() ? "" : "; ") +
                  fmt::format("{}: starts with {} beyond {} (it may move back, not further beyond)", p.label,
                              what, limit);
      from = p.end;
    }
    return least;
  }

  // A limit of the fence or reduced mode broken along piece `p` (docs/scene.md "Fence and
  // reduced mode"), refused like a contact: the detail names what and where.
  [[noreturn]] void refuse_limit(const PlannedPiece& p, double duration, const scene::MotionCheck& check) const {
    CollisionDetail d;
    d.contact = *check.contact;
    d.first_move = p.first_move;
    d.last_move = p.last_move;
    d.line = p.first_line;
    d.fraction = duration > 0 ? check.at / duration : 0;
    d.joints = check.joints;
    d.tool_point = kin_.pose_at(check.joints).position;
    const std::string beyond = d.contact.limit == scene::Limit::fence
                                   ? fmt::format("{:.1f} mm outside", d.contact.depth * 1e3)
                                   : "beyond";
    const std::string message =
        fmt::format("would leave the {} {:.0f}% into the motion, tool point at ({:.1f}, {:.1f}, {:.1f}) mm: {} {} {}",
                    d.contact.limit == scene::Limit::fence ? "fence" : "reduced mode's joint range", 100 * d.fraction,
                    d.tool_point.x() * 1e3, d.tool_point.y() * 1e3, d.tool_point.z() * 1e3, d.contact.first, beyond,
                    d.contact.second);
    refuse(p.first_move, p.last_move, Error{ErrorKind::invalid_argument, message, std::move(d)});
  }

  // Reduced mode's cap on the tool speed: PTPs and paths were timed within it; a motion with
  // its own times (a ROS trajectory) that goes faster is refused.
  void check_tool_speed(double cap) const {
    for (const PlannedPiece& p : pieces_) {
      if (p.kind != PieceKind::motion) continue;
      if (const double peak = peak_tool_speed(kin_, p.motion); peak > cap * (1 + kToolSpeedTolerance))
        refuse(p.first_move, p.last_move,
               Error{ErrorKind::invalid_argument,
                     fmt::format("moves the tool at up to {:.1f} mm/s; reduced mode caps it at {:.1f} mm/s (slow the "
                                 "motion down, or switch reduced mode off)",
                                 peak * 1e3, cap * 1e3)});
    }
  }

  // A PTP timed again, longer, until the tool point stays within reduced mode's cap (a
  // jerk-limited move stretched in time is not exactly scaled: a few rounds).
  void cap_tool_speed(std::size_t k, const ArmModel& model, JointMove& move, PlannedMotion& planned, std::string& note) const {
    if (!kin_.reduced() || !kin_.reduced()->tool_speed) return;
    const double cap = *kin_.reduced()->tool_speed;
    for (int round = 0; round < kToolSpeedRounds; ++round) {
      const double peak = peak_tool_speed(kin_, planned);
      if (peak <= cap) break;
      move.min_duration = planned.duration * peak / cap * (1 + kToolSpeedMargin);
      auto again = plan_joint_move(model, state_, move);
      if (!again) refuse(k, k, again.error());
      planned = std::move(again).value();
      if (round == 0)
        note += fmt::format("{}{}: slowed to {:.2f} s to keep the tool within reduced mode's {:.1f} mm/s",
                            note.empty() ? "" : "; ", label(k), planned.duration, cap * 1e3);
    }
  }

  std::string label(std::size_t k) const {
    return moves_[k].label.empty() ? fmt::format("move {}", k + 1) : moves_[k].label;
  }

  [[noreturn]] void refuse(std::size_t first, std::size_t last, const Error& e) const {
    throw Refused{e, MoveRefusal{first, last}};
  }
  [[noreturn]] void refuse(std::size_t k, std::string message) const {
    refuse(k, k, Error{ErrorKind::invalid_argument, std::move(message)});
  }

  PlannedPiece piece(PieceKind kind, std::size_t first, std::size_t last) const {
    PlannedPiece p;
    p.kind = kind;
    p.first_move = first;
    p.last_move = last;
    p.first_line = moves_[first].line;
    p.first_column = moves_[first].column;
    p.last_line = moves_[last].line;
    p.label = first == last ? label(first) : fmt::format("{} .. {}", label(first), label(last));
    return p;
  }

  // Every joint of a PTP's target: joint values over where the move before leaves the arm,
  // or the IK solution nearest there.
  std::vector<double> ptp_target(std::size_t k, const PtpMove& m, std::vector<bool>& given) const {
    std::vector<double> target = state_;
    given.assign(target.size(), false);
    if (const auto* joints = std::get_if<std::vector<std::optional<double>>>(&m.target)) {
      if (joints->size() != target.size())
        refuse(k, fmt::format("{} targets given for an arm with {} joints", joints->size(), target.size()));
      for (std::size_t i = 0; i < target.size(); ++i)
        if ((*joints)[i]) {
          target[i] = *(*joints)[i];
          given[i] = true;
        }
      return target;
    }
    auto solved = kin_.nearest_joints(std::get<CartesianGoal>(m.target), state_);
    if (!solved) refuse(k, k, solved.error());
    for (int i = 0; i < model_.chain_joints(); ++i) given[std::size_t(i)] = true;
    return std::move(solved).value();
  }

  void ptp(std::size_t k, const PtpMove& m) {
    std::vector<bool> given;
    const std::vector<double> target = ptp_target(k, m, given);
    // The joints the move sets (a joint it leaves keeps where it is, even a hair past a
    // limit as a servo reads back): the limits and the device's range.
    std::vector<std::optional<double>> set(target.size());
    for (std::size_t i = 0; i < target.size(); ++i)
      if (given[i]) set[i] = target[i];
    if (auto ok = kin_.check_targets(set, &state_); !ok) refuse(k, k, ok.error());
    for (const auto& w : m.waypoints)
      if (auto ok = kin_.check_targets(w); !ok) refuse(k, k, ok.error().prefixed("a waypoint: "));
    if (!(m.acceleration_scale > 0 && m.acceleration_scale <= 1))
      refuse(k, fmt::format("acceleration {:g} of the limits is not allowed: above 0 up to 1", m.acceleration_scale));
    const double speed = m.speed.value_or(motion::kDefaultJointSpeed);
    if (!m.duration)
      if (auto ok = check_fraction_in(speed, "speed (of the joints' velocity limits)", motion::kMinSpeedFraction,
                                      motion::kMaxSpeedFraction);
          !ok)
        refuse(k, k, ok.error());
    std::optional<MoveDuration> timed;
    if (m.duration) {
      auto t = joint_move_duration(model_, state_, target, *m.duration, m.duration_words);
      if (!t) refuse(k, k, t.error());
      timed = *t;
    }
    PlannedPiece p = piece(options_.ptp == PtpRun::board && m.waypoints.empty() ? PieceKind::board_move
                                                                                  : PieceKind::motion,
                           k, k);
    if (timed && timed->stretched) p.note = timed->note;
    p.moves = 1;
    p.end = target;
    // The jerk-limited move within the limits. Streamed, it is what plays; for a board move
    // (the device interpolates) its duration is the board's time, so that a PTP takes as
    // long however an app sends it (the one duration rule, docs/architecture.md).
    ArmModel scaled;
    const ArmModel* model = &model_;
    if (m.acceleration_scale != 1) {
      scaled = model_;
      for (auto& j : scaled.joints) j.limits.acceleration *= m.acceleration_scale;
      model = &scaled;
    }
    JointMove move;
    move.waypoints = m.waypoints;
    move.target = target;
    move.speed = timed ? 1.0 : speed;
    move.min_duration = timed ? std::max(timed->seconds, m.min_duration) : m.min_duration;
    auto planned = plan_joint_move(*model, state_, move);
    if (!planned) refuse(k, k, planned.error());
    cap_tool_speed(k, *model, move, *planned, p.note);
    if (p.kind == PieceKind::board_move) {
      // The joints that move, and the partner of a coupled one (its actuator value depends on both).
      p.targets.assign(target.size(), std::nullopt);
      for (std::size_t i = 0; i < target.size(); ++i)
        if (given[i]) p.targets[i] = target[i];
      for (const Coupling& c : model_.couplings)
        if (given[std::size_t(c.first)] || given[std::size_t(c.second)])
          for (int j : {c.first, c.second}) p.targets[std::size_t(j)] = target[std::size_t(j)];
      if (auto ok = kin_.check_targets(p.targets, &state_); !ok) refuse(k, k, ok.error());
      p.seconds = planned->duration;
    } else {
      p.motion = std::move(planned).value();
    }
    pieces_.push_back(std::move(p));
    state_ = target;
  }

  void cartesian(std::size_t from, std::size_t to) {
    std::vector<CartesianMove> targets;
    PathTiming timing = options_.timing;
    for (std::size_t k = from; k < to; ++k) {
      targets.push_back(std::get<CartesianMove>(moves_[k].what));
      // Reduced mode: no faster than its cap on the tool speed.
      if (kin_.reduced() && kin_.reduced()->tool_speed)
        targets.back().speed = std::min(targets.back().speed, *kin_.reduced()->tool_speed);
      if (targets.back().acceleration) timing.acceleration = std::min(timing.acceleration, *targets.back().acceleration);
    }
    const std::vector<motion::PathSegment> segments = path_segments(kin_, state_, targets);
    auto plan = plan_path(kin_, state_, segments, timing);
    if (!plan && options_.lead_in)
      if (auto led = lead_in(from, segments.front(), targets, timing)) plan = std::move(*led);
    if (!plan) refuse(from, to - 1, plan.error());
    const motion::JointVector& end = plan->checked->joints.back();
    for (int i = 0; i < end.size(); ++i) state_[std::size_t(i)] = end[i];
    PlannedPiece p = piece(PieceKind::motion, from, to - 1);
    p.motion = std::move(plan->motion);
    p.path = plan->path;
    p.checked = plan->checked;
    p.moves = to - from;
    p.end = state_;
    pieces_.push_back(std::move(p));
  }

  // A line cannot start where the arm is singular (the xArm straight up, as it starts:
  // motion::kSingularStart). So a joint move (PTP) first takes the tool kLeadIn along the
  // line, with the orientation the move asks (the xArm's pitch free), and the line goes on
  // from there: the plan of the line, with the joint move's piece before it, in the first
  // elbow configuration from which the line plans. Empty (nothing planned) when the arm is
  // not at a singularity, the line is too short or plans from no configuration.
  std::optional<PathPlan> lead_in(std::size_t k, const motion::PathSegment& first,
                                  const std::vector<CartesianMove>& targets, const PathTiming& timing) {
    const motion::JointVector q = kin_.chain_of(state_);
    if (first.kind != motion::SegmentKind::lin ||
        model_.kinematics->singularity(q, motion::kSingularStart) == motion::Singularity::none)
      return std::nullopt;
    const Eigen::Vector3d start = kin_.forward(q).position;
    const Eigen::Vector3d line = first.target.position - start;
    if (line.norm() < 2 * kLeadIn) return std::nullopt;
    CartesianGoal goal = targets.front().goal;
    goal.position = start + line.normalized() * kLeadIn;
    PtpMove ptp_move;
    const std::vector<double> before = state_;
    using motion::Elbow;
    for (Elbow elbow : {Elbow::up, Elbow::down, Elbow::left, Elbow::right}) {
      goal.elbow = elbow;
      ptp_move.target = goal;
      try {
        ptp(k, ptp_move);
      } catch (const Refused&) {
        continue;  // no solution with this elbow (or not this arm's kind of elbow)
      }
      auto plan = plan_path(kin_, state_, path_segments(kin_, state_, targets), timing);
      if (plan) {
        PlannedPiece& led = pieces_.back();
        led.label = fmt::format("{}: joint move off the singular start, {:.0f} mm along the line", label(k),
                                kLeadIn * 1e3);
        led.moves = 0;  // the line's move is counted with the line
        return std::move(plan).value();
      }
      pieces_.pop_back();
      state_ = before;
    }
    return std::nullopt;
  }

  void trajectory(std::size_t k, const TrajectoryMove& t) {
    auto planned = plan_spline(model_, state_, t.spline);
    if (!planned) refuse(k, k, planned.error());
    PlannedPiece p = piece(PieceKind::motion, k, k);
    p.motion = std::move(planned->motion);
    p.moves = 1;
    p.end = planned->target;
    pieces_.push_back(std::move(p));
    state_ = planned->target;
  }

  void wait(std::size_t k, const WaitMove& w) {
    if (!(w.seconds >= 0 && std::isfinite(w.seconds)))
      refuse(k, fmt::format("a wait of {:g} s is not allowed: 0 s or more", w.seconds));
    PlannedPiece p = piece(PieceKind::wait, k, k);
    p.seconds = w.seconds;
    p.end = state_;
    pieces_.push_back(std::move(p));
  }

  void message(std::size_t k, const MessageMove& m) {
    PlannedPiece p = piece(PieceKind::message, k, k);
    p.text = m.text;
    p.end = state_;
    pieces_.push_back(std::move(p));
  }

  const ArmKinematics& kin_;
  const ArmModel& model_;
  std::span<const Move> moves_;
  PlanOptions options_;
  std::vector<double> state_;
  std::vector<PlannedPiece> pieces_;
};

}  // namespace

std::string Plan::notes() const {
  std::string out;
  for (const auto& p : pieces)
    if (!p.note.empty()) out += (out.empty() ? "" : "; ") + p.note;
  return out;
}

Result<Plan> plan_moves(const ArmKinematics& kinematics, const std::vector<double>& from, std::span<const Move> moves,
                        const PlanOptions& options, MoveRefusal* refused) {
  if (from.size() != std::size_t(kinematics.joint_count()))
    return Error{ErrorKind::invalid_argument, fmt::format("the start has {} joint values; arm '{}' has {} joints",
                                                          from.size(), kinematics.model().name,
                                                          kinematics.joint_count())};
  for (std::size_t i = 0; i < from.size(); ++i)
    if (!std::isfinite(from[i]))
      return Error{ErrorKind::invalid_argument,
                   fmt::format("the start: joint {} is not a finite number", kinematics.model().joints[i].name)};
  try {
    return Planner(kinematics, from, moves, options).plan();
  } catch (const Refused& r) {
    if (refused) *refused = r.moves;
    return r.error;
  }
}

double run_duration(const Plan& plan, double speed_override) {
  double total = 0;
  for (const PlannedPiece& p : plan.pieces)
    total += p.kind == PieceKind::motion ? p.motion.duration / speed_override : p.duration();
  return total;
}

}  // namespace armctl::arm
