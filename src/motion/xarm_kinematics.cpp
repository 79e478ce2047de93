#include "motion/xarm_kinematics.hpp"

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
constexpr int kBase = 0, kShoulder = 1, kElbow = 2, kWristPitch = 3, kWristRoll = 4;
// How far (sine of the angle) the asked approach may lie out of the arm's plane and still
// count as in it: a pose written in degrees with a few decimals, not another orientation.
constexpr double kPlaneTolerance = 1e-6;

Error shape_error(std::string message) {
  return Error{ErrorKind::invalid_config, "URDF chain is not an xarm: " + std::move(message)};
}

double degrees(double rad) { return rad * 180 / kPi; }

struct XarmGeometry {
  Eigen::Vector3d up, base_point;  // the base joint's axis
  Eigen::Vector3d pitch;           // the shoulder's axis at zero; elbow and wrist pitch parallel
  double s_elbow = 1, s_wrist = 1; // their signs along `pitch`
  Eigen::Vector3d facing;          // where a positive shoulder angle leans the arm, at zero
  Eigen::Vector3d across;          // the arm plane's x axis (across x up = pitch)
  Eigen::Vector3d roll;            // the roll joint's axis (the approach) at zero
  Eigen::Vector2d shoulder;        // in the arm plane (across, up) from base_point
  detail::Planar2R arm;            // shoulder -> elbow -> wrist pitch axis
  Eigen::Vector2d wrist_to_tool;   // wrist pitch axis to tool point, at zero
  Eigen::Matrix3d tool_rotation0;
  Eigen::Vector3d approach_in_tool;  // the roll axis in the tool frame
  Eigen::Vector2d flat(const Eigen::Vector3d& p) const {
    return {(p - base_point).dot(across), (p - base_point).dot(up)};
  }
};

Result<XarmGeometry> xarm_geometry(const ChainModel& c) {
  if (c.size() != 5) {
    return shape_error(fmt::format("the xarm family needs 5 chain joints (base yaw, shoulder, elbow, wrist pitch, "
                                   "wrist roll); this chain has {}",
                                   c.size()));
  }
  for (int i = 0; i < 5; ++i) {
    if (!c.revolute(i)) return shape_error(fmt::format("joint {} is prismatic; every joint must be revolute", c.name(i)));
  }
  XarmGeometry g;
  g.up = c.axis0(kBase);
  g.base_point = c.point0(kBase);
  g.pitch = c.axis0(kShoulder);
  if (std::abs(g.pitch.dot(g.up)) > kShapeTolerance) {
    return shape_error(fmt::format("joint {}'s axis is {:.4g} deg off square to joint {}'s; the shoulder must pitch "
                                   "about an axis square to the base axis",
                                   c.name(kShoulder), degrees(std::asin(std::min(1.0, std::abs(g.pitch.dot(g.up))))),
                                   c.name(kBase)));
  }
  for (int i : {kElbow, kWristPitch}) {
    const double off = c.axis0(i).cross(g.pitch).norm();
    if (off > kShapeTolerance) {
      return shape_error(fmt::format("joint {}'s axis is {:.4g} deg off joint {}'s; the elbow and wrist pitch axes "
                                     "must be parallel to the shoulder's",
                                     c.name(i), degrees(std::asin(std::min(1.0, off))), c.name(kShoulder)));
    }
  }
  g.s_elbow = c.axis0(kElbow).dot(g.pitch) > 0 ? 1 : -1;
  g.s_wrist = c.axis0(kWristPitch).dot(g.pitch) > 0 ? 1 : -1;
  g.roll = c.axis0(kWristRoll);
  if (std::abs(g.roll.dot(g.pitch)) > kShapeTolerance) {
    return shape_error(fmt::format("joint {}'s axis is {:.4g} deg off square to the pitch axes; the wrist must roll "
                                   "about an axis in the arm's plane",
                                   c.name(kWristRoll), degrees(std::asin(std::min(1.0, std::abs(g.roll.dot(g.pitch)))))));
  }
  const Eigen::Vector3d tool = c.tool0().translation();
  const double off_roll = detail::distance_to_line(tool, c.point0(kWristRoll), g.roll);
  if (off_roll > kShapeTolerance) {
    return shape_error(fmt::format("the tool point is {:.4g} mm off joint {}'s axis; it must lie on the roll axis",
                                   off_roll * 1000, c.name(kWristRoll)));
  }
  const double sideways = (tool - g.base_point).dot(g.pitch);
  if (std::abs(sideways) > kShapeTolerance) {
    return shape_error(fmt::format("the tool point is {:.4g} mm sideways of the base axis (along joint {}'s axis); it "
                                   "must lie in the arm's plane through the base axis",
                                   sideways * 1000, c.name(kShoulder)));
  }
  g.across = g.up.cross(g.pitch);
  g.facing = -g.across;
  g.shoulder = g.flat(c.point0(kShoulder));
  g.arm = detail::Planar2R(g.flat(c.point0(kElbow)) - g.shoulder,
                           g.flat(c.point0(kWristPitch)) - g.flat(c.point0(kElbow)));
  if (g.arm.length1() < 1e-6) {
    return shape_error(fmt::format("joint {}'s axis is on joint {}'s: the upper arm has no length", c.name(kElbow),
                                   c.name(kShoulder)));
  }
  if (g.arm.length2() < 1e-6) {
    return shape_error(fmt::format("joint {}'s axis is on joint {}'s: the forearm has no length", c.name(kWristPitch),
                                   c.name(kElbow)));
  }
  g.wrist_to_tool = g.flat(tool) - g.flat(c.point0(kWristPitch));
  g.tool_rotation0 = c.tool0().linear();
  g.approach_in_tool = g.tool_rotation0.transpose() * g.roll;
  return g;
}

