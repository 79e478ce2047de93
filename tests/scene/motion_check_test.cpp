// check_motion remembers how far apart each pair of bodies is and skips it until the motion
// could have closed that gap. Against a reference that asks every pair (the world's own
// contact and clearance) at configurations four times closer than the resolution, over
// random motions of both arms in random scenes (straight joint-space lines, and motions that
// go out and turn back): nothing deeper than the resolution allows is missed, no contact is
// made up, and the smallest clearance is the reference's within the resolution, measured
// where it says. And the memory is what makes it cheap: most pairs are skipped.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "arm/arm_kinematics.hpp"
#include "random_scene.hpp"
#include "scene/motion_check.hpp"

namespace armctl::scene {
namespace {

constexpr double kGrid = kCheckResolution / 4;  // the reference's spacing: no point moves more between two

struct Reference {
  double deepest = 0;        // m: the deepest contact seen
  double first_contact = -1;  // s: where the first contact is (-1: none)
  double least = kClearanceHorizon;  // m: the smallest clearance where nothing touches
};

// Every pair asked at every configuration `kGrid` apart (the conservative bound of the
// whole motion's joint travel), the pairs touching at the start left out as check_motion does.
Reference reference(const CollisionWorld& world, const std::function<void(double, std::vector<double>&)>& sample,
                    double path_bound) {
  Reference r;
  std::vector<double> q;
  sample(0, q);
  const std::vector<int> skip = world.touching(q);
  const int n = std::max(1, int(std::ceil(path_bound / kGrid)));
  for (int k = 0; k <= n; ++k) {
    const double t = double(k) / n;
    sample(t, q);
    if (const auto c = world.contact(q, skip)) {
      r.deepest = std::max(r.deepest, c->depth);
      if (r.first_contact < 0) r.first_contact = t;
    } else {
      r.least = std::min(r.least, world.clearance(q, kClearanceHorizon, skip).distance);
    }
  }
  return r;
}

class MotionChecks : public ::testing::TestWithParam<const char*> {};

TEST_P(MotionChecks, AgreeWithEveryPairAskedEverywhereAndSkipMostPairs) {
  const arm::ArmKinematics plain(arm::load_arm_model(arm::arm_file_path(GetParam())).value());
  const arm::ArmModel& m = plain.model();
  std::mt19937_64 rng(2312);
  std::uniform_real_distribution<double> unit(0, 1);
  int contacts = 0, clear = 0;
  std::size_t checks = 0, queries = 0, could_ask = 0;
  for (int motion = 0; motion < 60; ++motion) {
    const auto kin = plain.with_scene(testing::random_scene(m.reach, 8, rng)).value();
    const CollisionWorld& world = *kin->collisions();
    // From a random configuration up to 0.8 rad (or 40 % of a prismatic joint's travel) away.
    std::vector<double> a, b;
    for (const auto& j : m.joints) {
      const double span = j.limits.upper - j.limits.lower;
      a.push_back(j.limits.lower + span * unit(rng));
      const double step = std::min(0.8, 0.4 * span) * (2 * unit(rng) - 1);
      b.push_back(std::clamp(a.back() + step, j.limits.lower, j.limits.upper));
    }
    // Odd motions go out and come back (sin(pi t)): their joints turn back halfway.
    const bool turns_back = motion % 2 == 1;
    auto sample = [&](double t, std::vector<double>& q) {
      const double s = turns_back ? std::sin(M_PI * t) : t;
      q.resize(a.size());
      for (std::size_t i = 0; i < q.size(); ++i) q[i] = a[i] + s * (b[i] - a[i]);
    };
    const MotionCheck got = check_motion(world, 1.0, sample);
    const Reference want = reference(world, sample, world.displacement_bound(a, b) * (turns_back ? M_PI : 1.0));
    const std::string where = std::string(GetParam()) + " motion " + std::to_string(motion);
    checks += got.checks;
    queries += got.queries;
    could_ask += got.checks * world.pairs_checked();

    std::vector<double> start;
    sample(0, start);
    const std::vector<int> skip = world.touching(start);
    if (got.contact) {
      ++contacts;
      // No contact made up: the world finds it where check_motion says, and the reference
      // came within its own spacing of it by then.
      EXPECT_TRUE(world.collides(got.joints, skip)) << where;
      EXPECT_TRUE(want.first_contact >= 0 || want.least <= 2 * kGrid) << where;
    } else {
      // Between two checks no point moves more than the resolution: a pair's two bodies come
      // at most twice that nearer. Anything deeper is seen.
      EXPECT_LE(want.deepest, 2 * kCheckResolution + 2 * kGrid) << where << ": missed a contact";
    }
    if (!got.contact && want.first_contact < 0) {
      ++clear;
      // The smallest clearance over its checks: never below the reference's (within the
      // reference's spacing), and not above it by more than one step could close.
      EXPECT_GE(got.clearance.distance, want.least - 2 * kGrid) << where;
      EXPECT_LE(got.clearance.distance, want.least + 2 * kCheckResolution) << where;
      if (got.clearance.distance < kClearanceHorizon) {
        EXPECT_NEAR(world.clearance(got.joints, kClearanceHorizon, skip).distance, got.clearance.distance, 1e-9) << where;
      }
    }
  }
  // The random motions meet things and pass them.
  EXPECT_GE(contacts, 8);
  EXPECT_GE(clear, 10);
  // Most pairs are skipped at most checks.
  EXPECT_LT(double(queries), 0.25 * double(could_ask));
  std::printf("%s: %d of 60 motions in contact; %zu checks, %zu pairs asked of %zu\n", GetParam(), contacts,
              checks, queries, could_ask);
}

INSTANTIATE_TEST_SUITE_P(BothArms, MotionChecks, ::testing::Values("xarm", "scara"));

}  // namespace
}  // namespace armctl::scene
