// The planning scene's costs (docs/scene.md), against issue 23's targets and a naive baseline
// measured in the same run:
// - one configuration checked (collides), per arm, the arm alone and with 20 objects around
//   it: target 5 us; naive: FCL on every checked pair, no bounding-box test first;
// - a whole 500 mm LIN of the SCARA checked (check_motion, 2 mm resolution): target 1 ms;
//   naive: a check every millisecond of the motion.
// - `--avoid` around one box (the xArm behind the box of examples/scenes/xarm-desk.json, the
//   direct move refused): the whole avoiding_move (the direct plan refused, the search, the
//   simplification, the waypoints' plan checked), median and p95 over 50 seeds: target median
//   100 ms; the search and simplification alone against a naive baseline: OMPL's stock
//   SimpleSetup (the same RRTConnect, its own discrete motion check at one fixed joint-space
//   resolution fine enough for 2 mm anywhere, its time-based simplifier).
// Times are thread CPU time (the machine is shared).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <ctime>
#include <random>
#include <string>
#include <vector>

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fmt/core.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>

#include <algorithm>

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include "bench_report.hpp"
#include "arm/arm_kinematics.hpp"
#include "arm/avoid_path.hpp"
#include "arm/plan_moves.hpp"
#include "scene/scene.hpp"
#include "scene/collision_world.hpp"
#include "scene/motion_check.hpp"

namespace {

using namespace armctl;

using armctl::bench::print;
using armctl::bench::thread_cpu_ns;

std::shared_ptr<fcl::CollisionGeometryd> geometry(const motion::Shape& s) {
  switch (s.kind) {
    case motion::Shape::Kind::box: return std::make_shared<fcl::Boxd>(s.size.x(), s.size.y(), s.size.z());
    case motion::Shape::Kind::cylinder: return std::make_shared<fcl::Cylinderd>(s.size.x(), s.size.y());
    case motion::Shape::Kind::sphere: return std::make_shared<fcl::Sphered>(s.size.x());
    case motion::Shape::Kind::capsule: return std::make_shared<fcl::Capsuled>(s.size.x(), s.size.y());
  }
  return nullptr;
}

// Objects around the arm, none touching it at zero (placed in a ring outside its base).
scene::Scene ring_of(int count, double reach, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0, 1);
  scene::Scene s;
  for (int k = 0; k < count; ++k) {
    scene::SceneObject o;
    o.name = "o" + std::to_string(k);
    o.shape.kind = static_cast<motion::Shape::Kind>(k % 3);
    o.shape.size = {0.01 + 0.03 * unit(rng), 0.01 + 0.03 * unit(rng), 0.01 + 0.03 * unit(rng)};
    const double r = reach * (0.4 + 0.6 * unit(rng)), a = 2 * M_PI * unit(rng);
    o.shape.pose.translation() = Eigen::Vector3d(r * std::cos(a), r * std::sin(a), reach * unit(rng));
    s.objects.push_back(o);
  }
  return s;
}

// Random configurations that touch nothing (a check's usual case: it runs to the end).
std::vector<std::vector<double>> free_configurations(const arm::ArmModel& m, const scene::CollisionWorld& w, int n) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<std::vector<double>> out;
  while (int(out.size()) < n) {
    std::vector<double> q;
    for (const auto& j : m.joints) q.push_back(j.limits.lower + (j.limits.upper - j.limits.lower) * unit(rng));
    if (!w.collides(q)) out.push_back(q);
  }
  return out;
}

// The naive check: every moving link shape against every object and every link shape of a
// link it is not joined to, straight to FCL.
struct Naive {
  struct Item {
    int body;
    motion::Shape shape;
    std::shared_ptr<fcl::CollisionGeometryd> g;
  };
  std::vector<Item> links, objects;
  std::shared_ptr<const motion::LinkBodies> bodies;
  bool collides(const std::vector<double>& q, std::vector<Eigen::Isometry3d>& poses) const {
    bodies->poses(q, poses);
    fcl::CollisionRequestd req;
    for (std::size_t i = 0; i < links.size(); ++i) {
      const auto& a = links[i];
      const Eigen::Isometry3d ta = poses[std::size_t(a.body)] * a.shape.pose;
      if (!bodies->moves(a.body)) continue;
      for (const auto& o : objects) {
        fcl::CollisionResultd res;
        if (fcl::collide(a.g.get(), ta, o.g.get(), o.shape.pose, req, res)) return true;
      }
      for (std::size_t j = 0; j < links.size(); ++j) {
        const auto& b = links[j];
        if (b.body == a.body || bodies->bodies[std::size_t(b.body)].parent == a.body ||
            bodies->bodies[std::size_t(a.body)].parent == b.body)
          continue;
        fcl::CollisionResultd res;
        if (fcl::collide(a.g.get(), ta, b.g.get(), poses[std::size_t(b.body)] * b.shape.pose, req, res)) return true;
      }
    }
    return false;
  }
};

