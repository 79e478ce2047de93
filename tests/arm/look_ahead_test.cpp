// The executor's look-ahead (arm/motion_executor.hpp): a box put in the arm's way after the
// motion was planned (from the dashboard, ROS or Python while the arm moves) stops the
// motion on its path before contact, naming the two bodies and the move; a box beside the
// path stops nothing. On simulated time, on both simulated arms.
#include <gtest/gtest.h>

#include <fmt/core.h>

#include <cmath>
#include <numbers>

#include "arm/plan_moves.hpp"
#include "arm/run_motion.hpp"
#include "scene/scene.hpp"
#include "simulated_arms.hpp"

namespace armctl::arm {
namespace {

using XarmLookAhead = testing::XarmOnEmulator;
using ScaraLookAhead = testing::ScaraOnBus;

constexpr double kDeg = std::numbers::pi / 180;

// A turn of `joint` by `degrees` as line 3 of a file.
Plan turn(Arm& arm, std::size_t joint, double degrees) { return testing::turn(arm, joint, degrees * kDeg, 3); }

// The tool point (mm) at `fraction` of the plan's first motion.
Eigen::Vector3d tool_at(const Arm& arm, const Plan& plan, double fraction) {
  const auto& m = plan.pieces.at(0).motion;
  std::vector<double> q(plan.start.size()), v(q.size()), a(q.size());
  m.sample(fraction * m.duration, q, v, a);
  return arm.kinematics()->pose_at(q).position * 1e3;
}

scene::Scene cube_at(const Eigen::Vector3d& mm, double side) {
  return scene::parse_scene(fmt::format(R"({{"objects": [{{"name": "box", "box": [{0}, {0}, {0}], "at": [{1:.1f}, {2:.1f}, {3:.1f}]}}]}})",
                                        side, mm.x(), mm.y(), mm.z()),
                            "scene")
      .value();
}

// Runs `plan`; once the arm is `when` (0..1) into it, the scene becomes `later`. Every
// position read back on the way is kept.
struct Outcome {
  Result<RunReport> run;
  std::vector<std::vector<double>> reads;
};
Outcome run_with_scene_change(Arm& arm, const Plan& plan, double when, const scene::Scene& later) {
  Outcome out{Error{ErrorKind::io, "not run"}, {}};
  bool changed = false;
  RunHooks hooks;
  hooks.executor.on_point = [&](const MotionProgress& p) {
    if (!changed && p.t >= when * p.duration) {
      changed = true;
      ASSERT_TRUE(arm.set_scene(later));
    }
  };
  hooks.executor.on_read = [&](const JointState& s) { out.reads.push_back(s.positions); };
  out.run = run_motion(arm, plan, hooks);
  EXPECT_TRUE(changed);
  return out;
}

void expect_stopped_before_the_box(Arm& arm, const Plan& plan, const Outcome& out, double box_at, std::size_t joint) {
  ASSERT_FALSE(out.run.ok()) << "the motion ran into the box";
  const Error& e = out.run.error();
  EXPECT_EQ(e.kind, ErrorKind::invalid_argument);
  const auto* d = e.detail_as<CollisionDetail>();
  ASSERT_NE(d, nullptr) << e.message;
  EXPECT_TRUE(d->while_moving);
  EXPECT_EQ(d->contact.second, "box 'box'") << e.message;
  EXPECT_EQ(d->line, 3u);  // the move it was in
  EXPECT_LT(d->fraction, box_at);
  EXPECT_LT(d->stopped_at, d->fraction);
  EXPECT_NE(e.message.find("stopped before a collision"), std::string::npos) << e.message;
  EXPECT_NE(e.message.find("is at rest on the path"), std::string::npos) << e.message;
  // Never touched: not at any read on the way, not where it rests.
  const auto world = arm.kinematics()->collisions();
  for (const auto& q : out.reads) EXPECT_FALSE(world->contact(q).has_value());
  auto rest = arm.wait();
  ASSERT_TRUE(rest.ok()) << rest.error().message;
  EXPECT_FALSE(world->contact(rest->positions).has_value());
  // On the path: only the turning joint moved.
  const auto& start = plan.start;
  for (std::size_t i = 0; i < start.size(); ++i) {
    if (i == joint) continue;
    EXPECT_NEAR(rest->positions[i], start[i], 1 * kDeg) << i;
  }
}

// The xArm bent forward (straight up, its tool stays on the base's axis) and turning its
// base; the SCARA turning its shoulder at full reach.
constexpr std::size_t kXarmBase = 0, kScaraShoulder = 1;
void bend_forward(Arm& arm) {
  CartesianGoal g;
  g.position = {0.18, 0.0, 0.12};
  ASSERT_TRUE(arm.move_to(g));
  ASSERT_TRUE(arm.wait());
}

TEST_F(XarmLookAhead, ABoxPutInTheWayWhileMovingStopsTheArmBeforeIt) {
  bend_forward(arm);
  const Plan plan = turn(arm, kXarmBase, 90);
  const Outcome out = run_with_scene_change(arm, plan, 0.15, cube_at(tool_at(arm, plan, 0.7), 40));
  expect_stopped_before_the_box(arm, plan, out, 0.7, kXarmBase);
}

TEST_F(ScaraLookAhead, ABoxPutInTheWayWhileMovingStopsTheArmBeforeIt) {
  const Plan plan = turn(arm, kScaraShoulder, 60);
  const Outcome out = run_with_scene_change(arm, plan, 0.15, cube_at(tool_at(arm, plan, 0.7), 40));
  expect_stopped_before_the_box(arm, plan, out, 0.7, kScaraShoulder);
}

TEST_F(XarmLookAhead, ABoxBesideThePathStopsNothing) {
  bend_forward(arm);
  const Plan plan = turn(arm, kXarmBase, 90);
  // Where the tool passes, but 150 mm higher.
  const Outcome out = run_with_scene_change(arm, plan, 0.15,
                                            cube_at(tool_at(arm, plan, 0.7) + Eigen::Vector3d(0, 0, 150), 40));
  ASSERT_TRUE(out.run.ok()) << out.run.error().message;
  EXPECT_TRUE(out.run->completed);
}

TEST_F(XarmLookAhead, WithoutTheLookAheadTheSameMotionRunsOn) {
  // The option is what stops it: off, the arm runs through (the simulator has no scene).
  bend_forward(arm);
  const Plan plan = turn(arm, kXarmBase, 90);
  bool changed = false;
  RunHooks hooks;
  hooks.executor.look_ahead = Duration{0};
  const scene::Scene later = cube_at(tool_at(arm, plan, 0.7), 40);
  hooks.executor.on_point = [&](const MotionProgress& p) {
    if (!changed && p.t >= 0.15 * p.duration) changed = arm.set_scene(later).ok();
  };
  auto run = run_motion(arm, plan, hooks);
  ASSERT_TRUE(changed);
  ASSERT_TRUE(run.ok()) << run.error().message;
  EXPECT_TRUE(run->completed);
}

}  // namespace
}  // namespace armctl::arm
