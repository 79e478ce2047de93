#include "motion/scara_kinematics.hpp"

#include <cmath>
#include <numbers>
#include <vector>

#include <fmt/format.h>

#include "motion/kinematics_chain.hpp"

namespace armctl::motion {

namespace {

using detail::ChainModel;
using detail::kShapeTolerance;
constexpr double kPi = std::numbers::pi;
constexpr int kZ = 0, kShoulder = 1, kElbow = 2, kWrist1 = 3, kWrist2 = 4, kWrist3 = 5;

Error shape_error(std::string message) {
  return Error{ErrorKind::invalid_config, "URDF chain is not a scara: " + std::move(message)};
}

double degrees(double rad) { return rad * 180 / kPi; }

// Everything the IK needs, taken from the chain at zero (base frame).
struct ScaraGeometry {
  Eigen::Vector3d up;                  // joint Z's direction; joints 2..4 turn about it
  double s_shoulder = 1, s_elbow = 1, s_wrist1 = 1;  // their axes' signs along `up`
  Eigen::Vector3d ex, ey;              // the plane across `up`, ex x ey = up
  Eigen::Vector2d shoulder;            // the shoulder axis in that plane
  detail::Planar2R arm;                // shoulder -> elbow -> wrist centre
  Eigen::Vector3d wrist_centre0;       // where the wrist axes meet, at zero
  Eigen::Vector3d w1, w2, w3;          // the wrist axes (UAJ, SKE, SKF) at zero
  Eigen::Vector3d across3;             // square to w3 (and w2): what SKF's angle turns
  Eigen::Vector3d tool_to_centre;      // tool point to wrist centre, in the tool frame
  Eigen::Matrix3d tool_rotation0;      // the tool frame's rotation at zero
  Eigen::Vector2d flat(const Eigen::Vector3d& p) const { return {p.dot(ex), p.dot(ey)}; }
};

Result<ScaraGeometry> scara_geometry(const ChainModel& c) {
  if (c.size() != 6) {
    return shape_error(fmt::format("the scara family needs 6 chain joints (Z, SHOULDER, UAE, UAJ, SKE, SKF); "
                                   "this chain has {}",
                                   c.size()));
  }
  if (c.revolute(kZ)) return shape_error(fmt::format("joint {} is revolute; joint 1 (Z) must be prismatic", c.name(kZ)));
  for (int i = 1; i < 6; ++i) {
    if (!c.revolute(i)) {
      return shape_error(fmt::format("joint {} is prismatic; joints 2..6 must be revolute", c.name(i)));
    }
  }
  ScaraGeometry g;
  g.up = c.axis0(kZ);
  for (int i : {kShoulder, kElbow, kWrist1}) {
    const double off = c.axis0(i).cross(g.up).norm();
    if (off > kShapeTolerance) {
      return shape_error(fmt::format("joint {}'s axis is {:.4g} deg off joint {}'s direction; joints 2..4 must "
                                     "turn about axes parallel to it",
                                     c.name(i), degrees(std::asin(std::min(1.0, off))), c.name(kZ)));
    }
  }
  g.s_shoulder = c.axis0(kShoulder).dot(g.up) > 0 ? 1 : -1;
  g.s_elbow = c.axis0(kElbow).dot(g.up) > 0 ? 1 : -1;
  g.s_wrist1 = c.axis0(kWrist1).dot(g.up) > 0 ? 1 : -1;
  g.w1 = c.axis0(kWrist1);
  g.w2 = c.axis0(kWrist2);
  g.w3 = c.axis0(kWrist3);
  if (g.w1.cross(g.w2).norm() < 1e-6) {
    return shape_error(fmt::format("joint {}'s axis is parallel to joint {}'s; a wrist needs axes that are not",
                                   c.name(kWrist2), c.name(kWrist1)));
  }
  if (g.w2.cross(g.w3).norm() < 1e-6) {
    return shape_error(fmt::format("joint {}'s axis is parallel to joint {}'s; a wrist needs axes that are not",
                                   c.name(kWrist3), c.name(kWrist2)));
  }
  // Where the first two wrist axes meet (the closest point of the first to the second).
  const Eigen::Vector3d n = g.w1.cross(g.w2);
  const Eigen::Vector3d d = c.point0(kWrist2) - c.point0(kWrist1);
  const double gap = std::abs(d.dot(n)) / n.norm();
  if (gap > kShapeTolerance) {
    return shape_error(fmt::format("the axes of joints {} and {} pass {:.4g} mm apart; the wrist axes must meet in "
                                   "one point",
                                   c.name(kWrist1), c.name(kWrist2), gap * 1000));
  }
  g.wrist_centre0 = c.point0(kWrist1) + g.w1 * (d.cross(g.w2).dot(n) / n.squaredNorm());
  const double off3 = detail::distance_to_line(g.wrist_centre0, c.point0(kWrist3), g.w3);
  if (off3 > kShapeTolerance) {
    return shape_error(fmt::format("joint {}'s axis passes {:.4g} mm from the wrist centre (where the axes of {} "
                                   "and {} meet); the wrist axes must meet in one point",
                                   c.name(kWrist3), off3 * 1000, c.name(kWrist1), c.name(kWrist2)));
  }
  // The plane across `up`: ex towards the wrist centre at zero when it is off the shoulder axis.
  Eigen::Vector3d across = g.wrist_centre0 - c.point0(kShoulder);
  across -= g.up * g.up.dot(across);
  if (across.norm() < 1e-6) across = g.up.unitOrthogonal();
  g.ex = across.normalized();
  g.ey = g.up.cross(g.ex);
  g.shoulder = g.flat(c.point0(kShoulder));
  g.arm = detail::Planar2R(g.flat(c.point0(kElbow) - c.point0(kShoulder)), g.flat(g.wrist_centre0 - c.point0(kElbow)));
  if (g.arm.length1() < 1e-6) {
    return shape_error(fmt::format("joint {}'s axis is on joint {}'s: the upper arm has no length", c.name(kElbow),
                                   c.name(kShoulder)));
  }
  if (g.arm.length2() < 1e-6) {
    return shape_error(fmt::format("the wrist centre is on joint {}'s axis: the forearm has no length",
                                   c.name(kElbow)));
  }
  g.across3 = g.w3.cross(g.w2).normalized();
  g.tool_rotation0 = c.tool0().linear();
  g.tool_to_centre = g.tool_rotation0.transpose() * (g.wrist_centre0 - c.tool0().translation());
  return g;
}

class ScaraKinematics final : public detail::ChainKinematics {
 public:
  ScaraKinematics(ChainModel chain, ScaraGeometry geometry, std::span<const PositionLimits> limits)
      : detail::ChainKinematics(std::move(chain), limits), g_(std::move(geometry)) {}