Naive naive_of(const arm::ArmModel& m, const scene::Scene& s) {
  Naive n;
  n.bodies = m.bodies;
  for (std::size_t b = 0; b < m.bodies->bodies.size(); ++b)
    for (const auto& sh : m.bodies->bodies[b].shapes) n.links.push_back({int(b), sh, geometry(sh)});
  for (const auto& o : s.objects) n.objects.push_back({-1, o.shape, geometry(o.shape)});
  return n;
}

void bench_configurations(const char* name) {
  const arm::ArmKinematics kin(arm::load_arm_model(arm::arm_file_path(name)).value());
  for (int objects : {0, 20}) {
    const scene::Scene s = ring_of(objects, kin.model().reach, 5);
    auto with = kin.with_scene(s).value();
    const auto& w = *with->collisions();
    const auto qs = free_configurations(kin.model(), w, 20000);
    for (int i = 0; i < 1000; ++i) benchmark::DoNotOptimize(w.collides(qs[std::size_t(i)]));
    double t0 = thread_cpu_ns();
    for (const auto& q : qs) benchmark::DoNotOptimize(w.collides(q));
    const double us = (thread_cpu_ns() - t0) / double(qs.size()) / 1e3;
    const Naive naive = naive_of(kin.model(), s);
    std::vector<Eigen::Isometry3d> poses;
    t0 = thread_cpu_ns();
    for (const auto& q : qs) benchmark::DoNotOptimize(naive.collides(q, poses));
    const double naive_us = (thread_cpu_ns() - t0) / double(qs.size()) / 1e3;
    const std::string figure = fmt::format("scene_check_{}_{}_objects", name, objects);
    print(figure, us, "us", 5.0);
    print(figure + "_vs_naive", us, "us", naive_us);
  }
}

double percentile(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, std::size_t(p * double(v.size() - 1) + 0.5))];
}

void bench_lin() {
  const arm::ArmKinematics kin(arm::load_arm_model(arm::arm_file_path("scara")).value());
  auto with = kin.with_scene(scene::Scene{}).value();  // the line's own check: the arm against itself
  const std::vector<double> start(std::size_t(kin.joint_count()), 0.0);
  // To the line's start (the tool pitched 30 deg: straight down is a wrist singularity), then
  // 500 mm across the front of the arm at 100 mm/s.
  arm::PtpMove to_start;
  arm::CartesianGoal g;
  g.position = Eigen::Vector3d(0.35, -0.25, 0.3);
  g.roll = M_PI;
  g.pitch = M_PI / 6;
  g.yaw = 0;
  to_start.target = g;
  arm::CartesianMove lin;
  lin.goal.position = Eigen::Vector3d(0.35, 0.25, 0.3);
  lin.speed = 0.1;
  auto plan = arm::plan_moves(*with, start, std::vector<arm::Move>{arm::Move{to_start}, arm::Move{lin}});
  if (!plan) {
    std::printf("bench_scene: the 500 mm LIN does not plan: %s\n", plan.error().message.c_str());
    return;
  }
  const auto& motion = plan->pieces.back().motion;
  // A motion's sample writes every joint into vectors sized by the caller.
  std::vector<double> v(start.size()), a(start.size());
  auto sample = [&](double t, std::vector<double>& q) {
    q.resize(start.size());
    motion.sample(t, q, v, a);
  };
  const auto& w = *with->collisions();
  const int n = 50;
  std::size_t checks = 0, queries = 0;
  // The median of single checks: one check is a millisecond, so a busy machine's
  // interruptions land in a few of them rather than in the figure.
  std::vector<double> each;
  for (int i = 0; i < 4 * n; ++i) {
    const double began = thread_cpu_ns();
    const scene::MotionCheck m = scene::check_motion(w, motion.duration, sample);
    each.push_back((thread_cpu_ns() - began) / 1e6);
    checks = m.checks;
    queries = m.queries;
  }
  const double ms = percentile(each, 0.5);
  double t0 = thread_cpu_ns();
  std::vector<double> q;
  for (int i = 0; i < n; ++i) {
    for (double t = 0; t <= motion.duration; t += 0.001) {
      sample(t, q);
      benchmark::DoNotOptimize(w.collides(q));
      (void)w.clearance(q);
    }
  }
  const double naive_ms = (thread_cpu_ns() - t0) / n / 1e6;
  // What of it is the motion's own sampling (a LIN solves IK at every sample): as many
  // samples as the check takes (two per step).
  t0 = thread_cpu_ns();
  for (int i = 0; i < n; ++i)
    for (std::size_t k = 0; k < 2 * checks; ++k) sample(motion.duration * double(k) / double(2 * checks), q);
  const double sampling_ms = (thread_cpu_ns() - t0) / n / 1e6;
  std::printf("bench_scene: the 500 mm LIN takes %.2f s; %zu checks of %zu pairs, %zu pair queries; sampling the motion "
              "takes %.3f ms of the check\n",
              motion.duration, checks, w.pairs_checked(), queries, sampling_ms);
  print("scene_check_lin_500mm", ms, "ms", 1.0);
  print("scene_check_lin_500mm_vs_naive", ms, "ms", naive_ms);
}

