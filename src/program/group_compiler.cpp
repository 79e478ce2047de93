#include "program/group_compiler.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/core.h>

#include "arm/group_actions.hpp"

namespace armctl::program {

namespace {

namespace rc = armctl::rc;

constexpr double kShortestAction = 0.02;  // s: finer than the servos follow

class Compiler {
 public:
  Compiler(const arm::Arm& arm, const CompileOptions& options) : arm_(arm), model_(arm.model()), options_(options) {}

  CompiledGroup compile(const ProgramPlan& plan) {
    action(plan.start, options_.first_move_seconds);
    std::vector<double> here = plan.start;
    for (const auto& piece : plan.pieces) {
      if (piece.kind == PieceKind::message) {
        out_.notes.push_back(fmt::format("line {}: PRINT is not replayed (the board has no output)", piece.first_line));
      } else if (piece.kind == PieceKind::wait) {
        for (double left = piece.seconds; left > 1e-9;) {
          const double t = std::min(left, rc::kMoveTimeMaxMs / 1000.0);
          action(here, t);
          left -= t;
        }
      } else {
        sample(piece.motion);
        here = piece.end;
      }
    }
    out_.duration = std::chrono::duration<double>(std::chrono::milliseconds(total_ms_)).count();
    if (out_.actions.size() > std::size_t(rc::kActionsMax))
      throw ArmctlError(ErrorKind::invalid_argument,
                        fmt::format("the program needs {} actions at a path error of {:.2f} mm; a group holds at most {} "
                                    "(shorten the program or allow a larger path error)",
                                    out_.actions.size(), options_.path_error * 1e3, rc::kActionsMax));
    return std::move(out_);
  }

 private:
  void position(const arm::PlannedMotion& m, double t, std::vector<double>& q) {
    v_.resize(q.size());
    a_.resize(q.size());
    m.sample(t, q, v_, a_);
  }
  Eigen::Vector3d tool(const std::vector<double>& q) const { return arm_.forward(arm_.chain_of(q)).position; }

  // The largest tool distance between the board's linear move from qa to qb over [ta, tb]
  // and the plan, at a quarter, half and three quarters of it.
  double error(const arm::PlannedMotion& m, double ta, double tb, const std::vector<double>& qa,
               const std::vector<double>& qb) {
    double worst = 0;
    std::vector<double> q(qa.size()), lerp(qa.size());
    for (double f : {0.25, 0.5, 0.75}) {
      position(m, ta + f * (tb - ta), q);
      for (std::size_t i = 0; i < q.size(); ++i) lerp[i] = qa[i] + f * (qb[i] - qa[i]);
      worst = std::max(worst, (tool(q) - tool(lerp)).norm());
    }
    return worst;
  }

  void sample(const arm::PlannedMotion& m) {
    std::vector<double> qa(model_.joints.size()), qb(qa.size());
    double ta = 0;
    position(m, 0, qa);
    while (ta < m.duration - 1e-9) {
      double tb = std::min(m.duration, ta + rc::kMoveTimeMaxMs / 1000.0);
      for (;;) {
        position(m, tb, qb);
        const double e = error(m, ta, tb, qa, qb);
        if (e <= options_.path_error || tb - ta <= kShortestAction) {
          out_.sampling_error = std::max(out_.sampling_error, e);
          break;
        }
        tb = ta + (tb - ta) / 2;
      }
      action(qb, tb - ta);
      ta = tb;
      qa = qb;
      if (out_.actions.size() > std::size_t(rc::kActionsMax)) return;  // refused in compile()
    }
  }

  // One action to `q` over `seconds`; times are rounded on the running total, so they do
  // not drift.
  void action(const std::vector<double>& q, double seconds) {
    planned_s_ += seconds;
    const long end_ms = std::lround(planned_s_ * 1000);
    const long ms = end_ms - total_ms_;
    if (ms <= 0) return;
    total_ms_ = end_ms;
    // The plan was checked against the board's range: an error here is the arm's own.
    out_.actions.push_back(arm::servo_action(model_, std::vector<std::optional<double>>(q.begin(), q.end()),
                                             std::uint16_t(std::min<long>(ms, rc::kMoveTimeMaxMs)))
                               .value());
  }

  const arm::Arm& arm_;
  const arm::ArmModel& model_;
  CompileOptions options_;
  std::vector<double> v_, a_;
  CompiledGroup out_;
  double planned_s_ = 0;
  long total_ms_ = 0;
};

}  // namespace

Result<CompiledGroup> compile_to_group(const arm::Arm& arm, const ProgramPlan& plan, const CompileOptions& options) {
  if (!(options.path_error > 0) || !std::isfinite(options.path_error))
    return Error{ErrorKind::invalid_argument, fmt::format("path error {} m is not allowed: above 0", options.path_error)};
  return catch_error([&]() -> Result<CompiledGroup> { return Compiler(arm, options).compile(plan); });
}

}  // namespace armctl::program
