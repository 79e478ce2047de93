// The analytic kinematics of both arms against KDL on the same chain (built from the same
// URDF file), in the same run:
//  - FK time per solve, against KDL's ChainFkSolverPos_recursive;
//  - IK time per solve (every solution), against 1 us and against KDL's numeric
//    ChainIkSolverPos_LMA (target: at least 100 times faster);
//  - IK success rate over random reachable poses (FK of random joints within the limits),
//    for both (target 100 %). Ours succeeds when every solution's FK is within 1e-9 m and
//    1e-9 of the pose and the joints the pose came from are among them; LMA when it
//    converges to within 1e-6 m and 1e-6 of the pose from the middle of the limits
//    (it ignores the limits; asked to stop at a weighted error of 1e-10).
#include <benchmark/benchmark.h>

#include <ctime>
#include <cstdio>
#include <string>
#include <vector>

#include <kdl/chainiksolverpos_lma.hpp>

#include "bench_report.hpp"
#include "kdl_oracle.hpp"
#include "motion/kinematics.hpp"
#include "motion/scara_kinematics.hpp"
#include "motion/xarm_kinematics.hpp"

namespace {

using namespace armctl::motion;
using MakeKinematics = decltype(&make_scara_kinematics);
// This thread's CPU time: the machine that runs the benchmarks is shared, and time spent
// preempted is not the solver's.
struct Clock {
  static double now() { return armctl::bench::thread_cpu_ns(); }
};

double ns_per(double elapsed_ns, std::size_t n) { return elapsed_ns / double(n); }

using armctl::bench::print;

void bench_arm(const std::string& arm, MakeKinematics make) {
  const std::string text = testing::read_text(std::string(ARMCTL_SOURCE_DIR) + "/config/" + arm + ".urdf");
  const UrdfChain chain = read_urdf_chain(text, "base_link", "tool").value();
  const auto limits = urdf_position_limits(chain);
  const auto kin = make(chain, limits).value();
  const KDL::Chain kdl = testing::kdl_chain(text, "base_link", "tool");

  testing::RandomJoints random(limits, 42);
  const std::size_t n = 200000;
  std::vector<JointVector> qs;
  std::vector<Pose> poses;
  qs.reserve(n);
  poses.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    qs.push_back(random());
    poses.push_back(kin->forward(qs.back()));
  }

  // Forward kinematics.
  auto t0 = Clock::now();
  for (const auto& q : qs) benchmark::DoNotOptimize(kin->forward(q));
  const double fk_ns = ns_per(Clock::now() - t0, n);
  KDL::ChainFkSolverPos_recursive kdl_fk(kdl);
  std::vector<KDL::JntArray> kqs;
  for (const auto& q : qs) kqs.push_back(testing::to_kdl(q));
  KDL::Frame f;
  t0 = Clock::now();
  for (const auto& q : kqs) {
    kdl_fk.JntToCart(q, f);
    benchmark::DoNotOptimize(f);
  }
  const double kdl_fk_ns = ns_per(Clock::now() - t0, n);
  print("kinematics_" + arm + "_fk", fk_ns, "ns", kdl_fk_ns);

  // Analytic IK: time over every pose, then check each.
  const JointVector near = JointVector::Zero(kin->joint_count());
  std::size_t solutions = 0;
  t0 = Clock::now();
  for (const auto& p : poses) {
    auto s = kin->inverse(IkRequest{p}, near);
    if (s.ok()) solutions += s->size();
    benchmark::DoNotOptimize(s);
  }
  const double ik_ns = ns_per(Clock::now() - t0, n);
  std::size_t ok = 0;
  for (std::size_t i = 0; i < n; ++i) {
    auto s = kin->inverse(IkRequest{poses[i]}, near);
    if (!s.ok()) continue;
    bool good = true, original = false;
    for (const auto& sol : *s) {
      const Pose back = kin->forward(sol.joints);
      good = good && testing::position_error(back.position, poses[i].position) < 1e-9 &&
             testing::rotation_error(back.orientation.toRotationMatrix(), poses[i].orientation.toRotationMatrix()) < 1e-9;
      original = original || (sol.joints - qs[i]).cwiseAbs().maxCoeff() < 1e-6;
    }
    ok += good && original;
  }

  // KDL's numeric IK from the middle of the limits, on fewer poses (it is slow).
  const std::size_t m = 5000;
  // Default weights (orientation 0.01), stopping at a weighted error of 1e-10: the
  // precision asked of ours, within the margin of the check below.
  KDL::ChainIkSolverPos_LMA lma(kdl, 1e-10);
  KDL::JntArray seed(kdl.getNrOfJoints()), out(kdl.getNrOfJoints());
  for (unsigned i = 0; i < seed.rows(); ++i) seed(i) = 0.5 * (limits[i].lower + limits[i].upper);
  std::vector<KDL::Frame> targets;
  for (std::size_t i = 0; i < m; ++i) targets.push_back(testing::to_kdl(poses[i]));
  std::vector<KDL::JntArray> lma_out(m, out);
  t0 = Clock::now();
  for (std::size_t i = 0; i < m; ++i) lma.CartToJnt(seed, targets[i], lma_out[i]);
  const double lma_ns = ns_per(Clock::now() - t0, m);
  std::size_t lma_ok = 0;
  for (std::size_t i = 0; i < m; ++i) {
    kdl_fk.JntToCart(lma_out[i], f);
    const Eigen::Isometry3d t = testing::to_eigen(f);
    lma_ok += testing::position_error(t.translation(), poses[i].position) < 1e-6 &&
              testing::rotation_error(t.linear(), poses[i].orientation.toRotationMatrix()) < 1e-6;
  }

  print("kinematics_" + arm + "_ik", ik_ns, "ns", 1000.0);
  print("kinematics_" + arm + "_ik_speedup_vs_kdl_lma", lma_ns / ik_ns, "x", 100.0);
  print("kinematics_" + arm + "_kdl_lma_ik", lma_ns, "ns", ik_ns);
  print("kinematics_" + arm + "_ik_success", 100.0 * double(ok) / double(n), "%", 100.0);
  print("kinematics_" + arm + "_kdl_lma_ik_success", 100.0 * double(lma_ok) / double(m), "%", 100.0);
  std::printf("# %s: %.2f analytic solutions per pose\n", arm.c_str(), double(solutions) / double(n));
}

}  // namespace

int main() {
  bench_arm("scara", make_scara_kinematics);
  bench_arm("xarm", make_xarm_kinematics);
  return 0;
}
