// Around obstacles (docs/scene.md): where the direct PTP collides, a path through
// collision-free waypoints that the planner accepts and that ends at the target, the same for
// the same request; a target walled off from the arm is refused within the time budget; a
// target where the arm itself would touch is refused at once.
#include <chrono>
#include <cstdio>

#include <fmt/core.h>
#include <gtest/gtest.h>

#include "arm/arm_kinematics.hpp"
#include "arm/avoid_path.hpp"
#include "arm/plan_moves.hpp"
#include "scene/motion_check.hpp"
#include "scene/scene.hpp"

namespace armctl::arm {
namespace {

std::shared_ptr<const ArmKinematics> arm_in(const char* name, const std::string& scene_json) {
  const ArmKinematics plain(load_arm_model(arm_file_path(name)).value());
  return plain.with_scene(scene::parse_scene(scene_json, "scene").value()).value();
}

std::shared_ptr<const ArmKinematics> xarm_on_the_desk() {
  const ArmKinematics plain(load_arm_model(arm_file_path("xarm")).value());
  return plain.with_scene(scene::load_scene(std::string(ARMCTL_SOURCE_DIR) + "/examples/scenes/xarm-desk.json").value())
      .value();
}

// The tests' budget: the sanitizer build on a shared machine is slow, and the path must not
// depend on how busy it is (a search cut short finds nothing rather than another path).
AvoidOptions generous() {
  AvoidOptions o;
  o.time_budget = 10;
  return o;
}

PtpMove ptp_to(double x, double y, double z) {
  PtpMove p;
  CartesianGoal g;
  g.position = Eigen::Vector3d(x, y, z) / 1000;
  p.target = g;
  return p;
}

PtpMove ptp_to_joints(const std::vector<double>& q) {
  PtpMove p;
  p.target = std::vector<std::optional<double>>(q.begin(), q.end());
  return p;
}

TEST(AvoidPath, XarmBehindTheBoxGoesAroundItAndEndsAtTheTarget) {
  const auto kin = xarm_on_the_desk();
  const std::vector<double> start(std::size_t(kin->joint_count()), 0.0);
  const PtpMove direct = ptp_to(150, -190, 40);
  auto refused = plan_moves(*kin, start, std::vector<Move>{Move{direct}});
  ASSERT_FALSE(refused.ok());
  ASSERT_NE(refused.error().detail_as<CollisionDetail>(), nullptr) << refused.error().message;

  auto around = avoiding_move(*kin, start, direct, generous());
  ASSERT_TRUE(around.ok()) << around.error().message;
  EXPECT_TRUE(around->avoided);
  EXPECT_GE(around->waypoints, 1u);
  EXPECT_EQ(around->waypoints, around->move.waypoints.size());
  EXPECT_GT(around->planning_s, 0.0);
  std::printf("xarm behind the box: %zu waypoints, %.0f ms\n", around->waypoints, around->planning_s * 1e3);
  auto plan = plan_moves(*kin, start, std::vector<Move>{Move{around->move}});
  ASSERT_TRUE(plan.ok()) << plan.error().message;
  ASSERT_TRUE(plan->clearance.has_value());
  EXPECT_GT(plan->clearance->distance, 0.0);
  EXPECT_LT((kin->pose_at(plan->end()).position - Eigen::Vector3d(0.15, -0.19, 0.04)).norm(), 1e-4);

  // The same request, the same path (the seed is fixed).
  auto again = avoiding_move(*kin, start, direct, generous());
  ASSERT_TRUE(again.ok()) << again.error().message;
  EXPECT_EQ(again->move.waypoints, around->move.waypoints);
}

TEST(AvoidPath, AClearMoveIsLeftAsItIs) {
  const auto kin = xarm_on_the_desk();
  const std::vector<double> start(std::size_t(kin->joint_count()), 0.0);
  auto same = avoiding_move(*kin, start, ptp_to(150, -100, 130));
  ASSERT_TRUE(same.ok()) << same.error().message;
  EXPECT_FALSE(same->avoided);
  EXPECT_TRUE(same->move.waypoints.empty());
}

TEST(AvoidPath, TheWaypointsAloneAreCollisionFreeLines) {
  const auto kin = xarm_on_the_desk();
  const std::vector<double> start(std::size_t(kin->joint_count()), 0.0);
  const std::vector<double> target = kin->nearest_joints(std::get<CartesianGoal>(ptp_to(150, -190, 40).target), start).value();
  auto path = collision_free_waypoints(*kin, start, target, generous());
  ASSERT_TRUE(path.ok()) << path.error().message;
  std::vector<std::vector<double>> points{start};
  points.insert(points.end(), path->waypoints.begin(), path->waypoints.end());
  points.push_back(target);
  const auto& world = *kin->collisions();
  for (std::size_t k = 0; k + 1 < points.size(); ++k) {
    const auto check = scene::check_motion(world, 1.0, [&](double t, std::vector<double>& q) {
      q.resize(start.size());
      for (std::size_t j = 0; j < q.size(); ++j) q[j] = points[k][j] + t * (points[k + 1][j] - points[k][j]);
    });
    EXPECT_FALSE(check.contact.has_value()) << "line " << k;
  }
}

TEST(AvoidPath, ScaraOverABoxInItsWay) {
  // A box 450 mm tall under the swinging arm: the direct swing at the bottom of Z runs the
  // forearm into it.
  const auto kin = arm_in("scara", R"({"objects": [{"name": "desk", "table": {"top": 0}},
      {"name": "box", "box": [80, 80, 450], "at": [283, 283, 225]}]})");
  std::vector<double> start(std::size_t(kin->joint_count()), 0.0), target = start;
  start[0] = target[0] = 0.05;
  target[1] = M_PI / 2;
  const PtpMove direct = ptp_to_joints(target);
  auto refused = plan_moves(*kin, start, std::vector<Move>{Move{direct}});
  ASSERT_FALSE(refused.ok());
  ASSERT_NE(refused.error().detail_as<CollisionDetail>(), nullptr) << refused.error().message;
  EXPECT_EQ(refused.error().detail_as<CollisionDetail>()->contact.second, "box 'box'");
  auto around = avoiding_move(*kin, start, direct, generous());
  ASSERT_TRUE(around.ok()) << around.error().message;
  EXPECT_TRUE(around->avoided);
  std::printf("scara over the box: %zu waypoints, %.0f ms\n", around->waypoints, around->planning_s * 1e3);
  auto plan = plan_moves(*kin, start, std::vector<Move>{Move{around->move}});
  ASSERT_TRUE(plan.ok()) << plan.error().message;
  for (std::size_t j = 0; j < target.size(); ++j) EXPECT_NEAR(plan->end()[j], target[j], 1e-9) << j;
}

