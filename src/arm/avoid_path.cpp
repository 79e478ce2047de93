#include "arm/avoid_path.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>
#include <utility>

#include <fmt/core.h>
#include <ompl/base/MotionValidator.h>
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/datastructures/NearestNeighborsLinear.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>

namespace armctl::arm {

namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;
using Clock = std::chrono::steady_clock;

// A request's own random numbers. OMPL's global seed (ompl::RNG::setSeed) holds once per
// process, before any generator exists, and each generator then draws the next seed: a
// second request in the same process would search differently. So each generator used here
// is seeded from the request instead.
class SeededSampler : public ob::RealVectorStateSampler {
 public:
  SeededSampler(const ob::StateSpace* space, std::uint32_t seed) : ob::RealVectorStateSampler(space) {
    rng_.setLocalSeed(seed);
  }
};

class SeededRRTConnect : public og::RRTConnect {
 public:
  SeededRRTConnect(const ob::SpaceInformationPtr& si, std::uint32_t seed) : og::RRTConnect(si) {
    rng_.setLocalSeed(seed);
  }
};

class SeededSimplifier : public og::PathSimplifier {
 public:
  SeededSimplifier(const ob::SpaceInformationPtr& si, std::uint32_t seed) : og::PathSimplifier(si) {
    rng_.setLocalSeed(seed);
  }
};

// The joints searched over (the chain's, and any other the move changes), the others held
// where the move starts.
struct JointSpace {
  std::vector<std::size_t> searched;
  std::vector<double> held;  // every joint
  std::vector<double> full(const ob::State* s) const {
    std::vector<double> q = held;
    const auto* v = s->as<ob::RealVectorStateSpace::StateType>();
    for (std::size_t k = 0; k < searched.size(); ++k) q[searched[k]] = v->values[k];
    return q;
  }
  void set(ob::State* s, const std::vector<double>& q) const {
    auto* v = s->as<ob::RealVectorStateSpace::StateType>();
    for (std::size_t k = 0; k < searched.size(); ++k) v->values[k] = q[searched[k]];
  }
};

// An edge is valid when every configuration along it, spaced so that no point of any body
// moves more than the resolution between two of them (CollisionWorld::displacement_bound),
// touches nothing: the 2 mm rule of scene::check_motion, on the straight joint-space line.
// Checked from the middle outwards (halving the spacing), where a contact is likeliest.
class StepValidator : public ob::MotionValidator {
 public:
  StepValidator(const ob::SpaceInformationPtr& si, const JointSpace& space, const scene::CollisionWorld& world,
                std::vector<int> skip, double resolution)
      : ob::MotionValidator(si), space_(space), world_(world), skip_(std::move(skip)), resolution_(resolution) {}

  bool checkMotion(const ob::State* s1, const ob::State* s2) const override {
    if (!si_->isValid(s2)) return fail();
    const std::vector<double> a = space_.full(s1), b = space_.full(s2);
    const int steps = step_count(a, b);
    int stride = 1;
    while (stride * 2 < steps) stride *= 2;
    std::vector<double> q(a.size());
    for (; stride >= 1; stride /= 2)
      for (int i = stride; i < steps; i += 2 * stride)  // the odd multiples: each step once
        if (touches(a, b, double(i) / steps, q)) return fail();
    ++valid_;
    return true;
  }

  bool checkMotion(const ob::State* s1, const ob::State* s2, std::pair<ob::State*, double>& last_valid) const override {
    const std::vector<double> a = space_.full(s1), b = space_.full(s2);
    const int steps = step_count(a, b);
    std::vector<double> q(a.size());
    for (int i = 1; i <= steps; ++i) {
      if (touches(a, b, double(i) / steps, q)) {
        last_valid.second = double(i - 1) / steps;
        if (last_valid.first) si_->getStateSpace()->interpolate(s1, s2, last_valid.second, last_valid.first);
        return fail();
      }
    }
    ++valid_;
    return true;
  }

