// A joint trajectory with its own times (a ROS FollowJointTrajectory goal, the
// JointTrajectory topic), checked against the arm and turned into a PlannedMotion for the
// executor. Pure: the model in, the motion out.
//
// Between points every joint follows a quintic (positions, velocities and accelerations
// given), a cubic (positions and velocities) or, with positions only, a cubic whose
// velocities at the inner points are estimated from the neighbouring slopes (0 where the
// joint turns back). The motion starts where the arm stands, at rest, at time 0, and ends at
// rest at the last point. Joints a point leaves empty hold where they are.
#pragma once

#include <optional>
#include <vector>

#include "arm/arm_model.hpp"
#include "arm/motion_executor.hpp"
#include "core/error.hpp"

namespace armctl::arm {

struct SplinePoint {
  double time = 0;  // s from the start
  // Every joint in the model's order: empty entries hold the joint where the arm stands.
  std::vector<std::optional<double>> positions;
  // Every joint, or empty; used only when every point gives them.
  std::vector<double> velocities, accelerations;
};

struct SplineRequest {
  std::vector<SplinePoint> points;
  // How close a point at time 0 must be to where the arm stands (the motion starts there).
  double start_angle_tolerance = 0.02;    // rad
  double start_length_tolerance = 0.002;  // m
  // The longest trajectory (s): beyond, the polynomials lose their precision.
  double longest = 3600;
};

struct SplinePlan {
  PlannedMotion motion;
  std::vector<double> target;  // every joint at the end (SI)
};

// Everything before anything moves: finite values, times from 0 and rising, every point
// and the interpolated motion (sampled at 200 Hz and at least 50 times a segment) within
// the joints' position, velocity and acceleration limits. `from`: where the arm stands
// (SI, every joint). Refusals: invalid_argument, naming the point, the joint and the limit.
Result<SplinePlan> plan_spline(const ArmModel& model, const std::vector<double>& from, const SplineRequest& request);

}  // namespace armctl::arm
