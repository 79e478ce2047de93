// The fence and reduced mode (docs/scene.md "Fence and reduced mode"), checked like
// collisions on both arms: the tool point inside, on the boundary and outside the fence;
// every link inside when asked; a PTP out of the fence and a joint move beyond a reduced
// range refused before anything moves with a typed detail (which limit, how far into the
// motion, the tool point); reduced mode's tool speed cap kept by a LIN and a PTP, measured
// from the plan's samples; each allowed again once switched off.
#include <fmt/core.h>
#include <gtest/gtest.h>

#include <fstream>
#include <numbers>
#include <sstream>

#include <nlohmann/json.hpp>

#include "arm/arm_kinematics.hpp"
#include "arm/plan_moves.hpp"
#include "arm/tool_speed.hpp"
#include "scene/scene.hpp"

namespace armctl::arm {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

// Per arm: where it starts (a pose that a LIN leaves), which joint a test turns, and a LIN
// from the start (mm).
struct ArmCase {
  const char* name;
  std::vector<double> start;
  std::size_t joint;
  Eigen::Vector3d lin_by;
};

ArmCase arm_case(const std::string& name) {
  if (name == "xarm") return {"xarm", {0.0, 0.5, 0.8, 0.6, 0.0, 0.0}, 1, {0, 0, -60}};
  return {"scara", {0.15, 0.3, 0.6, 0, 0.5, 0, 0}, 1, {0, 0, -100}};  // Z 150 mm, the elbow bent
}

class FenceAndReduced : public ::testing::TestWithParam<std::string> {
 protected:
  ArmCase arm = arm_case(GetParam());
  std::shared_ptr<const ArmKinematics> plain =
      std::make_shared<const ArmKinematics>(load_arm_model(arm_file_path(arm.name)).value());
  Eigen::Vector3d tool = plain->pose_at(arm.start).position;  // m