 private:
  int step_count(const std::vector<double>& a, const std::vector<double>& b) const {
    return std::max(1, int(std::ceil(world_.displacement_bound(a, b) / resolution_)));
  }
  bool touches(const std::vector<double>& a, const std::vector<double>& b, double t, std::vector<double>& q) const {
    for (std::size_t j = 0; j < q.size(); ++j) q[j] = a[j] + t * (b[j] - a[j]);
    return world_.collides(q, skip_);
  }
  bool fail() const {
    ++invalid_;
    return false;
  }
  const JointSpace& space_;
  const scene::CollisionWorld& world_;
  std::vector<int> skip_;
  double resolution_;
};

Error not_found(double budget) {
  return Error{ErrorKind::invalid_argument, fmt::format("no collision-free path found in {:g} s", budget)};
}

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The search itself: RRTConnect (two trees, one from each end, joined as soon as they
// meet), then the simplifier's vertex reduction and shortcuts, a fixed number of rounds (not
// "as long as time allows": the same request gives the same path). The path's states, both
// ends included.
Result<std::vector<std::vector<double>>> search(const ArmKinematics& kin, const std::vector<double>& from,
                                                const std::vector<double>& to, const AvoidOptions& options,
                                                std::uint32_t seed, Clock::time_point deadline) {
  static std::once_flag quiet;
  std::call_once(quiet, [] { ompl::msg::setLogLevel(ompl::msg::LOG_NONE); });  // our errors say it
  const auto& world_ptr = kin.collisions();
  if (!world_ptr)
    return Error{ErrorKind::invalid_argument,
                 fmt::format("arm '{}' has no collision model to plan around obstacles with", kin.model().name)};
  const scene::CollisionWorld& world = *world_ptr;
  const ArmModel& model = kin.model();
  if (from.size() != std::size_t(model.joint_count()) || to.size() != from.size())
    return Error{ErrorKind::invalid_argument,
                 fmt::format("around obstacles: {} and {} joint values given; arm '{}' has {} joints", from.size(),
                             to.size(), model.name, model.joint_count())};
  if (auto ok = kin.check_targets(to); !ok) return ok.error();

  JointSpace space;
  space.held = from;
  for (std::size_t j = 0; j < from.size(); ++j)
    if (int(j) < model.chain_joints() || from[j] != to[j]) space.searched.push_back(j);
  // A joint read back a hair past its limit starts the search inside them.
  std::vector<double> start = from;
  for (std::size_t j : space.searched)
    start[j] = std::clamp(start[j], model.joints[j].limits.lower, model.joints[j].limits.upper);

  // Pairs touching where the arm stands are not checked, as along any motion (check_motion).
  const std::vector<int> skip = world.touching(from);
  if (auto c = world.contact(to, skip))
    return Error{ErrorKind::invalid_argument,
                 fmt::format("no collision-free path: at the target {} touches {}, {:.1f} mm deep", c->first, c->second,
                             c->depth * 1e3)};

  auto state_space = std::make_shared<ob::RealVectorStateSpace>(unsigned(space.searched.size()));
  ob::RealVectorBounds bounds(unsigned(space.searched.size()));
  for (std::size_t k = 0; k < space.searched.size(); ++k) {
    const JointLimits& l = model.joints[space.searched[k]].limits;
    bounds.setLow(unsigned(k), l.lower);
    bounds.setHigh(unsigned(k), l.upper);
  }
  state_space->setBounds(bounds);
  state_space->setStateSamplerAllocator(
      [seed](const ob::StateSpace* s) { return std::make_shared<SeededSampler>(s, seed); });
  auto si = std::make_shared<ob::SpaceInformation>(state_space);
  si->setStateValidityChecker([&](const ob::State* s) { return !world.collides(space.full(s), skip); });
  si->setMotionValidator(std::make_shared<StepValidator>(si, space, world, skip, options.resolution));
  si->setup();

  ob::ScopedState<ob::RealVectorStateSpace> s0(state_space), s1(state_space);
  space.set(s0.get(), start);
  space.set(s1.get(), to);
  auto problem = std::make_shared<ob::ProblemDefinition>(si);
  problem->setStartAndGoalStates(s0, s1);
  SeededRRTConnect planner(si, seed + 1);
  planner.setProblemDefinition(problem);
  // Linear nearest-neighbour search: the default (GNAT) picks its pivots at random from a
  // generator of its own. The trees stay small (hundreds of states).
  planner.setNearestNeighbors<ompl::NearestNeighborsLinear>();
  planner.setup();

  const ob::PlannerTerminationCondition until_deadline([deadline] { return Clock::now() >= deadline; });
  if (planner.solve(until_deadline) != ob::PlannerStatus::EXACT_SOLUTION) return not_found(options.time_budget);
  auto& path = *problem->getSolutionPath()->as<og::PathGeometric>();

  SeededSimplifier simplifier(si, seed + 2);
  for (int round = 0; round < 5 && !until_deadline(); ++round) {
    bool shorter = simplifier.reduceVertices(path);
    shorter = simplifier.shortcutPath(path) || shorter;
    shorter = simplifier.collapseCloseVertices(path) || shorter;
    if (!shorter) break;
  }
  std::vector<std::vector<double>> out;
  for (std::size_t k = 0; k < path.getStateCount(); ++k) out.push_back(space.full(path.getState(k)));
  out.front() = from;
  return out;
}

// The waypoints of `states` (both ends included) with every line cut into `parts` pieces.
std::vector<std::vector<double>> waypoints_of(const std::vector<std::vector<double>>& states, int parts) {
  std::vector<std::vector<double>> out;
  for (std::size_t k = 0; k + 1 < states.size(); ++k) {
    if (k > 0) out.push_back(states[k]);
    for (int p = 1; p < parts; ++p) {
      std::vector<double> q = states[k];
      for (std::size_t j = 0; j < q.size(); ++j) q[j] += double(p) / parts * (states[k + 1][j] - states[k][j]);
      out.push_back(std::move(q));
    }
  }
  return out;
}

}  // namespace

Result<AvoidPath> collision_free_waypoints(const ArmKinematics& kinematics, const std::vector<double>& from,
                                           const std::vector<double>& to, const AvoidOptions& options) {
  const Clock::time_point start = Clock::now();
  const auto deadline = start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(options.time_budget));
  auto states = search(kinematics, from, to, options, options.seed, deadline);
  if (!states) return states.error();
  return AvoidPath{waypoints_of(*states, 1), seconds_since(start)};
}

