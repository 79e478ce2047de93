// The path planner (arm::plan_path: reach, the Cartesian path, its check along every
// sample, the timing) on the shipped xArm and SCARA arms with whatever numbers the fuzzer
// makes: each number is either raw bytes (NaN, infinity, 1e308, denormals) or one of the
// extremes people have typed (1e200 mm, 1e-300 mm/s). It must never crash or read out of
// bounds: every input is either refused with invalid_argument and a message, or planned
// into a motion whose duration is finite and whose joints are finite and inside the limits.
//
// Input: byte 0 picks the arm; then up to 4 segments of: a kind byte, then numbers for
// x, y, z (offsets from the start, m), via x, y, z, speed (m/s), angular speed (rad/s) and
// zone (m). A number is a tag byte then, for tag 0, 8 raw bytes.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <string>
#include <vector>

#include "arm/arm_model.hpp"
#include "arm/motion_planning.hpp"

namespace {

using namespace armctl;

void check(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "fuzz_path_plan: %s\n", what);
  std::abort();
}

struct Arm {
  arm::ArmModel model;
  std::vector<double> start;  // a bent pose in front of the arm, as the motion tests use
};

const Arm& arm_of(int which) {
  static const Arm arms[2] = {
      {arm::load_arm_model(ARMCTL_SOURCE_DIR "/config/xarm.arm.json").value(), {0.0, 0.5, 0.9, 0.6, 0.0, 0.0}},
      {arm::load_arm_model(ARMCTL_SOURCE_DIR "/config/scara.arm.json").value(), {0.15, 0.3, -0.8, 0.0, 0.0, 0.0, 0.0}},
  };
  return arms[which & 1];
}

class Reader {
 public:
  Reader(const std::uint8_t* data, std::size_t size) : p_(data), end_(data + size) {}
  bool empty() const { return p_ == end_; }
  std::uint8_t byte() { return p_ == end_ ? 0 : *p_++; }
  double number() {
    static const double kTable[] = {0.0,    0.05,    -0.05,   0.1,     1e-3,     1e-300,  -1e-300, 1e200,
                                    1e308,  -1e308,  1e-200,  5e-324,  1e300,    1e6,     0.2,     1.0};
    const std::uint8_t tag = byte();
    if (tag != 0) return kTable[tag % std::size(kTable)];
    double v = 0;
    std::uint8_t raw[8] = {};
    for (auto& b : raw) b = byte();
    std::memcpy(&v, raw, sizeof v);
    return v;
  }

 private:
  const std::uint8_t* p_;
  const std::uint8_t* end_;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Reader in(data, size);
  const Arm& a = arm_of(in.byte());
  const arm::ArmModel& model = a.model;
  motion::JointVector chain(model.chain_joints());
  for (int i = 0; i < chain.size(); ++i) chain[i] = a.start[std::size_t(i)];
  motion::Pose here = model.kinematics->forward(chain);
  here.position += here.orientation * model.tool.position;
  here.orientation = (here.orientation * model.tool.orientation).normalized();

  std::vector<motion::PathSegment> segments;
  while (!in.empty() && segments.size() < 4) {
    motion::PathSegment s;
    s.kind = in.byte() & 1 ? motion::SegmentKind::circ : motion::SegmentKind::lin;
    s.target = here;
    for (int k = 0; k < 3; ++k) s.target.position[k] += in.number();
    for (int k = 0; k < 3; ++k) s.via[k] = here.position[k] + in.number();
    s.speed = in.number();
    s.angular_speed = in.number();
    s.zone = in.number();
    segments.push_back(s);
  }
  if (segments.empty()) return 0;

  auto plan = arm::plan_path(model, a.start, segments);
  if (!plan) {
    check(plan.error().kind == ErrorKind::invalid_argument, "an error of another kind than invalid_argument");
    check(!plan.error().message.empty(), "an error without a message");
    return 0;
  }
  const arm::PlannedMotion& m = plan->motion;
  check(std::isfinite(m.duration) && m.duration > 0, "a plan whose duration is not finite and above 0");
  const std::size_t n = std::size_t(model.joint_count());
  std::vector<double> p(n), v(n), acc(n);
  for (int k = 0; k <= 16; ++k) {
    m.sample(m.duration * k / 16, p, v, acc);
    for (std::size_t j = 0; j < n; ++j) {
      check(std::isfinite(p[j]) && std::isfinite(v[j]) && std::isfinite(acc[j]), "a sample that is not finite");
      check(model.joints[j].limits.contains(p[j], 1e-6), "a sample outside the joint limits");
    }
  }
  return 0;
}
