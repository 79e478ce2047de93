// The fence and reduced mode end to end on both simulated arms (docs/scene.md "Fence and
// reduced mode"): a move out of the fence is refused before anything moves and runs once the
// fence is switched off; a fence switched on while the arm moves stops it on its path
// before it leaves; in reduced mode a LIN is timed under the tool speed cap (measured from
// the plan's samples) and runs to its end. On simulated time.
#include <gtest/gtest.h>

#include <fmt/core.h>

#include <numbers>

#include "arm/plan_moves.hpp"
#include "arm/run_motion.hpp"
#include "scene/scene.hpp"
#include "simulated_arms.hpp"

namespace armctl::arm {
namespace {

using XarmFence = testing::XarmOnEmulator;
using ScaraFence = testing::ScaraOnBus;

constexpr double kDeg = std::numbers::pi / 180;
constexpr std::size_t kXarmBase = 0, kScaraShoulder = 1;

// A turn of `joint` by `degrees` as line 5 of a file.
Plan turn(Arm& arm, std::size_t joint, double degrees) { return testing::turn(arm, joint, degrees * kDeg, 5); }

// A fence around where the tool passes in the first `until` (0..1) of the plan's first
// motion, `margin` m wider each way.
scene::Scene fence_around(const Arm& arm, const Plan& plan, double until, double margin, bool on) {
  const auto& m = plan.pieces.at(0).motion;
  std::vector<double> q(plan.start.size()), v(q.size()), a(q.size());
  Eigen::Vector3d low = Eigen::Vector3d::Constant(1e9), high = -low;
  for (int s = 0; s <= 100; ++s) {
    m.sample(until * m.duration * s / 100, q, v, a);
    const Eigen::Vector3d p = arm.kinematics()->pose_at(q).position;
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  scene::Scene out;
  out.fence = scene::Fence{low - Eigen::Vector3d::Constant(margin), high + Eigen::Vector3d::Constant(margin), false, on};
  return out;
}

bool inside(const scene::Fence& f, const Eigen::Vector3d& p, double slack) {
  return ((f.low.array() - slack) <= p.array()).all() && (p.array() <= (f.high.array() + slack)).all();
}

void refused_then_allowed(Arm& arm, std::size_t joint, double degrees) {
  const Plan plan = turn(arm, joint, degrees);
  ASSERT_TRUE(arm.set_scene(fence_around(arm, plan, 0.4, 0.005, true)));
  const std::vector<double> before = arm.read().value().positions;
  std::vector<std::optional<double>> targets(before.size());
  targets[joint] = before[joint] + degrees * kDeg;
  const Status moved = arm.move_joints(targets);
  ASSERT_FALSE(moved.ok());
  const auto* d = moved.error().detail_as<CollisionDetail>();
  ASSERT_NE(d, nullptr) << moved.error().message;
  EXPECT_EQ(d->contact.limit, scene::Limit::fence);
  EXPECT_FALSE(d->while_moving);
  EXPECT_GT(d->fraction, 0.3);
  EXPECT_LT(d->fraction, 0.8);
  // Nothing moved.
  const std::vector<double> after = arm.read().value().positions;
  for (std::size_t i = 0; i < before.size(); ++i) EXPECT_NEAR(after[i], before[i], 0.5 * kDeg) << i;
  // Switched off, the same move runs.
  ASSERT_TRUE(arm.set_fence(false));
  ASSERT_TRUE(arm.move_joints(targets));
  auto arrived = arm.wait();
  ASSERT_TRUE(arrived.ok()) << arrived.error().message;
  EXPECT_NEAR(arrived->positions[joint], before[joint] + degrees * kDeg, 1 * kDeg);
}

void stopped_when_switched_on_while_moving(Arm& arm, std::size_t joint, double degrees) {
  const Plan plan = turn(arm, joint, degrees);
  const scene::Scene fenced = fence_around(arm, plan, 0.6, 0.005, false);
  ASSERT_TRUE(arm.set_scene(fenced));
  bool switched = false;
  std::vector<std::vector<double>> reads;
  RunHooks hooks;
  hooks.executor.on_point = [&](const MotionProgress& p) {
    if (!switched && p.t >= 0.15 * p.duration) switched = arm.set_fence(true).ok();
  };
  hooks.executor.on_read = [&](const JointState& s) { reads.push_back(s.positions); };
  auto run = run_motion(arm, plan, hooks);
  ASSERT_TRUE(switched);
  ASSERT_FALSE(run.ok()) << "the motion left the fence";
  const auto* d = run.error().detail_as<CollisionDetail>();
  ASSERT_NE(d, nullptr) << run.error().message;
  EXPECT_EQ(d->contact.limit, scene::Limit::fence);
  EXPECT_TRUE(d->while_moving);
  EXPECT_EQ(d->line, 5u);
  EXPECT_NE(run.error().message.find("stopped before leaving the fence"), std::string::npos) << run.error().message;
  // Never out: at no read on the way (the check's 2 mm and the servos' rounding), nor at rest.
  const auto k = arm.kinematics();
  for (const auto& q : reads) EXPECT_TRUE(inside(*fenced.fence, k->pose_at(q).position, 0.004));
  auto rest = arm.wait();
  ASSERT_TRUE(rest.ok()) << rest.error().message;
  EXPECT_TRUE(inside(*fenced.fence, k->pose_at(rest->positions).position, 0.004));
}

// The tool point's largest speed along the plan's motions (finite differences 1 ms apart).
double sampled_peak(const ArmKinematics& k, const Plan& plan) {
  double peak = 0;
  std::vector<double> q(plan.start.size()), v(q.size()), a(q.size());
  for (const PlannedPiece& p : plan.pieces) {
    if (p.kind != PieceKind::motion) continue;
    p.motion.sample(0, q, v, a);
    Eigen::Vector3d before = k.pose_at(q).position;
    for (double t = 0.001; t < p.motion.duration + 0.001; t += 0.001) {
      p.motion.sample(std::min(t, p.motion.duration), q, v, a);
      const Eigen::Vector3d here = k.pose_at(q).position;
      peak = std::max(peak, (here - before).norm() / 0.001);
      before = here;
    }
  }
  return peak;
}

void lin_under_the_cap(Arm& arm) {
  ASSERT_TRUE(arm.set_scene(scene::parse_scene(R"({"reduced": {"tool_speed": 20}})", "scene").value()));
  const std::vector<double> from = arm.read().value().positions;
  CartesianMove lin;
  lin.goal.position = arm.kinematics()->pose_at(from).position + Eigen::Vector3d(0, 0, -0.04);
  lin.speed = 0.1;
  const std::vector<Move> moves{Move{lin, "line 8 (LIN)", 8}};
  auto plan = plan_moves(*arm.kinematics(), from, moves);
  ASSERT_TRUE(plan.ok()) << plan.error().message;
  EXPECT_LE(sampled_peak(*arm.kinematics(), *plan), 0.02 * 1.01);
  EXPECT_GE(plan->duration, 0.04 / 0.02);
  auto run = run_motion(arm, *plan, {});
  ASSERT_TRUE(run.ok()) << run.error().message;
  EXPECT_TRUE(run->completed);
  // Off: the line back at its own 100 mm/s (the joints' limits allowing).
  const Status off = arm.set_reduced_mode(false);
  ASSERT_TRUE(off.ok()) << off.error().message;
  lin.goal.position = arm.kinematics()->pose_at(from).position;
  auto fast = plan_moves(*arm.kinematics(), arm.read().value().positions, std::vector<Move>{Move{lin, "line 9 (LIN)", 9}});
  ASSERT_TRUE(fast.ok()) << fast.error().message;
  EXPECT_GT(sampled_peak(*arm.kinematics(), *fast), 2 * 0.02);
}

void bend_xarm(Arm& arm) {
  CartesianGoal g;
  g.position = {0.18, 0.0, 0.12};
  ASSERT_TRUE(arm.move_to(g));
  ASSERT_TRUE(arm.wait());
}

void bend_scara(Arm& arm) {
  // Z 150 mm, the elbow and the wrist bent: away from its singular straight-out start.
  ASSERT_TRUE(arm.move_joints({0.15, 0.3, 0.6, 0.0, 0.5, 0.0, std::nullopt}));
  ASSERT_TRUE(arm.wait());
}

TEST_F(XarmFence, AMoveOutOfTheFenceIsRefusedBeforeAnythingMovesAndRunsOnceItIsOff) {
  bend_xarm(arm);
  refused_then_allowed(arm, kXarmBase, 90);
}

TEST_F(ScaraFence, AMoveOutOfTheFenceIsRefusedBeforeAnythingMovesAndRunsOnceItIsOff) {
  refused_then_allowed(arm, kScaraShoulder, 60);
}

TEST_F(XarmFence, AFenceSwitchedOnWhileMovingStopsTheArmInsideIt) {
  bend_xarm(arm);
  stopped_when_switched_on_while_moving(arm, kXarmBase, 90);
}

TEST_F(ScaraFence, AFenceSwitchedOnWhileMovingStopsTheArmInsideIt) {
  stopped_when_switched_on_while_moving(arm, kScaraShoulder, 60);
}

TEST_F(XarmFence, ReducedModeRunsALinUnderItsToolSpeedCap) {
  bend_xarm(arm);
  lin_under_the_cap(arm);
}

TEST_F(ScaraFence, ReducedModeRunsALinUnderItsToolSpeedCap) {
  bend_scara(arm);
  lin_under_the_cap(arm);
}

}  // namespace
}  // namespace armctl::arm