// The naive baseline: OMPL's stock setup, collision checks every `step` of joint space along
// an edge (the fraction of the space's extent that moves no point more than 2 mm in the worst
// direction), simplified by OMPL's time-based simplifier.
double naive_avoid_ms(const arm::ArmKinematics& kin, const std::vector<double>& from, const std::vector<double>& to) {
  namespace ob = ompl::base;
  const auto& world = *kin.collisions();
  const int n = kin.model().chain_joints();
  auto space = std::make_shared<ob::RealVectorStateSpace>(unsigned(n));
  ob::RealVectorBounds bounds{unsigned(n)};
  double reach2 = 0;
  for (int j = 0; j < n; ++j) {
    bounds.setLow(unsigned(j), kin.model().joints[std::size_t(j)].limits.lower);
    bounds.setHigh(unsigned(j), kin.model().joints[std::size_t(j)].limits.upper);
    std::vector<double> e(from.size(), 0.0);
    e[std::size_t(j)] = 1;
    const double r = world.displacement_bound(std::vector<double>(from.size(), 0.0), e);
    reach2 += r * r;
  }
  space->setBounds(bounds);
  ompl::geometric::SimpleSetup setup(space);
  auto full = [&](const ob::State* s) {
    std::vector<double> q = from;
    for (int j = 0; j < n; ++j) q[std::size_t(j)] = s->as<ob::RealVectorStateSpace::StateType>()->values[j];
    return q;
  };
  setup.setStateValidityChecker([&](const ob::State* s) { return !world.collides(full(s)); });
  setup.getSpaceInformation()->setStateValidityCheckingResolution(scene::kCheckResolution / std::sqrt(reach2) /
                                                                   space->getMaximumExtent());
  setup.setPlanner(std::make_shared<ompl::geometric::RRTConnect>(setup.getSpaceInformation()));
  ob::ScopedState<ob::RealVectorStateSpace> a(space), b(space);
  for (int j = 0; j < n; ++j) {
    a[unsigned(j)] = from[std::size_t(j)];
    b[unsigned(j)] = to[std::size_t(j)];
  }
  setup.setStartAndGoalStates(a, b);
  const double t0 = thread_cpu_ns();
  if (setup.solve(5.0) != ob::PlannerStatus::EXACT_SOLUTION) return -1;
  setup.simplifySolution(0.5);
  return (thread_cpu_ns() - t0) / 1e6;
}

void bench_avoid() {
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
  ompl::RNG::setSeed(1);  // the baseline's generators: each draws the next seed from this one
  const arm::ArmKinematics plain(arm::load_arm_model(arm::arm_file_path("xarm")).value());
  auto kin = plain.with_scene(scene::load_scene(std::string(ARMCTL_SOURCE_DIR) + "/examples/scenes/xarm-desk.json").value())
                 .value();
  const std::vector<double> start(std::size_t(kin->joint_count()), 0.0);
  arm::PtpMove move;
  arm::CartesianGoal goal;
  goal.position = Eigen::Vector3d(0.15, -0.19, 0.04);
  move.target = goal;
  const std::vector<double> target = kin->nearest_joints(goal, start).value();
  std::vector<double> whole, search, naive;
  std::size_t waypoints = 0, failed = 0;
  for (std::uint32_t seed = 1; seed <= 50; ++seed) {
    arm::AvoidOptions o;
    o.seed = seed;
    double t0 = thread_cpu_ns();
    auto around = arm::avoiding_move(*kin, start, move, o);
    whole.push_back((thread_cpu_ns() - t0) / 1e6);
    if (!around || !around->avoided) ++failed;
    else waypoints += around->waypoints;
    t0 = thread_cpu_ns();
    (void)arm::collision_free_waypoints(*kin, start, target, o);
    search.push_back((thread_cpu_ns() - t0) / 1e6);
    naive.push_back(naive_avoid_ms(*kin, start, target));
  }
  std::printf("bench_scene: --avoid behind the box: %zu of 50 seeds failed, %.1f waypoints on average\n", failed,
              double(waypoints) / double(50 - failed));
  print("scene_avoid_xarm_box_median", percentile(whole, 0.5), "ms", 100.0);
  print("scene_avoid_xarm_box_p95", percentile(whole, 0.95), "ms", 1000.0);
  print("scene_avoid_search_median_vs_naive", percentile(search, 0.5), "ms", percentile(naive, 0.5));
  print("scene_avoid_search_p95_vs_naive", percentile(search, 0.95), "ms", percentile(naive, 0.95));
}

}  // namespace

// `bench_scene [avoid|configurations|lin]...`: only those parts (a profile of one); all by default.
int main(int argc, char** argv) {
  const std::vector<std::string> parts(argv + 1, argv + argc);
  auto wanted = [&](const char* part) { return parts.empty() || std::find(parts.begin(), parts.end(), part) != parts.end(); };
  if (wanted("avoid")) bench_avoid();
  if (wanted("configurations")) {
    bench_configurations("xarm");
    bench_configurations("scara");
  }
  if (wanted("lin")) bench_lin();
  return 0;
}