Result<AvoidingMove> avoiding_move(const ArmKinematics& kinematics, const std::vector<double>& from, const PtpMove& move,
                                   const AvoidOptions& options, const PlanOptions& plan) {
  const Clock::time_point start = Clock::now();
  const auto deadline = start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(options.time_budget));
  AvoidingMove out;
  out.move = move;
  const std::vector<Move> direct{Move{move}};
  auto planned = plan_moves(kinematics, from, direct, plan);
  if (planned || !planned.error().detail_as<CollisionDetail>() || !move.waypoints.empty()) {
    out.planning_s = seconds_since(start);
    if (!planned) return planned.error();
    return out;
  }
  // Where the move ends, as the planner finds it (the IK solution nearest the start).
  std::vector<double> target = from;
  if (const auto* joints = std::get_if<std::vector<std::optional<double>>>(&move.target)) {
    for (std::size_t j = 0; j < target.size() && j < joints->size(); ++j)
      if ((*joints)[j]) target[j] = *(*joints)[j];
  } else {
    auto solved = kinematics.nearest_joints(std::get<CartesianGoal>(move.target), from);
    if (!solved) return solved.error();
    target = std::move(solved).value();
  }
  // Each search's path through more and more waypoints on its own lines (the timed motion
  // hugs them closer), then another seed.
  for (std::uint32_t attempt = 0; Clock::now() < deadline; ++attempt) {
    auto states = search(kinematics, from, target, options, options.seed + 1000 * attempt, deadline);
    if (!states) return states.error();  // out of time, or no path can exist (the target touches)
    for (int parts : {1, 2, 4, 8}) {
      if (Clock::now() >= deadline) break;
      PtpMove around = move;
      around.waypoints = waypoints_of(*states, parts);
      if (plan_moves(kinematics, from, std::vector<Move>{Move{around}}, plan)) {
        out.move = std::move(around);
        out.avoided = true;
        out.waypoints = out.move.waypoints.size();
        out.planning_s = seconds_since(start);
        return out;
      }
    }
  }
  return not_found(options.time_budget);
}

}  // namespace armctl::arm