  std::string_view family() const override { return "scara"; }
  Singularity singularity(const JointVector& joints, double tolerance) const override {
    check_size(joints);
    if (std::abs(g_.arm.bend_sine(g_.s_elbow * joints[kElbow])) < tolerance) return Singularity::arm_stretched;
    const Eigen::Vector3d last = Eigen::AngleAxisd(joints[kWrist1], g_.w1) *
                                 (Eigen::AngleAxisd(joints[kWrist2], g_.w2) * g_.w3);
    if (last.cross(g_.w1).norm() < tolerance) return Singularity::wrist_aligned;
    return Singularity::none;
  }

  Result<std::vector<IkSolution>> inverse(const IkRequest& request, const JointVector& near) const override {
    auto target = detail::checked_target(request.target);
    if (!target) return target.error();
    if (auto ok = detail::check_near(chain_, near); !ok) return ok.error();
    const Eigen::Matrix3d r = target->orientation.toRotationMatrix();
    const Eigen::Vector3d centre = target->position + r * g_.tool_to_centre;

    std::array<detail::Planar2R::Solution, 2> planar;
    double shortfall = 0;
    const Eigen::Vector2d reach = g_.flat(centre) - g_.shoulder;
    const int planar_count = g_.arm.solve(reach, planar, shortfall);
    if (planar_count == 0) return reach_error(reach.norm(), shortfall);

    std::vector<IkSolution> solutions;
    solutions.reserve(4);
    std::array<detail::Refusal, 4> refused;
    std::size_t refused_count = 0;
    const Eigen::Matrix3d chain_rotation = r * g_.tool_rotation0.transpose();
    std::array<std::array<double, 3>, 2> w{};
    int wrist_count = 0;
    bool wrist_aligned = false;
    double first_turn = 0;
    for (int b = 0; b < planar_count; ++b) {
      const auto& p = planar[std::size_t(b)];
      JointVector q(6);
      q[kZ] = (centre - g_.wrist_centre0).dot(g_.up);
      q[kShoulder] = g_.s_shoulder * p.a1.angle;
      q[kElbow] = g_.s_elbow * p.a2.angle;
      const Elbow elbow = detail::cross2(reach, p.elbow) < 0 ? Elbow::right : Elbow::left;
      // What is left for the wrist once the shoulder and elbow have turned about `up`.
      // UAJ turns about `up` too, so the other elbow's wrist differs from the first's only
      // in UAJ, by the difference in shoulder + elbow (unless the wrist is aligned: then UAJ
      // stays at `near` and the wrist is solved again).
      if (b == 0 || wrist_aligned) {
        const Eigen::Matrix3d wrist = detail::rotation(g_.up, -(p.a1 + p.a2)) * chain_rotation;
        wrist_count = solve_wrist(wrist, near[kWrist1], w, wrist_aligned);
        first_turn = p.a1.angle + p.a2.angle;
      } else {
        const double shift = g_.s_wrist1 * (first_turn - (p.a1.angle + p.a2.angle));
        for (int k = 0; k < wrist_count; ++k) w[std::size_t(k)][0] += shift;
      }
      for (int k = 0; k < wrist_count; ++k) {
        q[kWrist1] = w[std::size_t(k)][0];
        q[kWrist2] = w[std::size_t(k)][1];
        q[kWrist3] = w[std::size_t(k)][2];
        const bool flipped = std::remainder(q[kWrist2], 2 * kPi) < 0;
        const int miss = detail::fit_into_limits(chain_, limits_, near, q);  // q[miss] stays as it was
        if (miss >= 0) {
          refused[refused_count++] =
              detail::Refusal{elbow, flipped ? "wrist flipped" : "wrist not flipped", miss, q[miss]};
          continue;
        }
        solutions.push_back(IkSolution{q, Configuration{elbow, flipped, std::nullopt}});
      }
    }
    if (solutions.empty()) {
      return detail::limits_refused(chain_, limits_, std::span(refused.data(), refused_count));
    }
    detail::sort_and_dedupe(chain_, near, solutions);
    return solutions;
  }

