#include "arm/tool_speed.hpp"

#include <algorithm>
#include <cmath>

#include "arm/servo_twist.hpp"

namespace armctl::arm {

double peak_tool_speed(const ArmKinematics& kinematics, const PlannedMotion& motion) {
  const std::size_t n = std::size_t(kinematics.joint_count());
  std::vector<double> q(n), v(n), a(n);
  const int steps = std::clamp(int(std::ceil(motion.duration / kToolSpeedStep)), 1, kMaxToolSpeedSamples);
  double peak = 0;
  for (int s = 0; s <= steps; ++s) {
    motion.sample(motion.duration * s / steps, q, v, a);
    const motion::JointVector chain = kinematics.chain_of(q);
    const motion::Jacobian j = tool_jacobian(kinematics, chain);
    const motion::JointVector qd = kinematics.chain_of(v);
    peak = std::max(peak, (j.topRows<3>() * qd).norm());
  }
  return peak;
}

}  // namespace armctl::arm
