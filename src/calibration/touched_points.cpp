#include "calibration/touched_points.hpp"

#include <cmath>

#include <fmt/core.h>

#include "core/printable.hpp"

namespace armctl::calibration {

Status check_touched_points(const arm::ArmModel& model, std::span<const TouchedPoint> points) {
  const std::size_t n = std::size_t(model.chain_joints());
  for (std::size_t k = 0; k < points.size(); ++k) {
    const TouchedPoint& p = points[k];
    const std::string what = fmt::format("touched point {} ('{}')", k + 1, printable(p.name));
    if (p.joints.size() != n)
      return Error{ErrorKind::invalid_argument,
                   fmt::format("{}: {} joint readings; arm '{}' has {} chain joints", what, p.joints.size(), model.name, n)};
    for (std::size_t i = 0; i < n; ++i) {
      const arm::JointModel& j = model.joints[i];
      if (!std::isfinite(p.joints[i]))
        return Error{ErrorKind::invalid_argument, fmt::format("{}: the reading of {} is not a number", what, j.name)};
      // A reading a little beyond a limit is a joint stopped at its end: 1 % of the travel.
      const double slack = 0.01 * (j.limits.upper - j.limits.lower);
      if (!j.limits.contains(p.joints[i], slack))
        return Error{ErrorKind::invalid_argument,
                     fmt::format("{}: {} reads {}, outside its limits {}..{}", what, j.name,
                                 format_quantity(j.dimension, p.joints[i]), format_quantity(j.dimension, j.limits.lower),
                                 format_quantity(j.dimension, j.limits.upper))};
    }
    if (Status s = arm::within_reach(model, p.position, what); !s) return s;
  }
  return Ok{};
}

ResidualReport residual_report(std::vector<PointResidual> points) {
  ResidualReport r;
  double sum = 0;
  for (const PointResidual& p : points) {
    sum += p.distance * p.distance;
    if (p.distance >= r.max) {
      r.max = p.distance;
      r.worst = p.name;
    }
  }
  r.rms = points.empty() ? 0 : std::sqrt(sum / double(points.size()));
  r.points = std::move(points);
  return r;
}

Result<ResidualReport> verify_points(const arm::ArmModel& model, std::span<const TouchedPoint> points) {
  if (points.empty()) return Error{ErrorKind::invalid_argument, "no touched points to verify"};
  if (Status s = check_touched_points(model, points); !s) return s.error();
  std::vector<PointResidual> out;
  for (const TouchedPoint& p : points) {
    motion::JointVector q(model.chain_joints());
    for (int i = 0; i < model.chain_joints(); ++i) q[i] = p.joints[std::size_t(i)];
    const motion::Pose link = model.kinematics->forward(q);
    const Eigen::Vector3d tool = link.position + link.orientation * model.tool.position;
    const Eigen::Vector3d error = tool - p.position;
    out.push_back(PointResidual{p.name, error, error.norm()});
  }
  return residual_report(std::move(out));
}

std::string to_text(const ResidualReport& report) {
  std::string out;
  for (const PointResidual& p : report.points)
    out += fmt::format("{}{} {:.2f} mm", out.empty() ? "" : ", ", printable(p.name), p.distance * 1e3);
  return out + fmt::format("; rms {:.2f} mm, max {:.2f} mm ({})", report.rms * 1e3, report.max * 1e3,
                           printable(report.worst));
}

}  // namespace armctl::calibration
