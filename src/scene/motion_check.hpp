// A whole motion checked against the collision world: at every step small enough that no
// point of any body moves more than the resolution (2 mm) between two checks, every pair of
// bodies that could touch is asked; a pair known to be apart is not (docs/scene.md, "How a
// motion is checked"). The world's limits (the fence, reduced mode's joint ranges) are asked
// at every check; a limit broken is a contact whose `limit` says which.
#pragma once

#include <functional>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "scene/collision_world.hpp"

namespace armctl::scene {

struct MotionCheck {
  std::optional<Contact> contact;
  // Pairs already in contact where the motion starts (an arm switched on in a bent pose, an
  // object placed where the arm stands): not checked along it, so that the arm can move
  // out; said in the plan's note.
  std::vector<std::pair<std::string, std::string>> started_touching;
  // Limits already broken where it starts (the fence switched on with the tool outside it):
  // along the motion the arm may move back but never further beyond them than it has been
  // since the start (a contact saying "further beyond ... than where the motion started").
  std::vector<std::pair<std::string, std::string>> started_beyond;
  double at = 0;  // s into the motion where the contact is (or where the clearance is smallest)
  std::vector<double> joints;  // there
  Clearance clearance;         // the smallest along the motion (no contact)
  std::size_t checks = 0;      // configurations checked
  std::size_t queries = 0;     // pairs asked at them: contact or distance (FCL after a box test)
};
inline constexpr double kCheckResolution = 0.002;  // m

// The limits (fence, reduced mode's joint ranges) broken where a motion starts: the arm may
// move back, but never further beyond one than it has been since the start (the least depth
// so far), so that a fence switched on with the tool outside lets it come in, not go out.
// Used by check_motion along a plan and by the servo mode for each step's resting place.
class LimitsBeyond {
 public:
  LimitsBeyond() = default;
  // `skip`: CollisionWorld::touching at the start (its pairs are ignored here, its limits taken).
  LimitsBeyond(const CollisionWorld& world, std::span<const int> skip);
  bool empty() const { return limits_.empty(); }
  // The limit the configuration placed in `at` is further beyond than the least so far, as a
  // Contact that says so, or nothing; `update`: the least depths take this configuration's.
  std::optional<Contact> deeper(std::span<const double> joints, CollisionWorld::Placement& at, bool update);

 private:
  const CollisionWorld* world_ = nullptr;
  std::vector<std::pair<int, double>> limits_;  // index, least depth so far
};

// `sample(t, joints)`: every joint at t (s) of a motion lasting `duration` s.
//
// Each pair keeps a lower bound on how far apart its two bodies are: measured when it was
// last asked, less how much nearer each step since could have brought them (the step's
// displacement bound over the joints between the two). A pair is asked about contact only
// once that bound is used up, and about its distance only once the bound falls below the
// smallest clearance so far: the answers are those of asking every pair at every check
// (conservative advancement), with far fewer FCL queries.
MotionCheck check_motion(const CollisionWorld& world, double duration,
                         const std::function<void(double, std::vector<double>&)>& sample,
                         double resolution = kCheckResolution);

}  // namespace armctl::scene