TEST(AvoidPath, ATargetWalledOffIsRefusedWithinTheBudget) {
  // A floor-to-ceiling keep-out wall along +y, from just beyond the SCARA's column: the upper
  // arm cannot swing past it at any height, and the shoulder's limits (+-150 deg) do not let
  // it go round the other way. Both ends stand clear of it.
  const auto kin = arm_in("scara", R"({"objects": [
      {"name": "wall", "keep_out": true, "box": [10, 1000, 3000], "at": [0, 580, 1500]}]})");
  std::vector<double> start(std::size_t(kin->joint_count()), 0.0), target = start;
  start[0] = target[0] = 0.05;
  target[1] = 0.75 * M_PI;  // 135 deg: pointing back, on the wall's far side
  ASSERT_FALSE(kin->collisions()->collides(start));
  ASSERT_FALSE(kin->collisions()->collides(target));
  AvoidOptions options;
  options.time_budget = 0.3;
  const auto t0 = std::chrono::steady_clock::now();
  auto around = avoiding_move(*kin, start, ptp_to_joints(target), options);
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_FALSE(around.ok());
  EXPECT_EQ(around.error().kind, ErrorKind::invalid_argument);
  EXPECT_EQ(around.error().message, "no collision-free path found in 0.3 s");
  EXPECT_LT(took, 0.3 + 0.25);  // the budget, and the last check or simplification under way
}

TEST(AvoidPath, ATargetWhereTheArmTouchesIsRefusedAtOnce) {
  const auto kin = xarm_on_the_desk();
  const std::vector<double> start(std::size_t(kin->joint_count()), 0.0);
  auto into = avoiding_move(*kin, start, ptp_to(150, -100, 60));  // the hand in the box
  ASSERT_FALSE(into.ok());
  EXPECT_EQ(into.error().kind, ErrorKind::invalid_argument);
  EXPECT_NE(into.error().message.find("no collision-free path: at the target"), std::string::npos) << into.error().message;
  EXPECT_NE(into.error().message.find("box 'box'"), std::string::npos) << into.error().message;
}

}  // namespace
}  // namespace armctl::arm