class XarmKinematics final : public detail::ChainKinematics {
 public:
  XarmKinematics(ChainModel chain, XarmGeometry geometry, std::span<const PositionLimits> limits)
      : detail::ChainKinematics(std::move(chain), limits), g_(std::move(geometry)) {}

  std::string_view family() const override { return "xarm"; }
  Singularity singularity(const JointVector& joints, double tolerance) const override {
    check_size(joints);
    if (std::abs(g_.arm.bend_sine(g_.s_elbow * joints[kElbow])) < tolerance) return Singularity::arm_stretched;
    const Eigen::Vector3d tool = chain_.forward(joints).translation();
    if (detail::distance_to_line(tool, g_.base_point, g_.up) < tolerance) return Singularity::over_base_axis;
    return Singularity::none;
  }

  Result<std::vector<IkSolution>> inverse(const IkRequest& request, const JointVector& near) const override {
    auto target = detail::checked_target(request.target);
    if (!target) return target.error();
    if (auto ok = detail::check_near(chain_, near); !ok) return ok.error();
    Eigen::Matrix3d r = target->orientation.toRotationMatrix();
    const Eigen::Vector3d rel = target->position - g_.base_point;
    const double height = rel.dot(g_.up);
    const Eigen::Vector3d horizontal = rel - height * g_.up;
    const double radius = horizontal.norm();

    // The base angles that put the point (or, over the base axis, the approach) in the arm's plane.
    struct Base {
      detail::Turn turn;
      bool back;
    };
    std::array<Base, 2> bases{};
    Eigen::Vector3d approach = r * g_.approach_in_tool;
    if (radius > 1e-9) {
      const detail::Turn facing = detail::rotation_turn(g_.up, g_.facing, horizontal);
      bases = {Base{facing, false}, Base{facing.half_turn(), true}};
      const Eigen::Vector3d normal = facing.c * g_.pitch + facing.s * g_.up.cross(g_.pitch);
      const double out_of_plane = approach.dot(normal);
      if (std::abs(out_of_plane) > kPlaneTolerance || request.nearest_orientation) {
        Eigen::Vector3d in_plane = approach - out_of_plane * normal;
        if (in_plane.norm() < 1e-9) in_plane = horizontal;  // square to the plane: any direction is as near
        const Eigen::Matrix3d nearest = Eigen::Quaterniond::FromTwoVectors(approach, in_plane.normalized()) * r;
        if (std::abs(out_of_plane) > kPlaneTolerance && !request.nearest_orientation) {
          const Rpy asked = to_rpy(Eigen::Quaterniond(r));
          const Rpy reachable = to_rpy(Eigen::Quaterniond(nearest));
          return detail::unreachable(fmt::format(
              "orientation not reachable by this 5-joint arm: yaw must be {:.1f} deg at this position (asked {:.1f} "
              "deg; the approach is {:.1f} deg out of the arm's plane)",
              degrees(reachable.yaw), degrees(asked.yaw), degrees(std::asin(std::min(1.0, std::abs(out_of_plane))))));
        }
        r = nearest;
      }
    } else {
      const Eigen::Vector3d level = approach - approach.dot(g_.up) * g_.up;
      const detail::Turn facing = level.norm() > 1e-9 ? detail::rotation_turn(g_.up, g_.facing, level)
                                                      : detail::turn_of(near[kBase]);
      bases = {Base{facing, false}, Base{facing.half_turn(), true}};
    }

    std::vector<IkSolution> solutions;
    solutions.reserve(4);
    std::array<detail::Refusal, 4> refused;
    std::size_t refused_count = 0;
    double best_shortfall = 0, best_distance = 0;
    bool any_reach = false;
    const Eigen::Matrix3d chain_rotation = r * g_.tool_rotation0.transpose();
    const Eigen::Vector3d chain_roll = chain_rotation * g_.roll, chain_pitch = chain_rotation * g_.pitch;
    for (const Base& base : bases) {
      // The base first: half the reaching-back branches end here.
      double base_angle = base.turn.angle;
      if (!detail::fit_joint(chain_, limits_, near, kBase, base_angle)) {
        refused[refused_count++] = detail::Refusal{std::nullopt, base.back ? "reaching back" : "facing the point", kBase,
                                                   base.turn.angle};
        continue;
      }
      // With the base turned back: Rot(pitch, pitch_sum) Rot(roll, roll) is what is left.
      const Eigen::Vector3d roll_axis = detail::rotated(g_.up, -base.turn, chain_roll);
      const Eigen::Vector3d pitch_axis = detail::rotated(g_.up, -base.turn, chain_pitch);
      const detail::Turn pitch_sum = detail::rotation_turn(g_.pitch, g_.roll, roll_axis);
      const double roll = detail::rotation_angle(g_.roll, g_.pitch, detail::rotated(g_.pitch, -pitch_sum, pitch_axis));
      const Eigen::Vector3d across = base.turn.c * g_.across + base.turn.s * g_.up.cross(g_.across);
      const Eigen::Vector2d tool(rel.dot(across), height);
      const Eigen::Vector2d wrist = tool - detail::rotate2(g_.wrist_to_tool, pitch_sum);
      const Eigen::Vector2d reach = wrist - g_.shoulder;
      std::array<detail::Planar2R::Solution, 2> planar;
      double shortfall = 0;
      const int count = g_.arm.solve(reach, planar, shortfall);
      if (count == 0) {
        if (!any_reach || std::abs(shortfall) < std::abs(best_shortfall)) {
          best_shortfall = shortfall;
          best_distance = reach.norm();
        }
        any_reach = true;
        continue;
      }
      for (int b = 0; b < count; ++b) {
        const auto& p = planar[std::size_t(b)];
        JointVector q(5);
        q[kBase] = base.turn.angle;
        q[kShoulder] = p.a1.angle;
        q[kElbow] = g_.s_elbow * p.a2.angle;
        q[kWristPitch] = g_.s_wrist * (pitch_sum.angle - p.a1.angle - p.a2.angle);
        q[kWristRoll] = roll;
        const double side = detail::cross2(reach, p.elbow) * (reach.x() >= 0 ? 1 : -1);
        const Elbow elbow = side > 0 ? Elbow::up : Elbow::down;
        const int miss = detail::fit_into_limits(chain_, limits_, near, q);  // q[miss] stays as it was
        if (miss >= 0) {
          refused[refused_count++] = detail::Refusal{elbow, base.back ? "reaching back" : "", miss, q[miss]};
          continue;
        }
        solutions.push_back(IkSolution{q, Configuration{elbow, std::nullopt, base.back}});
      }
    }
    if (solutions.empty()) {
      if (refused_count == 0) return reach_error(best_distance, best_shortfall);
      Error e = detail::limits_refused(chain_, limits_, std::span(refused.data(), refused_count));
      if (any_reach) e.message += "; otherwise " + reach_error(best_distance, best_shortfall).message;
      return e;
    }
    detail::sort_and_dedupe(chain_, near, solutions);
    return solutions;
  }