 private:
  Error reach_error(double distance, double shortfall) const {
    const std::string& axis = chain_.name(kShoulder);
    if (shortfall > 0) {
      return detail::unreachable(fmt::format(
          "pose beyond reach by {:.1f} mm: the wrist centre would be {:.1f} mm from the {} axis, the arm reaches "
          "{:.1f} mm",
          shortfall * 1000, distance * 1000, axis, (g_.arm.length1() + g_.arm.length2()) * 1000));
    }
    return detail::unreachable(fmt::format(
        "pose too close to the {} axis by {:.1f} mm: the wrist centre would be {:.1f} mm from it, the arm folds to "
        "no less than {:.1f} mm",
        axis, -shortfall * 1000, distance * 1000, std::abs(g_.arm.length1() - g_.arm.length2()) * 1000));
  }

  // exp(w1 a) exp(w2 b) exp(w3 c) = wrist: the two solutions (one when the wrist is
  // aligned: then the first angle stays at `near1` and the last takes up the rest).
  int solve_wrist(const Eigen::Matrix3d& wrist, double near1, std::array<std::array<double, 3>, 2>& out,
                  bool& any_aligned) const {
    any_aligned = false;
    const Eigen::Vector3d& w1 = g_.w1;
    const Eigen::Vector3d& w2 = g_.w2;
    const Eigen::Vector3d& x = g_.w3;
    const Eigen::Vector3d y = wrist * x;
    const double k = w1.dot(w2);
    const double alpha = (w1.dot(y) - k * w2.dot(x)) / (1 - k * k);
    const double beta = (w2.dot(x) - k * w1.dot(y)) / (1 - k * k);
    const Eigen::Vector3d n = w1.cross(w2);
    const double gamma2 = (1 - alpha * alpha - beta * beta - 2 * alpha * beta * k) / n.squaredNorm();
    const double gamma = std::sqrt(std::max(0.0, gamma2));
    const int count = gamma > 0 ? 2 : 1;
    for (int s = 0; s < count; ++s) {
      const Eigen::Vector3d z = alpha * w1 + beta * w2 + (s == 0 ? gamma : -gamma) * n;
      const detail::Turn b = detail::rotation_turn(w2, x, z);
      const bool aligned = (z - w1 * w1.dot(z)).norm() < 1e-9;
      any_aligned = any_aligned || aligned;
      const detail::Turn a = aligned ? detail::turn_of(near1) : detail::rotation_turn(w1, z, y);
      const Eigen::Matrix3d first = (detail::rotation(w1, a) * detail::rotation(w2, b)).transpose() * wrist;
      const double c = detail::rotation_angle(x, g_.across3, first * g_.across3);
      out[std::size_t(s)] = {a.angle, b.angle, c};
    }
    return count;
  }

  ScaraGeometry g_;
};

}  // namespace

Result<std::unique_ptr<Kinematics>> make_scara_kinematics(const UrdfChain& chain,
                                                          std::span<const PositionLimits> limits) {
  if (chain.joints.size() > std::size_t(kMaxChainJoints)) {
    return shape_error(fmt::format("the chain has {} joints; the scara family needs 6", chain.joints.size()));
  }
  ChainModel model(chain);
  auto g = scara_geometry(model);
  if (!g) return g.error();
  if (auto ok = detail::check_limits(model, limits, "scara"); !ok) return ok.error();
  return std::unique_ptr<Kinematics>(std::make_unique<ScaraKinematics>(std::move(model), std::move(*g), limits));
}

}  // namespace armctl::motion
