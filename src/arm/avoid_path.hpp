// Around obstacles (`move-to --avoid`, docs/scene.md "Around obstacles"): when the direct PTP
// would collide, a collision-free path in joint space (OMPL's RRTConnect, then its path
// simplifier), handed to the one planner as the PTP's waypoints, so that the jerk-limited
// generator times it and plan_moves checks it as any plan. Pure: the kinematics value and
// joints in, waypoints out; no device, no I/O.
//
// Deterministic: every random number OMPL draws here comes from generators seeded with
// AvoidOptions::seed (fixed by default), so the same request gives the same path, as long as
// it is found within the time budget.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "arm/arm_kinematics.hpp"
#include "arm/plan_moves.hpp"
#include "core/error.hpp"
#include "scene/motion_check.hpp"

namespace armctl::arm {

inline constexpr std::uint32_t kAvoidSeed = 23;  // issue 23
// The time budgets an app may ask for (s): from a quick try to a long search.
inline constexpr double kMinAvoidTime = 0.01, kMaxAvoidTime = 60;

struct AvoidOptions {
  double time_budget = 1.0;  // s: searching, simplifying and checking the plan, all told
  std::uint32_t seed = kAvoidSeed;
  // No point of any body moves more than this between two configurations checked along an
  // edge of the search (the 2 mm rule of scene::check_motion).
  double resolution = scene::kCheckResolution;
};

struct AvoidPath {
  std::vector<std::vector<double>> waypoints;  // every joint, SI; neither `from` nor `to`
  double planning_s = 0;                       // wall time spent
};

// A path from `from` to `to` (every joint, SI) whose straight joint-space lines between
// consecutive points touch nothing of the arm's collision world (pairs already touching at
// `from` are not checked, as plan_moves does not). Errors (invalid_argument): the arm has no
// collision model, the target itself touches something, or no path within the budget ("no
// collision-free path found in 1 s").
Result<AvoidPath> collision_free_waypoints(const ArmKinematics& kinematics, const std::vector<double>& from,
                                           const std::vector<double>& to, const AvoidOptions& options = {});

struct AvoidingMove {
  PtpMove move;           // the PTP as given, or through the waypoints found
  bool avoided = false;   // the direct move would collide: `move` goes around
  std::size_t waypoints = 0;
  double planning_s = 0;
};

// The PTP `move` from `from` as plan_moves would plan it with `plan`; when its direct motion
// would collide (a refusal with a CollisionDetail), the same move through collision-free
// waypoints, checked by plan_moves: if the timed motion still touches (it passes waypoints
// without stopping, so it cuts their corners a little), the path is given more waypoints
// along the same lines, then searched again with another seed, within the budget. Any other
// refusal (IK, limits) is returned as it is. A PTP with waypoints of its own is not re-routed.
Result<AvoidingMove> avoiding_move(const ArmKinematics& kinematics, const std::vector<double>& from, const PtpMove& move,
                                   const AvoidOptions& options = {}, const PlanOptions& plan = {});

}  // namespace armctl::arm