 private:
  Error reach_error(double distance, double shortfall) const {
    const std::string& wrist = chain_.name(kWristPitch);
    const std::string& shoulder = chain_.name(kShoulder);
    if (shortfall > 0) {
      return detail::unreachable(fmt::format(
          "pose beyond reach by {:.1f} mm at this tool pitch: joint {}'s axis would be {:.1f} mm from joint {}'s, the "
          "arm reaches {:.1f} mm",
          shortfall * 1000, wrist, distance * 1000, shoulder, (g_.arm.length1() + g_.arm.length2()) * 1000));
    }
    return detail::unreachable(fmt::format(
        "pose too close to joint {}'s axis by {:.1f} mm at this tool pitch: joint {}'s axis would be {:.1f} mm from "
        "it, the arm folds to no less than {:.1f} mm",
        shoulder, -shortfall * 1000, wrist, distance * 1000, std::abs(g_.arm.length1() - g_.arm.length2()) * 1000));
  }

  XarmGeometry g_;
};

}  // namespace

Result<std::unique_ptr<Kinematics>> make_xarm_kinematics(const UrdfChain& chain,
                                                         std::span<const PositionLimits> limits) {
  if (chain.joints.size() > std::size_t(kMaxChainJoints)) {
    return shape_error(fmt::format("the chain has {} joints; the xarm family needs 5", chain.joints.size()));
  }
  ChainModel model(chain);
  auto g = xarm_geometry(model);
  if (!g) return g.error();
  if (auto ok = detail::check_limits(model, limits, "xarm"); !ok) return ok.error();
  return std::unique_ptr<Kinematics>(std::make_unique<XarmKinematics>(std::move(model), std::move(*g), limits));
}

}  // namespace armctl::motion
