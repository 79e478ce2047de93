// The planner checks every motion against the arm's collision world before anything moves
// (docs/scene.md): on both arms, a PTP or a LIN into the table or a box is refused with the
// two bodies, the move, how far into it and the tool point (a typed detail, not only text);
// a motion that stays clear is planned with its smallest clearance; without a scene the arm
// still never plans into itself.
#include <fmt/core.h>
#include <gtest/gtest.h>

#include "arm/arm_kinematics.hpp"
#include "arm/plan_moves.hpp"
#include "scene/scene.hpp"

namespace armctl::arm {
namespace {

struct Arm {
  std::shared_ptr<const ArmKinematics> plain, with_scene;
  std::vector<double> start;
};

// The arm on a table (top at z 0, the base plate on it) with a box (mm) in front.
Arm arm_on_table(const char* name, const Eigen::Vector3d& box_at, const Eigen::Vector3d& box_size) {
  Arm a;
  a.plain = std::make_shared<const ArmKinematics>(load_arm_model(arm_file_path(name)).value());
  scene::Scene s = scene::parse_scene(fmt::format(R"({{"objects": [{{"name": "desk", "table": {{"top": 0}}}},
      {{"name": "box", "box": [{}, {}, {}], "at": [{}, {}, {}]}}]}})",
                                                  box_size.x(), box_size.y(), box_size.z(), box_at.x(), box_at.y(), box_at.z()),
                                      "scene")
                      .value();
  a.with_scene = a.plain->with_scene(s).value();
  a.start.assign(std::size_t(a.plain->joint_count()), 0.0);
  return a;
}

Move ptp_to(double x, double y, double z) {
  PtpMove p;
  CartesianGoal g;
  g.position = Eigen::Vector3d(x, y, z) / 1000;
  p.target = g;
  return Move{p, "line 7 (PTP)", 7};
}

Move lin_to(double x, double y, double z) {
  CartesianMove c;
  c.goal.position = Eigen::Vector3d(x, y, z) / 1000;
  return Move{c, "line 9 (LIN)", 9};
}

TEST(PlanCollisions, XarmPtpIntoTheBoxIsRefusedWithBothBodiesAndWhere) {
  const Arm a = arm_on_table("xarm", {170, 0, 50}, {60, 80, 100});
  const std::vector<Move> moves{ptp_to(170, 0, 60)};
  // Without the scene the same target plans: the box is what refuses it.
  ASSERT_TRUE(plan_moves(*a.plain, a.start, moves).ok());
  MoveRefusal refused;
  auto plan = plan_moves(*a.with_scene, a.start, moves, {}, &refused);
  ASSERT_FALSE(plan.ok());
  EXPECT_EQ(plan.error().kind, ErrorKind::invalid_argument);
  const auto* d = plan.error().detail_as<CollisionDetail>();
  ASSERT_NE(d, nullptr) << plan.error().message;
  EXPECT_EQ(d->contact.second, "box 'box'");
  EXPECT_EQ(d->line, 7u);
  EXPECT_GT(d->fraction, 0.0);
  EXPECT_LE(d->fraction, 1.0);
  EXPECT_GT(d->contact.depth, 0.0);
  EXPECT_LT(d->contact.depth, 0.002);  // found within the 2 mm resolution of first contact
  EXPECT_EQ(plan.error().message.rfind("would collide", 0), 0u) << plan.error().message;
  EXPECT_NE(plan.error().message.find("with box 'box'"), std::string::npos) << plan.error().message;
}

TEST(PlanCollisions, ScaraLinDownIntoABoxIsRefusedWhereTheToolMeetsIt) {
  // The SCARA's tool reaches down to 200 mm above its base (Z at 0): a box whose top is at
  // 260 mm stands under the stretched-out arm's tool.
  const Arm a = arm_on_table("scara", {685, 0, 230}, {60, 60, 60});
  std::vector<double> start = a.start;
  start[0] = 0.15;  // Z: the tool 350 mm up
  const Eigen::Vector3d here = a.plain->pose_at(start).position * 1000;
  const std::vector<Move> moves{lin_to(here.x(), here.y(), 210)};
  ASSERT_TRUE(plan_moves(*a.plain, start, moves).ok());
  auto plan = plan_moves(*a.with_scene, start, moves);
  ASSERT_FALSE(plan.ok());
  const auto* d = plan.error().detail_as<CollisionDetail>();
  ASSERT_NE(d, nullptr) << plan.error().message;
  EXPECT_EQ(d->contact.second, "box 'box'");
  EXPECT_EQ(d->line, 9u);
  // Refused where the tool meets the box, not at the target: the gripper's fingers reach
  // 15 mm beyond the tool point.
  EXPECT_GT(d->tool_point.z(), 0.26 - 0.02);
  EXPECT_LT(d->tool_point.z(), 0.26 + 0.02);
  EXPECT_GT(d->fraction, 0.3);
  EXPECT_LT(d->fraction, 0.9);
}