  std::shared_ptr<const ArmKinematics> with(const scene::Scene& s) const { return plain->with_scene(s).value(); }
  // A fence `below` .. `above` around the start's tool point (m).
  static scene::Scene fenced(const Eigen::Vector3d& low, const Eigen::Vector3d& high, bool links = false, bool on = true) {
    scene::Scene s;
    s.fence = scene::Fence{low, high, links, on};
    return s;
  }
  scene::Scene reduced(const std::string& json) const {
    return scene::parse_scene(fmt::format(R"({{"reduced": {}}})", json), "scene.json").value();
  }
  std::string joint_name() const { return plain->model().joints[arm.joint].name; }
  Move turn(double degrees) const {
    PtpMove p;
    std::vector<std::optional<double>> targets(arm.start.size());
    targets[arm.joint] = arm.start[arm.joint] + degrees * kDeg;
    p.target = targets;
    return Move{p, "line 4 (PTP)", 4};
  }
  Move lin() const {
    CartesianMove c;
    c.goal.position = tool + arm.lin_by / 1000;
    c.speed = 0.05;
    return Move{c, "line 6 (LIN)", 6};
  }
};

TEST_P(FenceAndReduced, ToolPointInsideOnTheBoundaryAndOutside) {
  const Eigen::Vector3d margin(0.05, 0.05, 0.05);
  EXPECT_FALSE(with(fenced(tool - margin, tool + margin))->collisions()->collides(arm.start));
  // On the face is inside.
  Eigen::Vector3d face = tool + margin;
  face.x() = tool.x();
  EXPECT_FALSE(with(fenced(tool - margin, face))->collisions()->collides(arm.start));
  // A micrometre beyond it is outside, named, and how far.
  face.x() = tool.x() - 1e-6;
  const auto k = with(fenced(tool - margin, face));
  ASSERT_TRUE(k->collisions()->collides(arm.start));
  const auto c = k->collisions()->contact(arm.start);
  ASSERT_TRUE(c);
  EXPECT_EQ(c->limit, scene::Limit::fence);
  EXPECT_EQ(c->first, "the tool point");
  EXPECT_EQ(c->second, "the fence");
  EXPECT_NEAR(c->depth, 1e-6, 1e-9);
  // Switched off, nothing is checked.
  EXPECT_FALSE(with(fenced(tool - margin, face, false, false))->collisions()->collides(arm.start));
}

TEST_P(FenceAndReduced, EveryLinkInsideWhenAsked) {
  // Around the tool point only: the tool point is inside, the arm's links are not.
  const Eigen::Vector3d margin(0.03, 0.03, 0.03);
  EXPECT_FALSE(with(fenced(tool - margin, tool + margin))->collisions()->collides(arm.start));
  const auto c = with(fenced(tool - margin, tool + margin, true))->collisions()->contact(arm.start);
  ASSERT_TRUE(c);
  EXPECT_EQ(c->limit, scene::Limit::fence);
  EXPECT_EQ(c->first.rfind("link '", 0), 0u) << c->first;
  // A fence around the whole reach holds every link.
  const Eigen::Vector3d reach(2, 2, 2);
  EXPECT_FALSE(with(fenced(-reach, reach, true))->collisions()->collides(arm.start));
}

TEST_P(FenceAndReduced, AMoveOutOfTheFenceIsRefusedBeforeAnythingMoves) {
  const Eigen::Vector3d margin(0.02, 0.02, 0.02);
  const std::vector<Move> moves{turn(30)};
  ASSERT_TRUE(plan_moves(*plain, arm.start, moves).ok());
  MoveRefusal refused;
  auto plan = plan_moves(*with(fenced(tool - margin, tool + margin)), arm.start, moves, {}, &refused);
  ASSERT_FALSE(plan.ok());
  EXPECT_EQ(plan.error().kind, ErrorKind::invalid_argument);
  const auto* d = plan.error().detail_as<CollisionDetail>();
  ASSERT_NE(d, nullptr) << plan.error().message;
  EXPECT_EQ(d->contact.limit, scene::Limit::fence);
  EXPECT_EQ(d->line, 4u);
  EXPECT_GT(d->fraction, 0);
  EXPECT_LT(d->fraction, 1);
  // Where it leaves: just outside (the check's resolution is 2 mm).
  const Eigen::Vector3d out = (d->tool_point - tool).cwiseAbs() - margin;
  EXPECT_GT(out.maxCoeff(), 0) << plan.error().message;
  EXPECT_LT(out.maxCoeff(), 0.0025) << plan.error().message;
  EXPECT_NE(plan.error().message.find("would leave the fence"), std::string::npos) << plan.error().message;
  // Switched off, the same move plans.
  EXPECT_TRUE(plan_moves(*with(fenced(tool - margin, tool + margin, false, false)), arm.start, moves).ok());
}

// A limit already broken where a motion starts (the fence or reduced mode switched on with
// the arm beyond it): the arm may come back, never go further beyond it, and once back in,
// not out again.
TEST_P(FenceAndReduced, AMotionThatStartsBeyondALimitMayComeBackButGoesNoFurther) {
  // The fence 10 mm away along where turning the joint by 20 deg takes the tool (the axis it
  // moves along most): the tool starts beyond that face, turning on goes in through it.
  std::vector<double> turned = arm.start;
  turned[arm.joint] += 20 * kDeg;
  const Eigen::Vector3d v = plain->pose_at(turned).position - tool;
  Eigen::Index axis = 0;
  v.cwiseAbs().maxCoeff(&axis);
  const double side = v[axis] > 0 ? 1 : -1;
  ASSERT_GT(std::abs(v[axis]), 0.02);
  Eigen::Vector3d low = tool - Eigen::Vector3d::Constant(0.3), high = tool + Eigen::Vector3d::Constant(0.3);
  (side > 0 ? low : high)[axis] = tool[axis] + side * 0.010;
  const auto k = with(fenced(low, high));
  ASSERT_TRUE(k->collisions()->collides(arm.start));
  auto back = plan_moves(*k, arm.start, std::vector<Move>{turn(20)});
  EXPECT_TRUE(back.ok()) << back.error().message;  // in through the face it is beyond
  auto further = plan_moves(*k, arm.start, std::vector<Move>{turn(-5)});
  ASSERT_FALSE(further.ok());
  const auto* d = further.error().detail_as<CollisionDetail>();
  ASSERT_NE(d, nullptr) << further.error().message;
  EXPECT_EQ(d->contact.limit, scene::Limit::fence);
  EXPECT_LT(d->fraction, 0.3) << further.error().message;  // soon, not at the end
  EXPECT_NE(further.error().message.find("further beyond"), std::string::npos) << further.error().message;

  // The same with a reduced range the joint starts 10 deg below.
  const std::string range = fmt::format(R"({{"joints": {{"{}": [{}, {}]}}}})", joint_name(),
                                        arm.start[arm.joint] / kDeg + 10, arm.start[arm.joint] / kDeg + 40);
  const auto r = with(reduced(range));
  EXPECT_TRUE(plan_moves(*r, arm.start, std::vector<Move>{turn(20)}).ok());  // into the range
  EXPECT_TRUE(plan_moves(*r, arm.start, std::vector<Move>{turn(5)}).ok());   // nearer it
  auto away = plan_moves(*r, arm.start, std::vector<Move>{turn(-5)});
  ASSERT_FALSE(away.ok());
  EXPECT_EQ(away.error().detail_as<CollisionDetail>()->contact.limit, scene::Limit::joint_range);
  // In through the lower end and out through the upper one: refused where it leaves again.
  auto through = plan_moves(*r, arm.start, std::vector<Move>{turn(60)});
  ASSERT_FALSE(through.ok());
  const auto* t = through.error().detail_as<CollisionDetail>();
  ASSERT_NE(t, nullptr) << through.error().message;
  EXPECT_NEAR(t->joints[arm.joint], arm.start[arm.joint] + 40 * kDeg, 0.5 * kDeg) << through.error().message;
}

TEST_P(FenceAndReduced, AJointMoveBeyondAReducedRangeIsRefused) {
  const std::string range = fmt::format(R"({{"joints": {{"{}": [{}, {}]}}}})", joint_name(),
                                        arm.start[arm.joint] / kDeg - 10, arm.start[arm.joint] / kDeg + 10);
  const auto k = with(reduced(range));
  EXPECT_TRUE(plan_moves(*k, arm.start, std::vector<Move>{turn(8)}).ok());
  auto plan = plan_moves(*k, arm.start, std::vector<Move>{turn(30)});
  ASSERT_FALSE(plan.ok());
  const auto* d = plan.error().detail_as<CollisionDetail>();
  ASSERT_NE(d, nullptr) << plan.error().message;
  EXPECT_EQ(d->contact.limit, scene::Limit::joint_range);
  EXPECT_EQ(d->contact.first, fmt::format("joint '{}'", joint_name()));
  EXPECT_NEAR(d->joints[arm.joint], arm.start[arm.joint] + 10 * kDeg, 0.5 * kDeg);
  // Reduced mode off: the arm's own limits.
  scene::Scene off = reduced(range);
  off.reduced->on = false;
  EXPECT_TRUE(plan_moves(*with(off), arm.start, std::vector<Move>{turn(30)}).ok());
}

TEST_P(FenceAndReduced, AReducedRangeOutsideTheJointsOwnLimitsIsRefused) {
  auto k = plain->with_scene(reduced(fmt::format(R"({{"joints": {{"{}": [-400, 10]}}}})", joint_name())));
  ASSERT_FALSE(k.ok());
  EXPECT_EQ(k.error().kind, ErrorKind::invalid_config);
  EXPECT_NE(k.error().message.find("reduced.joints." + joint_name()), std::string::npos) << k.error().message;
  auto unknown = plain->with_scene(reduced(R"({"joints": {"elbow9": [-10, 10]}})"));
  ASSERT_FALSE(unknown.ok());
  EXPECT_NE(unknown.error().message.find("no joint 'elbow9'"), std::string::npos) << unknown.error().message;
}

std::string text_of(const std::filesystem::path& file) {
  std::ostringstream text;
  text << std::ifstream(file).rdbuf();
  return text.str();
}

// The arm file may set the fence and reduced mode itself: they hold with no scene and with a
// scene that sets none, switch like a scene's, and give way to a scene's own.
TEST_P(FenceAndReduced, TheArmFilesFenceAndReducedModeHoldWhereTheSceneSetsNone) {
  const auto file = arm_file_path(arm.name);
  nlohmann::json doc = nlohmann::json::parse(text_of(file));
  const Eigen::Vector3d low = (tool - Eigen::Vector3d::Constant(0.02)) * 1e3, high = (tool + Eigen::Vector3d::Constant(0.02)) * 1e3;
  doc["fence"] = {{"min", {low.x(), low.y(), low.z()}}, {"max", {high.x(), high.y(), high.z()}}};
  doc["reduced"] = {{"joints", {{joint_name(), {-10, 10}}}}, {"on", false}};
  const std::string urdf = doc["urdf"].get<std::string>();
  auto model = parse_arm_model(doc.dump(), "fenced.arm.json", text_of(file.parent_path() / urdf), urdf);
  ASSERT_TRUE(model.ok()) << model.error().message;
  const auto own = std::make_shared<const ArmKinematics>(*model);
  const std::vector<Move> moves{turn(30)};
  for (const auto& k : {own, own->with_scene(scene::Scene{}).value()}) {
    auto plan = plan_moves(*k, arm.start, moves);
    ASSERT_FALSE(plan.ok());
    const auto* d = plan.error().detail_as<CollisionDetail>();
    ASSERT_NE(d, nullptr) << plan.error().message;
    EXPECT_EQ(d->contact.limit, scene::Limit::fence);
  }
  const scene::Scene theirs = with_arm_limits(scene::Scene{}, *model);
  ASSERT_TRUE(theirs.fence && theirs.reduced);
  EXPECT_TRUE(plan_moves(*own->with_scene(scene::with_fence(theirs, false).value()).value(), arm.start, moves).ok());
  // A scene's own fence replaces the arm file's: one around the whole reach lets it pass.
  const double reach = plain->model().reach;
  EXPECT_TRUE(plan_moves(*own->with_scene(fenced(Eigen::Vector3d::Constant(-reach), Eigen::Vector3d::Constant(reach))).value(),
                         arm.start, moves)
                  .ok());
  // Reduced mode, off in the file, switched on: the 30 deg turn leaves its 10 deg.
  scene::Scene reduced_on = scene::with_reduced_mode(scene::with_fence(theirs, false).value(), true).value();
  auto beyond = plan_moves(*own->with_scene(reduced_on).value(), arm.start, moves);
  ASSERT_FALSE(beyond.ok());
  EXPECT_NE(beyond.error().message.find("beyond its reduced range"), std::string::npos) << beyond.error().message;

  // Checked as the file is read: the key, the value and what is allowed, naming the file.
  doc["reduced"]["joints"][joint_name()] = {-400, 10};
  auto bad = parse_arm_model(doc.dump(), "fenced.arm.json", text_of(file.parent_path() / urdf), urdf);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().kind, ErrorKind::invalid_config);
  EXPECT_EQ(bad.error().message.rfind("fenced.arm.json: reduced.joints." + joint_name() + ": [-400, 10]", 0), 0u)
      << bad.error().message;
  doc["reduced"]["joints"][joint_name()] = {-10, 10};
  doc["fence"]["walls"] = 2;
  bad = parse_arm_model(doc.dump(), "fenced.arm.json", text_of(file.parent_path() / urdf), urdf);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().message.rfind("fenced.arm.json: fence.walls: unknown key", 0), 0u) << bad.error().message;
}

