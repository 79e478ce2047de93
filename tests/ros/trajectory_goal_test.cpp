// Trajectory goals as ROS sends them: every refusal names what was wrong (and carries
// control_msgs' error code), and an accepted trajectory passes through its points and stays
// within the arm's limits. No roscore: ros/trajectory_goal.hpp has no ROS types.
#include <cmath>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "arm/arm_kinematics.hpp"
#include "arm/arm_model.hpp"
#include "ros/trajectory_goal.hpp"

namespace armctl::ros_node {
namespace {

using ::testing::HasSubstr;

arm::ArmModel model(const char* name) {
  return arm::load_arm_model(std::string(ARMCTL_SOURCE_DIR) + "/config/" + name + ".arm.json").value();
}

std::vector<std::string> chain_names(const arm::ArmModel& m) {
  std::vector<std::string> out;
  for (int j = 0; j < m.chain_joints(); ++j) out.push_back(m.joints[std::size_t(j)].name);
  return out;
}

// Every chain joint at `value` scaled into its range (0 = the middle), at `time`.
TrajectoryPoint point_at(const arm::ArmModel& m, double time, double fraction) {
  TrajectoryPoint p;
  p.time = time;
  for (int j = 0; j < m.chain_joints(); ++j) {
    const auto& l = m.joints[std::size_t(j)].limits;
    p.positions.push_back(0.5 * (l.lower + l.upper) + fraction * 0.5 * (l.upper - l.lower));
  }
  return p;
}

std::vector<double> middle(const arm::ArmModel& m) {
  std::vector<double> q;
  for (const auto& j : m.joints) q.push_back(0.5 * (j.limits.lower + j.limits.upper));
  return q;
}

TrajectoryRequest five_points(const arm::ArmModel& m) {
  TrajectoryRequest r;
  r.joint_names = chain_names(m);
  const double f[] = {0.1, 0.2, 0.05, -0.1, 0.0};
  for (int k = 0; k < 5; ++k) r.points.push_back(point_at(m, 2.0 * (k + 1), f[k]));
  return r;
}

GoalRefusal refusal(const arm::ArmModel& m, const TrajectoryRequest& r) {
  auto plan = plan_trajectory(m, middle(m), r);
  EXPECT_FALSE(plan.ok());
  if (plan.ok()) return {GoalError::none, ""};
  return refusal_of(plan.error());
}

class TrajectoryGoal : public ::testing::TestWithParam<const char*> {};

// A ROS trajectory is planned with the arm's kinematics and its scene (docs/scene.md): one that
// passes through a box is refused before anything moves, as an invalid goal naming the bodies.
TEST(TrajectoryGoalScene, ATrajectoryThroughABoxIsRefused) {
  const auto m = model("xarm");
  const auto r = five_points(m);
  const arm::ArmKinematics plain(m);
  auto clear = plan_trajectory(plain, middle(m), r);
  ASSERT_TRUE(clear.ok()) << clear.error().message;
  // A ball 60 mm across around where the tool point passes halfway to the first point (the
  // tool point itself has no shape: the ball reaches the fingers and the hand).
  std::vector<double> p(m.joints.size()), v(m.joints.size()), a(m.joints.size());
  clear->motion.sample(1.0, p, v, a);
  const Eigen::Vector3d tool = plain.pose_at(p).position;
  scene::SceneObject ball;
  ball.name = "ball";
  ball.shape.kind = motion::Shape::Kind::sphere;
  ball.shape.size = {0.03, 0, 0};
  ball.shape.pose.translation() = tool;
  auto with = plain.with_scene(scene::Scene{{ball}, {}}).value();
  auto plan = plan_trajectory(*with, middle(m), r);
  ASSERT_FALSE(plan.ok());
  EXPECT_EQ(refusal_of(plan.error()).code, GoalError::invalid_goal);
  EXPECT_THAT(plan.error().message, HasSubstr("with sphere 'ball'"));
}

TEST_P(TrajectoryGoal, PassesThroughEveryPointWithinTheLimits) {
  const auto m = model(GetParam());
  const auto r = five_points(m);
  auto plan = plan_trajectory(m, middle(m), r);
  ASSERT_TRUE(plan.ok()) << plan.error().message;
  EXPECT_DOUBLE_EQ(plan->motion.duration, 10.0);
  std::vector<double> p, v, a;
  plan->motion.sample(0, p, v, a);
  for (std::size_t j = 0; j < p.size(); ++j) {
    EXPECT_NEAR(p[j], middle(m)[j], 1e-12) << "starts where the arm stands";
    EXPECT_NEAR(v[j], 0, 1e-12) << "at rest";
  }
  for (const auto& pt : r.points) {
    plan->motion.sample(pt.time, p, v, a);
    for (std::size_t i = 0; i < pt.positions.size(); ++i) EXPECT_NEAR(p[i], pt.positions[i], 1e-9) << pt.time;
  }
  plan->motion.sample(10.0, p, v, a);
  for (double x : v) EXPECT_NEAR(x, 0, 1e-12) << "ends at rest";
  // The gripper, not named, holds.
  const std::size_t g = std::size_t(m.joint_count() - 1);
  for (double t = 0; t <= 10; t += 0.25) {
    plan->motion.sample(t, p, v, a);
    EXPECT_DOUBLE_EQ(p[g], middle(m)[g]);
    for (std::size_t j = 0; j < p.size(); ++j) {
      EXPECT_LE(std::abs(v[j]), m.joints[j].limits.velocity);
      EXPECT_LE(std::abs(a[j]), m.joints[j].limits.acceleration);
    }
  }
  EXPECT_EQ(plan->target[0], r.points.back().positions[0]);
}

TEST_P(TrajectoryGoal, AFirstPointAtZeroMustBeWhereTheArmStands) {
  const auto m = model(GetParam());
  auto r = five_points(m);
  r.points.insert(r.points.begin(), point_at(m, 0, 0.0));
  EXPECT_TRUE(plan_trajectory(m, middle(m), r).ok());
  r.points.front() = point_at(m, 0, 0.3);
  const auto e = refusal(m, r);
  EXPECT_EQ(e.code, GoalError::invalid_goal);
  EXPECT_THAT(e.message, HasSubstr("where the arm stands"));
}

TEST_P(TrajectoryGoal, UnknownMissingAndRepeatedJointsAreRefused) {
  const auto m = model(GetParam());
  auto r = five_points(m);
  r.joint_names[1] = "elbow_of_someone_else";
  auto e = refusal(m, r);
  EXPECT_EQ(e.code, GoalError::invalid_joints);
  EXPECT_THAT(e.message, HasSubstr("unknown joint 'elbow_of_someone_else'"));
  EXPECT_THAT(e.message, HasSubstr(m.joints[0].name));  // says which are allowed

  r = five_points(m);
  r.joint_names.pop_back();
  for (auto& p : r.points) p.positions.pop_back();
  e = refusal(m, r);
  EXPECT_EQ(e.code, GoalError::invalid_joints);
  EXPECT_THAT(e.message, HasSubstr("leaves out joint(s) " + m.joints[std::size_t(m.chain_joints() - 1)].name));

  r = five_points(m);
  r.joint_names[1] = r.joint_names[0];
  EXPECT_THAT(refusal(m, r).message, HasSubstr("named twice"));

  r = five_points(m);
  r.joint_names.clear();
  EXPECT_EQ(refusal(m, r).code, GoalError::invalid_joints);
}

TEST_P(TrajectoryGoal, PointsBeyondALimitAreRefusedNamingTheJoint) {
  const auto m = model(GetParam());
  auto r = five_points(m);
  r.points[2].positions[1] = m.joints[1].limits.upper + 0.01;
  const auto e = refusal(m, r);
  EXPECT_EQ(e.code, GoalError::invalid_goal);
  EXPECT_THAT(e.message, HasSubstr("point 2"));
  EXPECT_THAT(e.message, HasSubstr("joint " + m.joints[1].name));
  EXPECT_THAT(e.message, HasSubstr("beyond its limits"));
}

TEST_P(TrajectoryGoal, TimesMustBeFiniteNonNegativeAndRising) {
  const auto m = model(GetParam());
  auto r = five_points(m);
  r.points[3].time = r.points[2].time;
  auto e = refusal(m, r);
  EXPECT_THAT(e.message, HasSubstr("times must rise"));
  EXPECT_THAT(e.message, HasSubstr("point 3"));

  r = five_points(m);
  r.points[0].time = -1;
  EXPECT_THAT(refusal(m, r).message, HasSubstr("negative"));

  r = five_points(m);
  r.points[1].time = std::nan("");
  EXPECT_THAT(refusal(m, r).message, HasSubstr("not finite"));

  r = five_points(m);
  r.points.back().time = 1e277;  // found by fuzz_trajectory_goal: the polynomials lost precision
  EXPECT_THAT(refusal(m, r).message, HasSubstr("beyond the longest trajectory, 3600 s"));
}

TEST_P(TrajectoryGoal, EmptyNanWrongSizesAndEffortAreRefused) {
  const auto m = model(GetParam());
  auto r = five_points(m);
  r.points.clear();
  EXPECT_THAT(refusal(m, r).message, HasSubstr("no points"));

  r = five_points(m);
  r.points[1].positions[0] = std::nan("");
  EXPECT_THAT(refusal(m, r).message, HasSubstr("not finite"));

  r = five_points(m);
  r.points[1].positions.pop_back();
  EXPECT_THAT(refusal(m, r).message, HasSubstr("positions for"));

  r = five_points(m);
  r.points[1].velocities.assign(2, 0.0);
  EXPECT_THAT(refusal(m, r).message, HasSubstr("velocities for"));

  r = five_points(m);
  r.points[1].effort.assign(r.joint_names.size(), 1.0);
  EXPECT_THAT(refusal(m, r).message, HasSubstr("effort"));

  r = five_points(m);
  for (auto& p : r.points) p.velocities.assign(r.joint_names.size(), 0.0);
  r.points.back().velocities[0] = 0.1;
  EXPECT_THAT(refusal(m, r).message, HasSubstr("last velocities must be 0"));
}

TEST_P(TrajectoryGoal, TooFastIsRefusedWithTheLimit) {
  const auto m = model(GetParam());
  TrajectoryRequest r;
  r.joint_names = chain_names(m);
  r.points.push_back(point_at(m, 0.05, 0.8));  // most of the range in 50 ms
  const auto e = refusal(m, r);
  EXPECT_EQ(e.code, GoalError::invalid_goal);
  EXPECT_THAT(e.message, ::testing::AnyOf(HasSubstr("velocity limit"), HasSubstr("acceleration limit")));
  EXPECT_THAT(e.message, HasSubstr("give the points more time"));
}

TEST_P(TrajectoryGoal, GivenVelocitiesAndAccelerationsAreFollowed) {
  const auto m = model(GetParam());
  auto r = five_points(m);
  for (std::size_t k = 0; k < r.points.size(); ++k) {
    r.points[k].velocities.assign(r.joint_names.size(), k + 1 < r.points.size() ? 0.01 : 0.0);
    r.points[k].accelerations.assign(r.joint_names.size(), 0.0);
  }
  auto plan = plan_trajectory(m, middle(m), r);
  ASSERT_TRUE(plan.ok()) << plan.error().message;
  std::vector<double> p, v, a;
  plan->motion.sample(r.points[1].time, p, v, a);
  EXPECT_NEAR(v[0], 0.01, 1e-9);
  EXPECT_NEAR(a[0], 0.0, 1e-9);
}

TEST_P(TrajectoryGoal, TolerancesAreMappedByName) {
  const auto m = model(GetParam());
  const auto names = chain_names(m);
  auto t = map_tolerances(m, names, {{names[1], 0.05}}, {{names[0], -1}}, 0.5);
  ASSERT_TRUE(t.ok()) << t.error().message;
  EXPECT_EQ(t->path[1], 0.05);
  EXPECT_FALSE(t->path[0].has_value());
  EXPECT_TRUE(std::isinf(*t->goal[0]));
  EXPECT_EQ(t->goal_time, 0.5);
  auto bad = map_tolerances(m, names, {{"nope", 0.1}}, {}, 0);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(refusal_of(bad.error()).code, GoalError::invalid_joints);
  EXPECT_FALSE(map_tolerances(m, names, {}, {}, -1).ok());
  // A tolerance for a name the trajectory gives but the arm does not have (found by
  // fuzz_trajectory_goal: it was looked up without a check).
  auto unknown = names;
  unknown[0] = "nope";
  auto e = map_tolerances(m, unknown, {{"nope", 0.1}}, {}, 0);
  ASSERT_FALSE(e.ok());
  EXPECT_EQ(refusal_of(e.error()).code, GoalError::invalid_joints);
  EXPECT_THAT(e.error().message, HasSubstr("unknown joint 'nope'"));
}

INSTANTIATE_TEST_SUITE_P(BothArms, TrajectoryGoal, ::testing::Values("xarm", "scara"));

}  // namespace
}  // namespace armctl::ros_node