TEST(PlanCollisions, AMotionThatStaysClearReportsItsSmallestClearance) {
  const Arm a = arm_on_table("xarm", {170, 0, 50}, {60, 80, 100});
  auto plan = plan_moves(*a.with_scene, a.start, std::vector<Move>{ptp_to(120, 120, 120)});
  ASSERT_TRUE(plan.ok()) << plan.error().message;
  ASSERT_TRUE(plan->clearance.has_value());
  EXPECT_GT(plan->clearance->distance, 0.0);
  EXPECT_LE(plan->clearance->distance, scene::kClearanceHorizon);
}

TEST(PlanCollisions, WithoutASceneTheArmStillNeverPlansIntoItself) {
  const Arm a = arm_on_table("xarm", {170, 0, 50}, {60, 80, 100});
  // The fingers down into the base plate.
  auto plan = plan_moves(*a.plain, a.start, std::vector<Move>{ptp_to(60, 0, 10)});
  ASSERT_FALSE(plan.ok());
  const auto* d = plan.error().detail_as<CollisionDetail>();
  ASSERT_NE(d, nullptr) << plan.error().message;
  EXPECT_EQ(d->contact.first, "link 'base_link'");
}

TEST(PlanCollisions, AnArmThatStartsInContactMayMoveOutAndIsTold) {
  const Arm a = arm_on_table("xarm", {170, 0, 50}, {60, 80, 100});
  // Where the fingers first touch the base plate on the way down.
  auto into = plan_moves(*a.plain, a.start, std::vector<Move>{ptp_to(60, 0, 10)});
  ASSERT_FALSE(into.ok());
  const auto* d = into.error().detail_as<CollisionDetail>();
  ASSERT_NE(d, nullptr);
  // From there, back to zero: planned, the touching pair named in the note.
  PtpMove back;
  back.target = std::vector<std::optional<double>>(a.start.begin(), a.start.end());
  auto out = plan_moves(*a.plain, d->joints, std::vector<Move>{Move{back, "line 3 (PTP)", 3}});
  ASSERT_TRUE(out.ok()) << out.error().message;
  EXPECT_NE(out->notes().find("starts where link 'base_link' with link 'gripper_finger' already touch"), std::string::npos)
      << out->notes();
  // Deeper into the plate from there is still refused: other pairs (the hand) are checked.
  auto deeper = plan_moves(*a.plain, d->joints, std::vector<Move>{ptp_to(60, 0, -20)});
  EXPECT_FALSE(deeper.ok());
}

TEST(PlanCollisions, AHeldPartIsCheckedWithTheTool) {
  const ArmKinematics plain(load_arm_model(arm_file_path("xarm")).value());
  // A ball 80 mm across held at the tool point: the move that clears the desk with the bare
  // tool (30 mm above it) puts the ball 10 mm into it.
  const auto scene = scene::parse_scene(R"({"objects": [{"name": "desk", "table": {"top": 0}},
      {"name": "ball", "attached": "tool", "sphere": {"radius": 40}, "at": [0, 0, 0]}]})",
                                        "scene")
                         .value();
  const scene::Scene desk_only{{scene.objects[0]}, {}};
  const std::vector<double> start(std::size_t(plain.joint_count()), 0.0);
  const std::vector<Move> moves{ptp_to(200, 0, 30)};
  auto bare = plan_moves(*plain.with_scene(desk_only).value(), start, moves);
  ASSERT_TRUE(bare.ok()) << bare.error().message;
  auto held = plan_moves(*plain.with_scene(scene).value(), start, moves);
  ASSERT_FALSE(held.ok());
  const auto* d = held.error().detail_as<CollisionDetail>();
  ASSERT_NE(d, nullptr) << held.error().message;
  EXPECT_EQ(d->contact.first + " " + d->contact.second, "the table 'desk' held sphere 'ball'");
}

}  // namespace
}  // namespace armctl::arm
