// Synthetic touched points for the fit tests: a "true" arm (the shipped one with its zeros
// off by a few degrees and its lengths by a few millimetres, loaded through the arm file's
// link_lengths like any calibrated arm), poses spread over its joints' travel, where its tool
// point truly is there (the motion layer's kinematics of the true arm, not the fit's chain),
// plus noise, and what the nominal arm's joints read at those poses.
#pragma once

#include <map>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <fmt/core.h>

#include "arm_files.hpp"
#include "calibration/touched_points.hpp"

namespace armctl::calibration::testing {

struct Truth {
  std::map<std::string, double> zero_error;  // joint -> true value minus reading (rad or m)
  std::map<std::string, double> length;      // URDF joint -> its origin's true length (m)
};

// The true arm: the shipped one with `truth.length` as its link lengths.
inline arm::ArmModel true_arm(const std::string& arm, const Truth& truth) {
  auto doc = arm::testing::arm_json(arm);
  for (const auto& [joint, length] : truth.length) doc["link_lengths"][joint] = fmt::format("{:.9f}mm", length * 1e3);
  return arm::testing::parse(arm, doc).value();
}

struct PointOptions {
  int count = 30;
  double noise_sigma = 0.0001;  // m, per axis
  double noise_max = 0.0003;    // m: no point is off by more
  double travel = 0.7;          // the fraction of each joint's limits the poses use, about the middle
  unsigned seed = 1;
  int unmoved_joint = -1;       // this joint stands at the same reading at every point
  bool unmoved_at_middle = false;  // that reading: the middle of its limits (else a tenth off it)
};

inline std::vector<TouchedPoint> touched_points(const arm::ArmModel& nominal, const Truth& truth,
                                                const PointOptions& o) {
  const arm::ArmModel real = true_arm(nominal.name, truth);
  std::mt19937 random(o.seed);
  std::normal_distribution<double> noise(0, o.noise_sigma);
  std::vector<TouchedPoint> out;
  const int n = nominal.chain_joints();
  for (int k = 0; k < o.count; ++k) {
    TouchedPoint p;
    p.name = fmt::format("P{}", k + 1);
    motion::JointVector q(n);
    for (int i = 0; i < n; ++i) {
      const arm::JointLimits& l = nominal.joints[std::size_t(i)].limits;
      const double mid = (l.lower + l.upper) / 2, half = (l.upper - l.lower) / 2 * o.travel;
      const double reading = i == o.unmoved_joint ? mid + (o.unmoved_at_middle ? 0.0 : 0.1 * half) : std::uniform_real_distribution<double>(mid - half, mid + half)(random);
      auto e = truth.zero_error.find(nominal.joints[std::size_t(i)].name);
      q[i] = reading + (e == truth.zero_error.end() ? 0.0 : e->second);
      p.joints.push_back(reading);
    }
    const motion::Pose link = real.kinematics->forward(q);
    Eigen::Vector3d e(noise(random), noise(random), noise(random));
    if (e.norm() > o.noise_max) e *= o.noise_max / e.norm();
    p.position = link.position + link.orientation * real.tool.position + e;
    out.push_back(p);
  }
  return out;
}

}  // namespace armctl::calibration::testing