// The tool point's largest speed along every motion of `plan`, from its samples 1 ms apart
// (finite differences: independent of the Jacobian the planner measures with).
double sampled_peak(const ArmKinematics& k, const Plan& plan) {
  double peak = 0;
  for (const PlannedPiece& p : plan.pieces) {
    if (p.kind != PieceKind::motion) continue;
    const std::size_t n = plan.start.size();
    std::vector<double> q(n), v(n), a(n);
    constexpr double dt = 0.001;
    p.motion.sample(0, q, v, a);
    Eigen::Vector3d before = k.pose_at(q).position;
    for (double t = dt; t <= p.motion.duration + dt; t += dt) {
      p.motion.sample(std::min(t, p.motion.duration), q, v, a);
      const Eigen::Vector3d here = k.pose_at(q).position;
      peak = std::max(peak, (here - before).norm() / dt);
      before = here;
    }
  }
  return peak;
}

TEST_P(FenceAndReduced, ReducedModeCapsTheToolSpeedOfALinAndAPtp) {
  const double cap = 0.02;  // m/s
  const auto k = with(reduced(R"({"tool_speed": 20})"));
  for (const std::vector<Move>& moves : {std::vector<Move>{lin()}, std::vector<Move>{turn(30)}}) {
    const double free_peak = sampled_peak(*plain, plan_moves(*plain, arm.start, moves).value());
    EXPECT_GT(free_peak, 2 * cap);  // the cap is what slows it
    auto capped = plan_moves(*k, arm.start, moves);
    ASSERT_TRUE(capped.ok()) << capped.error().message;
    const double peak = sampled_peak(*k, *capped);
    EXPECT_LE(peak, cap * 1.01);
    EXPECT_GT(peak, cap * 0.7);  // not much slower than it needs
    EXPECT_LE(peak_tool_speed(*k, capped->pieces.back().motion), cap * 1.01);
  }
}

