#include "motion/kinematics.hpp"

#include <cmath>
#include <numbers>

namespace armctl::motion {

Eigen::Quaterniond from_rpy(const Rpy& rpy) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(rpy.yaw, Eigen::Vector3d::UnitZ()) *
                            Eigen::AngleAxisd(rpy.pitch, Eigen::Vector3d::UnitY()) *
                            Eigen::AngleAxisd(rpy.roll, Eigen::Vector3d::UnitX()));
}

Rpy to_rpy(const Eigen::Quaterniond& q) {
  const Eigen::Matrix3d r = q.normalized().toRotationMatrix();
  Rpy out;
  const double sp = -r(2, 0);
  if (std::abs(sp) >= 1 - 1e-12) {
    // Pitch +-90 deg: roll and yaw turn about the same axis; all of it goes to yaw.
    out.pitch = std::copysign(std::numbers::pi / 2, sp);
    out.roll = 0;
    out.yaw = std::atan2(-r(0, 1), r(1, 1));
    return out;
  }
  out.pitch = std::asin(sp);
  out.roll = std::atan2(r(2, 1), r(2, 2));
  out.yaw = std::atan2(r(1, 0), r(0, 0));
  return out;
}

const char* to_string(Elbow elbow) {
  switch (elbow) {
    case Elbow::left: return "left";
    case Elbow::right: return "right";
    case Elbow::up: return "up";
    case Elbow::down: return "down";
  }
  return "?";
}

std::optional<Elbow> parse_elbow(std::string_view word) {
  for (Elbow e : {Elbow::left, Elbow::right, Elbow::up, Elbow::down})
    if (word == to_string(e)) return e;
  return std::nullopt;
}

const char* to_string(Singularity s) {
  switch (s) {
    case Singularity::none: return "none";
    case Singularity::arm_stretched: return "arm stretched or folded";
    case Singularity::wrist_aligned: return "wrist axes aligned";
    case Singularity::over_base_axis: return "tool over the base axis";
  }
  return "?";
}

std::vector<PositionLimits> urdf_position_limits(const UrdfChain& chain) {
  std::vector<PositionLimits> out;
  for (const auto& j : chain.joints) out.push_back(PositionLimits{j.limits.lower, j.limits.upper});
  return out;
}

}  // namespace armctl::motion
