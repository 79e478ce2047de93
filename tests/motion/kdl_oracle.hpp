// KDL, built from the same URDF text by kdl_parser, as the independent oracle for armctl's
// kinematics (tests/motion) and its comparison (bench/motion). Also the random joint
// values both draw from.
#pragma once

#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <kdl/chain.hpp>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/frames.hpp>
#include <kdl/jntarray.hpp>
#include <kdl/tree.hpp>
#include <kdl_parser/kdl_parser.hpp>

#include "motion/kinematics.hpp"

namespace armctl::motion::testing {

inline std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline KDL::Chain kdl_chain(const std::string& urdf_text, const std::string& base, const std::string& tip) {
  KDL::Tree tree;
  if (!kdl_parser::treeFromString(urdf_text, tree)) throw std::runtime_error("kdl_parser refused the URDF");
  KDL::Chain chain;
  if (!tree.getChain(base, tip, chain)) throw std::runtime_error("KDL has no chain " + base + ".." + tip);
  return chain;
}

inline KDL::JntArray to_kdl(const JointVector& q) {
  KDL::JntArray a(unsigned(q.size()));
  for (int i = 0; i < q.size(); ++i) a(unsigned(i)) = q[i];
  return a;
}

inline JointVector from_kdl(const KDL::JntArray& a) {
  JointVector q(int(a.rows()));
  for (int i = 0; i < q.size(); ++i) q[i] = a(unsigned(i));
  return q;
}

inline Eigen::Isometry3d to_eigen(const KDL::Frame& f) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r) {
    t.translation()[r] = f.p(r);
    for (int c = 0; c < 3; ++c) t.linear()(r, c) = f.M(r, c);
  }
  return t;
}

inline KDL::Frame to_kdl(const Pose& p) {
  const Eigen::Matrix3d r = p.orientation.toRotationMatrix();
  return KDL::Frame(KDL::Rotation(r(0, 0), r(0, 1), r(0, 2), r(1, 0), r(1, 1), r(1, 2), r(2, 0), r(2, 1), r(2, 2)),
                    KDL::Vector(p.position.x(), p.position.y(), p.position.z()));
}

// Uniform joint values within the limits, from a fixed seed (reproducible failures).
class RandomJoints {
 public:
  RandomJoints(std::vector<PositionLimits> limits, std::uint64_t seed) : limits_(std::move(limits)), rng_(seed) {}
  JointVector operator()() {
    JointVector q(int(limits_.size()));
    for (std::size_t i = 0; i < limits_.size(); ++i) {
      q[int(i)] = std::uniform_real_distribution<double>(limits_[i].lower, limits_[i].upper)(rng_);
    }
    return q;
  }

 private:
  std::vector<PositionLimits> limits_;
  std::mt19937_64 rng_;
};

// Largest difference between two poses: position in m, orientation as the largest
// rotation-matrix entry difference (about the angle in rad for small differences).
inline double position_error(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return (a - b).norm(); }
inline double rotation_error(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) { return (a - b).cwiseAbs().maxCoeff(); }

}  // namespace armctl::motion::testing
