// The collision world against hand-checked cases (touching, grazing, inside) and, over
// 100,000 random configurations per arm with a random scene, against an independent brute
// force: points sampled 1.5 mm apart on every link shape and every object (surfaces and axes),
// each tested analytically against the other shape. A configuration whose sampled
// penetration is deeper than 0.5 mm must be found in collision, and one found in collision
// must have samples within the sampling's reach of the other shape (no phantom contacts).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "arm/arm_model.hpp"
#include "random_scene.hpp"
#include "scene/collision_world.hpp"
#include "scene/motion_check.hpp"

namespace armctl::scene {
namespace {

using motion::Shape;

// Signed distance of point q (in the shape's own frame) from `s`: negative inside.
double signed_distance(const Shape& s, const Eigen::Vector3d& q) {
  // Outside: the distance to the nearest point; inside: minus the distance to the nearest face.
  auto combine = [](double a, double b, double c) {
    const double outside = std::sqrt(std::max(a, 0.0) * std::max(a, 0.0) + std::max(b, 0.0) * std::max(b, 0.0) +
                                     std::max(c, 0.0) * std::max(c, 0.0));
    return outside > 0 ? outside : std::max({a, b, c});
  };
  switch (s.kind) {
    case Shape::Kind::box:
      return combine(std::abs(q.x()) - 0.5 * s.size.x(), std::abs(q.y()) - 0.5 * s.size.y(), std::abs(q.z()) - 0.5 * s.size.z());
    case Shape::Kind::cylinder:
      return combine(std::hypot(q.x(), q.y()) - s.size.x(), std::abs(q.z()) - 0.5 * s.size.y(), -1.0);
    case Shape::Kind::sphere: return q.norm() - s.size.x();
    case Shape::Kind::capsule: {  // from the segment between the half spheres' centres
      const double h = 0.5 * s.size.y();
      return (q - Eigen::Vector3d(0, 0, std::clamp(q.z(), -h, h))).norm() - s.size.x();
    }
  }
  return 0;
}

// Points on the surface and the inside of `s` in its own frame, about `step` apart.
std::vector<Eigen::Vector3d> samples(const Shape& s, double step) {
  std::vector<Eigen::Vector3d> out;
  auto count = [&](double length) { return std::max(1, int(std::ceil(length / step))); };
  switch (s.kind) {
    case Shape::Kind::box: {
      const Eigen::Vector3d h = 0.5 * s.size;
      const int nx = count(s.size.x()), ny = count(s.size.y()), nz = count(s.size.z());
      for (int i = 0; i <= nx; ++i)
        for (int j = 0; j <= ny; ++j)
          for (int k = 0; k <= nz; ++k) {
            const bool surface = i == 0 || i == nx || j == 0 || j == ny || k == 0 || k == nz;
            const bool core = (i == nx / 2 && j == ny / 2) || (j == ny / 2 && k == nz / 2) || (i == nx / 2 && k == nz / 2);
            if (!surface && !core) continue;
            out.emplace_back(-h.x() + 2 * h.x() * i / nx, -h.y() + 2 * h.y() * j / ny, -h.z() + 2 * h.z() * k / nz);
          }
      break;
    }
    case Shape::Kind::cylinder: {
      const double r = s.size.x(), h = 0.5 * s.size.y();
      const int nz = count(s.size.y()), nr = count(r), na = std::max(8, count(2 * M_PI * r));
      for (int k = 0; k <= nz; ++k) {
        const double z = -h + 2 * h * k / nz;
        out.emplace_back(0, 0, z);
        for (int ir = 1; ir <= nr; ++ir) {
          if (ir < nr && k != 0 && k != nz) continue;
          for (int a = 0; a < na; ++a) {
            const double t = 2 * M_PI * a / na;
            out.emplace_back(r * ir / nr * std::cos(t), r * ir / nr * std::sin(t), z);
          }
        }
      }
      break;
    }
    case Shape::Kind::sphere:
    case Shape::Kind::capsule: {
      // A sphere's surface about each end of the segment (one point for a sphere), and the
      // segment's own points with the cylinder's surface about them.
      const double r = s.size.x(), h = (s.kind == Shape::Kind::capsule ? 0.5 * s.size.y() : 0.0);
      const int n = std::max(8, count(M_PI * r)), nz = h > 0 ? count(2 * h) : 0;
      const std::vector<double> ends = h > 0 ? std::vector<double>{-h, h} : std::vector<double>{0.0};
      for (const double end : ends) {
        for (int i = 0; i <= n; ++i) {
          const double th = M_PI * i / n;
          for (int j = 0; j < 2 * n; ++j) {
            const double ph = M_PI * j / n;
            out.emplace_back(r * std::sin(th) * std::cos(ph), r * std::sin(th) * std::sin(ph), end + r * std::cos(th));
          }
        }
      }
      for (int k = 0; k <= nz; ++k) {
        const double z = nz ? -h + 2 * h * k / nz : 0.0;
        out.emplace_back(0, 0, z);
        for (int j = 0; nz && j < 2 * n; ++j) out.emplace_back(r * std::cos(M_PI * j / n), r * std::sin(M_PI * j / n), z);
      }
      break;
    }
  }
  return out;
}

// A shape with its samples, made once.
struct Sampled {
  Shape shape;
  std::vector<Eigen::Vector3d> points;
};
constexpr double kSampleStep = 0.0015;  // m: every point of a shape is within 1.07 mm of a sample

// The deepest any sample of one shape lies inside the other (m; negative: the nearest gap
// the samples see).
double sampled_depth(const Sampled& a, const Eigen::Isometry3d& pa, const Sampled& b, const Eigen::Isometry3d& pb) {
  double deepest = -1e9;
  const Eigen::Isometry3d a_in_b = pb.inverse() * pa, b_in_a = a_in_b.inverse();
  for (const auto& p : a.points) deepest = std::max(deepest, -signed_distance(b.shape, a_in_b * p));
  for (const auto& p : b.points) deepest = std::max(deepest, -signed_distance(a.shape, b_in_a * p));
  return deepest;
}

ArmBodies arm_bodies(const arm::ArmModel& m, bool self) {
  ArmBodies a;
  a.links = m.bodies;
  a.tool_link = m.tool_link;
  for (const auto& j : m.joints) a.joint_reach.push_back(std::max(std::abs(j.limits.lower), std::abs(j.limits.upper)));
  if (!self) {  // every pair of links allowed: only the scene is checked
    for (const auto& x : m.bodies->bodies)
      for (const auto& y : m.bodies->bodies) a.allowed.emplace_back(x.name, y.name);
  } else {
    a.allowed = m.allowed_collisions;
  }
  return a;
}

// A single link turning about z with a 100 x 20 x 20 mm box from its axis out along x.
std::shared_ptr<const motion::LinkBodies> one_link() {
  auto b = std::make_shared<motion::LinkBodies>();
  b->bodies.push_back(motion::LinkBody{"base", -1, Eigen::Isometry3d::Identity(), Eigen::Vector3d::UnitZ(), false, -1, {}});
  Shape s;
  s.size = {0.1, 0.02, 0.02};
  s.pose.translation() = Eigen::Vector3d(0.05, 0, 0);
  b->bodies.push_back(motion::LinkBody{"arm", 0, Eigen::Isometry3d::Identity(), Eigen::Vector3d::UnitZ(), false, 0, {s}});
  return b;
}

Scene one_sphere(const Eigen::Vector3d& at, double radius) {
  SceneObject o;
  o.name = "ball";
  o.shape.kind = Shape::Kind::sphere;
  o.shape.size = {radius, 0, 0};
  o.shape.pose.translation() = at;
  return Scene{{o}, {}};
}

std::shared_ptr<const CollisionWorld> world_of(const Scene& scene) {
  ArmBodies a;
  a.links = one_link();
  a.tool_link = "arm";
  a.joint_reach = {M_PI};
  return CollisionWorld::build(a, scene).value();
}

TEST(CollisionWorld, HandCheckedTouchingGrazingInside) {
  const std::vector<double> zero{0.0}, turned{M_PI / 2};
  {  // 10 mm clear of the box's end: no contact, clearance 10 mm, named
    auto w = world_of(one_sphere({0.12, 0, 0}, 0.01));
    EXPECT_FALSE(w->collides(zero));
    const Clearance c = w->clearance(zero);
    EXPECT_NEAR(c.distance, 0.01, 1e-6);
    EXPECT_EQ(c.first, "link 'arm'");
    EXPECT_EQ(c.second, "sphere 'ball'");
  }
  {  // grazing: 0.1 mm clear
    auto w = world_of(one_sphere({0.1101, 0, 0}, 0.01));
    EXPECT_FALSE(w->collides(zero));
    EXPECT_NEAR(w->clearance(zero).distance, 0.0001, 1e-6);
  }
  {  // 5 mm in: contact, 5 mm deep, at the box's end
    auto w = world_of(one_sphere({0.105, 0, 0}, 0.01));
    EXPECT_TRUE(w->collides(zero));
    const auto c = w->contact(zero);
    ASSERT_TRUE(c.has_value());
    EXPECT_NEAR(c->depth, 0.005, 1e-4);
    EXPECT_EQ(c->first, "link 'arm'");
    EXPECT_NEAR(c->point.x(), 0.1, 0.006);
    // Turned a quarter away: clear.
    EXPECT_FALSE(w->collides(turned));
  }
  {  // the sphere wholly inside the box
    auto w = world_of(one_sphere({0.05, 0, 0}, 0.005));
    EXPECT_TRUE(w->collides(zero));
  }
  {  // nothing within the horizon: no names
    auto w = world_of(one_sphere({0.5, 0, 0}, 0.01));
    const Clearance c = w->clearance(zero);
    EXPECT_EQ(c.distance, kClearanceHorizon);
    EXPECT_TRUE(c.first.empty());
  }
}

// A capsule's ends are half spheres: along its axis it reaches its radius past the straight
// part, where a cylinder of the same length ends flat.
TEST(CollisionWorld, ACapsuleReachesItsRadiusBeyondItsStraightPart) {
  for (const auto kind : {Shape::Kind::capsule, Shape::Kind::cylinder}) {
    SceneObject o;
    o.name = "pipe";
    o.shape.kind = kind;
    o.shape.size = {0.01, 0.06, 0};  // r 10 mm, straight part 60 mm
    o.shape.pose.translation() = Eigen::Vector3d(0.15, 0, 0);  // its axis along x: 120..180 mm
    o.shape.pose.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
    auto w = world_of(Scene{{o}, {}});
    const std::vector<double> zero{0.0};
    const Clearance c = w->clearance(zero);  // from the box's end at 100 mm
    EXPECT_NEAR(c.distance, kind == Shape::Kind::capsule ? 0.01 : 0.02, 1e-6) << motion::to_string(kind);
    EXPECT_EQ(c.second, kind == Shape::Kind::capsule ? "capsule 'pipe'" : "cylinder 'pipe'");
  }
}

TEST(CollisionWorld, AMotionIsCheckedEveryTwoMillimetres) {
  // The link's tip (100 mm out, 14 mm off the axis at the corners) sweeps through a sphere
  // 1 mm thin on its way: sampled every 2 mm of the farthest point, the check catches it.
  auto w = world_of(one_sphere({0, 0.08, 0}, 0.004));
  const MotionCheck m = check_motion(*w, 1.0, [](double t, std::vector<double>& q) { q.assign(1, t * M_PI); });
  ASSERT_TRUE(m.contact.has_value());
  EXPECT_NEAR(m.at, 0.5, 0.06);
  // Close enough to see the resolution: at least one check per 2 mm of the tip's arc up to
  // the contact.
  EXPECT_GE(double(m.checks), 0.1 * M_PI * m.at / kCheckResolution);
  // A bound that holds: over the whole turn the tip moves at most reach x angle.
  EXPECT_GE(w->displacement_bound(std::vector<double>{0}, std::vector<double>{1}), 0.1);
}

class ArmCollisions : public ::testing::TestWithParam<const char*> {};

TEST_P(ArmCollisions, AgreesWithABruteForceOverRandomConfigurations) {
  const arm::ArmModel m = arm::load_arm_model(arm::arm_file_path(GetParam())).value();
  std::mt19937_64 rng(20261202);
  std::uniform_real_distribution<double> unit(0, 1);
  const int kConfigs = std::getenv("ARMCTL_SCENE_CONFIGS") ? std::atoi(std::getenv("ARMCTL_SCENE_CONFIGS")) : 30000, kScenes = 20;
  int collided = 0, deep_checked = 0;
  std::vector<Eigen::Isometry3d> poses;
  std::vector<std::vector<Sampled>> link_samples;
  for (const auto& b : m.bodies->bodies) {
    link_samples.emplace_back();
    for (const auto& s : b.shapes) link_samples.back().push_back({s, samples(s, kSampleStep)});
  }
  for (int sc = 0; sc < kScenes; ++sc) {
    // Five objects within the arm's reach, of every kind.
    const Scene scene = testing::random_scene(m.reach, 5, rng);
    auto world = CollisionWorld::build(arm_bodies(m, false), scene).value();
    std::vector<Sampled> object_samples;
    for (const auto& o : scene.objects) object_samples.push_back({o.shape, samples(o.shape, kSampleStep)});
    for (int c = 0; c < kConfigs / kScenes; ++c) {
      std::vector<double> q;
      for (const auto& j : m.joints) q.push_back(j.limits.lower + (j.limits.upper - j.limits.lower) * unit(rng));
      const bool hit = world->collides(q);
      collided += hit;
      m.bodies->poses(q, poses);
      double deepest = -1e9;
      for (std::size_t b = 0; b < m.bodies->bodies.size(); ++b) {
        if (!m.bodies->moves(int(b))) continue;
        for (const auto& s : link_samples[b]) {
          const Eigen::Isometry3d ps = poses[b] * s.shape.pose;
          Eigen::Vector3d l1, h1;
          motion::world_bounds(s.shape, ps, l1, h1);
          for (const auto& o : object_samples) {
            Eigen::Vector3d l2, h2;
            motion::world_bounds(o.shape, o.shape.pose, l2, h2);
            if (((l1.array() > h2.array() + 0.002).any()) || ((l2.array() > h1.array() + 0.002).any())) continue;
            ++deep_checked;
            deepest = std::max(deepest, sampled_depth(s, ps, o, o.shape.pose));
          }
        }
      }
      if (deepest > 0.0005) {
        ASSERT_TRUE(hit) << GetParam() << " scene " << sc << " config " << c << ": samples " << deepest * 1e3
                         << " mm deep, the check saw no contact";
      }
      if (hit) {
        // Every point of a shape lies within 1.07 mm of one of its samples.
        ASSERT_GT(deepest, -0.0011) << GetParam() << " scene " << sc << " config " << c
                                    << ": a contact where the samples stay " << -deepest * 1e3 << " mm apart";
      }
    }
  }
  // The random scenes are near enough to matter.
  EXPECT_GT(collided, kConfigs / 100);
  EXPECT_GT(deep_checked, kConfigs / 10);
  std::printf("%s: %d of %d configurations in contact; %d shape pairs sampled\n", GetParam(), collided, kConfigs, deep_checked);
}

// The pairs of links in contact in (almost) every sampled configuration, as MoveIt's setup
// assistant finds them ("always": 95 % of the samples, its default): each pair alone checked
// (every other pair allowed) over random configurations inside the joint limits. Joined
// links are never checked, so never listed.
std::set<std::pair<std::string, std::string>> always_touching(const arm::ArmModel& m, int samples) {
  std::set<std::pair<std::string, std::string>> out;
  const auto& bodies = m.bodies->bodies;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<std::vector<double>> qs;
  for (int k = 0; k < samples; ++k) {
    std::vector<double> q;
    for (const auto& j : m.joints) q.push_back(j.limits.lower + (j.limits.upper - j.limits.lower) * unit(rng));
    qs.push_back(q);
  }
  for (std::size_t a = 0; a < bodies.size(); ++a) {
    for (std::size_t b = a + 1; b < bodies.size(); ++b) {
      if (bodies[a].shapes.empty() || bodies[b].shapes.empty()) continue;
      ArmBodies only = arm_bodies(m, false);
      std::erase_if(only.allowed, [&](const auto& p) {
        return (p.first == bodies[a].name && p.second == bodies[b].name) || (p.first == bodies[b].name && p.second == bodies[a].name);
      });
      auto world = CollisionWorld::build(only, Scene{}).value();
      if (world->pairs_checked() == 0) continue;  // joined, or neither moves
      int touching = 0;
      for (const auto& q : qs) touching += world->collides(q);
      if (touching >= samples * 95 / 100) out.emplace(std::min(bodies[a].name, bodies[b].name), std::max(bodies[a].name, bodies[b].name));
    }
  }
  return out;
}

TEST_P(ArmCollisions, TheArmFileAllowsExactlyThePairsThatAlwaysTouch) {
  const arm::ArmModel m = arm::load_arm_model(arm::arm_file_path(GetParam())).value();
  std::set<std::pair<std::string, std::string>> allowed;
  for (const auto& [a, b] : m.allowed_collisions) allowed.emplace(std::min(a, b), std::max(a, b));
  const auto found = always_touching(m, 1000);
  std::string listed;
  for (const auto& [a, b] : found) listed += "{\"links\": [\"" + a + "\", \"" + b + "\"], \"why\": \"always touching\"} ";
  EXPECT_EQ(allowed, found) << GetParam() << ": the arm file's collision.allowed should be: " << listed;
  // With those allowed, the arm stands free at zero (every joint at 0, or its nearest limit)
  // and is not in contact everywhere.
  auto world = CollisionWorld::build(arm_bodies(m, true), Scene{}).value();
  std::vector<double> zero(m.joints.size(), 0.0);
  for (std::size_t i = 0; i < zero.size(); ++i) zero[i] = std::clamp(0.0, m.joints[i].limits.lower, m.joints[i].limits.upper);
  const auto c = world->contact(zero);
  EXPECT_FALSE(c.has_value()) << c->first << " with " << c->second;
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> unit(0, 1);
  int in_contact = 0;
  for (int k = 0; k < 2000; ++k) {
    std::vector<double> q;
    for (const auto& j : m.joints) q.push_back(j.limits.lower + (j.limits.upper - j.limits.lower) * unit(rng));
    in_contact += world->collides(q);
  }
  EXPECT_LT(in_contact, 2000);
  std::printf("%s: %d of 2000 random configurations touch themselves\n", GetParam(), in_contact);
}

INSTANTIATE_TEST_SUITE_P(BothArms, ArmCollisions, ::testing::Values("xarm", "scara"));

}  // namespace
}  // namespace armctl::scene