INSTANTIATE_TEST_SUITE_P(BothArms, FenceAndReduced, ::testing::Values("xarm", "scara"));

TEST(FenceFile, KeysReadValidatedAndWrittenBack) {
  auto s = scene::parse_scene(R"({"fence": {"min": [-300, -300, 0], "max": [300, 300, 400], "links": true},
      "reduced": {"tool_speed": 100, "joints": {"servo1": [-90, 90]}, "on": false}})",
                              "bench.json");
  ASSERT_TRUE(s.ok()) << s.error().message;
  ASSERT_TRUE(s->fence);
  EXPECT_TRUE(s->fence->on);  // on when configured
  EXPECT_TRUE(s->fence->links);
  EXPECT_NEAR(s->fence->high.z(), 0.4, 1e-12);
  ASSERT_TRUE(s->reduced);
  EXPECT_FALSE(s->reduced->on);
  EXPECT_NEAR(*s->reduced->tool_speed, 0.1, 1e-12);
  ASSERT_EQ(s->reduced->joints.size(), 1u);
  EXPECT_EQ(s->reduced->joints[0].lower, -90);
  auto back = scene::parse_scene(scene::scene_json(*s), "again");
  ASSERT_TRUE(back.ok()) << back.error().message;
  EXPECT_TRUE(back->fence->low.isApprox(s->fence->low));
  EXPECT_EQ(back->reduced->on, false);
  EXPECT_EQ(back->reduced->joints[0].upper, 90);

  const std::pair<const char*, const char*> bad[] = {
      {R"({"fence": {"min": [0, 0, 0], "max": [300, 300, 0]}})", "bench.json: fence.max: z 0 mm is not above min's 0 mm"},
      {R"({"fence": {"min": [0, 0], "max": [1, 1, 1]}})", "bench.json: fence.min: must be an array of 3 numbers"},
      {R"({"fence": {"min": [0, 0, 0], "max": [1, 1, 1], "walls": 2}})", "bench.json: fence.walls: unknown key"},
      {R"({"fence": {"min": [0, 0, 0], "max": [1, 1, 1], "on": "yes"}})", "bench.json: fence.on: \"yes\": must be true or false"},
      {R"({"reduced": {"tool_speed": 0}})", "bench.json: reduced.tool_speed: 0 is outside the allowed range 1..2000"},
      {R"({"reduced": {"joints": {"servo1": [10, -10]}}})", "bench.json: reduced.joints.servo1: [10, -10]: lower must be below upper"},
      {R"({"reduced": {}})", "bench.json: reduced: sets nothing"},
      {R"({})", "bench.json: objects: missing"},
  };
  for (const auto& [text, message] : bad) {
    auto e = scene::parse_scene(text, "bench.json");
    ASSERT_FALSE(e.ok()) << text;
    EXPECT_EQ(e.error().kind, ErrorKind::invalid_config);
    EXPECT_EQ(e.error().message.rfind(message, 0), 0u) << e.error().message;
  }
}

}  // namespace
}  // namespace armctl::arm
