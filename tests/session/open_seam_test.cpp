// The device seam is open: a device kind (URI kind -> factory), a protocol and an arm family
// that armctl does not ship are added from this file alone, with no edit under src/, and the
// arm they make is opened by URI and moved through the Arm API like a shipped one
// (docs/architecture.md "How to add an arm, a device, an app").
#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "arm/arm_families.hpp"
#include "arm/protocols.hpp"
#include "core/clock.hpp"
#include "session/arm_session.hpp"
#include "session/device_kinds.hpp"

namespace armctl::session {
namespace {

using ::testing::HasSubstr;
constexpr double kDeg = std::numbers::pi / 180;

// ---- the arm family: a planar arm of two revolute joints about z -----------------------

class Planar2Kinematics final : public motion::Kinematics {
 public:
  Planar2Kinematics(const motion::UrdfChain& chain, std::span<const motion::PositionLimits> limits)
      : chain_(chain), limits_(limits.begin(), limits.end()) {
    l1_ = chain.joints[1].from_previous.translation().head<2>().norm();
    l2_ = chain.tip_from_last.translation().head<2>().norm();
  }
  std::string_view family() const override { return "planar2"; }
  int joint_count() const override { return 2; }
  motion::Pose forward(const motion::JointVector& q) const override {
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    for (int i = 0; i < 2; ++i) t = t * chain_.joints[std::size_t(i)].from_previous * Eigen::AngleAxisd(q[i], Eigen::Vector3d::UnitZ());
    t = t * chain_.tip_from_last;
    return {t.translation(), Eigen::Quaterniond(t.rotation())};
  }
  // Position only (the family reaches positions with the nearest orientation): elbow left
  // and right, nearest first.
  Result<std::vector<motion::IkSolution>> inverse(const motion::IkRequest& request,
                                                  const motion::JointVector& near) const override {
    const double x = request.target.position.x(), y = request.target.position.y();
    const double c2 = (x * x + y * y - l1_ * l1_ - l2_ * l2_) / (2 * l1_ * l2_);
    if (!(std::abs(c2) <= 1)) return Error{ErrorKind::invalid_argument, "planar2: the point is beyond reach"};
    std::vector<motion::IkSolution> out;
    for (double sign : {1.0, -1.0}) {
      const double q2 = sign * std::acos(c2);
      const double q1 = std::atan2(y, x) - std::atan2(l2_ * std::sin(q2), l1_ + l2_ * std::cos(q2));
      motion::IkSolution s;
      s.joints = motion::JointVector(2);
      s.joints << q1, q2;
      bool inside = true;
      for (int i = 0; i < 2; ++i) inside = inside && s.joints[i] >= limits_[std::size_t(i)].lower && s.joints[i] <= limits_[std::size_t(i)].upper;
      s.configuration.elbow = sign > 0 ? motion::Elbow::left : motion::Elbow::right;
      if (inside) out.push_back(s);
    }
    if (out.empty()) return Error{ErrorKind::invalid_argument, "planar2: no solution inside the joint limits"};
    std::sort(out.begin(), out.end(), [&](const auto& a, const auto& b) { return (a.joints - near).norm() < (b.joints - near).norm(); });
    return out;
  }
  motion::Jacobian jacobian(const motion::JointVector& q) const override {
    motion::Jacobian j(6, 2);
    const double s1 = std::sin(q[0]), c1 = std::cos(q[0]), s12 = std::sin(q[0] + q[1]), c12 = std::cos(q[0] + q[1]);
    j.col(0) << -l1_ * s1 - l2_ * s12, l1_ * c1 + l2_ * c12, 0, 0, 0, 1;
    j.col(1) << -l2_ * s12, l2_ * c12, 0, 0, 0, 1;
    return j;
  }
  motion::Singularity singularity(const motion::JointVector& q, double tolerance) const override {
    return std::abs(std::sin(q[1])) < tolerance ? motion::Singularity::arm_stretched : motion::Singularity::none;
  }

 private:
  motion::UrdfChain chain_;
  std::vector<motion::PositionLimits> limits_;
  double l1_ = 0, l2_ = 0;
};

Result<std::unique_ptr<motion::Kinematics>> make_planar2(const motion::UrdfChain& chain,
                                                         std::span<const motion::PositionLimits> limits) {
  if (chain.joints.size() != 2) return Error{ErrorKind::invalid_config, "planar2 needs 2 chain joints"};
  return std::unique_ptr<motion::Kinematics>(std::make_unique<Planar2Kinematics>(chain, limits));
}

// ---- the device kind: `fake:NAME`, a device that reaches its targets linearly in time ---

struct FakeBench {  // what the device talks through: here, what the test reads back
  std::string name;
  std::vector<std::vector<double>> moves;  // every move's targets, in device units
};

class FakeArmDevice final : public arm::ArmDevice {
 public:
  FakeArmDevice(arm::Protocol protocol, std::shared_ptr<FakeBench> bench)
      : protocol_(protocol), bench_(std::move(bench)), from_(2, 2000.0), to_(2, 2000.0) {}
  arm::Protocol protocol() const override { return protocol_; }
  std::string description() const override { return "fake bench " + bench_->name; }
  const Clock& clock() const override { return clock_; }
  Duration poll_interval() const override { return std::chrono::milliseconds(20); }
  Result<std::vector<double>> read_positions() override { return at(clock_.now()); }
  Status move(const std::vector<std::optional<double>>& targets, Duration duration) override {
    from_ = at(clock_.now());
    for (std::size_t i = 0; i < to_.size(); ++i) to_[i] = targets[i].value_or(from_[i]);
    start_ = clock_.now();
    end_ = start_ + duration;
    bench_->moves.push_back(to_);
    return Ok{};
  }
  Status stop() override {
    from_ = to_ = at(clock_.now());
    end_ = start_ = clock_.now();
    return Ok{};
  }
  Status set_torque(bool) override { return Ok{}; }
  Duration stream_period(bool) const override { return std::chrono::milliseconds(10); }
  Duration stream_latency() const override { return Duration{0}; }
  Status stream(const std::vector<double>& targets, const std::vector<double>&, Duration in) override {
    std::vector<std::optional<double>> t(targets.begin(), targets.end());
    return move(t, in);
  }
  Status idle(Duration d) override {
    clock_.advance(d);
    return Ok{};
  }

 private:
  std::vector<double> at(TimePoint t) const {
    const double f = end_ <= start_ || t >= end_ ? 1.0 : std::chrono::duration<double>(t - start_) / (end_ - start_);
    std::vector<double> out(to_.size());
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = from_[i] + f * (to_[i] - from_[i]);
    return out;
  }

  arm::Protocol protocol_;
  std::shared_ptr<FakeBench> bench_;
  SimClock clock_;
  std::vector<double> from_, to_;
  TimePoint start_{}, end_{};
};

// Registered once per process, as a plugin's static registration would be.
void register_fakes() {
  static const bool done = [] {
    arm::ProtocolInfo fake_bus{"fake_bus", "channel", 4, {0, 4000}, "ticks", {}};
    EXPECT_TRUE(arm::register_protocol(fake_bus));
    EXPECT_TRUE(arm::register_arm_family({"planar2", make_planar2, {.reaches_nearest_orientation = true}}));
    EXPECT_TRUE(register_device_kind("fake", [](const DeviceRequest& r) -> Result<OpenedDevice> {
      const auto protocol = arm::find_protocol("fake_bus");
      if (!protocol) return protocol.error();
      if (!r.model.supports(*protocol))
        return Error{ErrorKind::invalid_argument, "fake: the arm has no fake_bus mapping"};
      auto bench = std::make_shared<FakeBench>();
      bench->name = r.parts.path;
      OpenedDevice out;
      out.device = std::make_unique<FakeArmDevice>(*protocol, bench);
      out.connection = bench;
      return out;
    }));
    return true;
  }();
  (void)done;
}

const std::string kArmFile = std::string(ARMCTL_SOURCE_DIR) + "/tests/session/open_seam/planar2.arm.json";

FakeBench& bench_of(ArmSession& s) { return *std::static_pointer_cast<FakeBench>(s.connection); }

TEST(OpenSeam, AFakeArmFamilyProtocolAndDeviceKindAreOpenedByUri) {
  register_fakes();
  auto opened = open_arm_session(kArmFile, "fake:bench1");
  ASSERT_TRUE(opened) << opened.error().message;
  ArmSession& s = **opened;
  EXPECT_EQ(s.arm->model().family, "planar2");
  EXPECT_EQ(s.arm->model().joint_count(), 2);
  EXPECT_EQ(s.arm->device().protocol().name(), "fake_bus");
  EXPECT_EQ(s.arm->device().description(), "fake bench bench1");
  EXPECT_EQ(s.arm->device().action_groups(), nullptr) << "a capability the device does not offer";
  EXPECT_FALSE(s.arm->model().joints[0].map(arm::Protocol::robot_commands));
  EXPECT_EQ(s.arm->model().joints[1].map(*arm::find_protocol("fake_bus"))->id, 2);
}

TEST(OpenSeam, TheFakeArmMovesThroughTheArmApi) {
  register_fakes();
  auto s = open_arm_session(kArmFile, "fake:bench2").value();
  arm::Arm& arm = *s->arm;

  // Joints: 40 deg and -80 deg, in the device's ticks by the arm file's maps (shoulder
  // 0..4000 over -160..160 deg; the elbow reversed).
  ASSERT_TRUE(arm.move_joints({40 * kDeg, -80 * kDeg}));
  auto at = arm.wait();
  ASSERT_TRUE(at) << at.error().message;
  EXPECT_NEAR(at->positions[0], 40 * kDeg, 1e-9);
  EXPECT_NEAR(at->positions[1], -80 * kDeg, 1e-9);
  ASSERT_EQ(bench_of(*s).moves.size(), 1u);
  EXPECT_NEAR(bench_of(*s).moves[0][0], 2500, 1e-6);
  EXPECT_NEAR(bench_of(*s).moves[0][1], 3000, 1e-6);

  // The tool to a point: the family's IK, the nearest solution, the planner's one duration.
  const motion::Pose goal_pose = arm.forward(arm.chain_of({-30 * kDeg, 60 * kDeg}));
  arm::CartesianGoal goal;
  goal.position = goal_pose.position;
  ASSERT_TRUE(arm.move_to(goal));
  ASSERT_TRUE(arm.wait());
  auto pose = arm.pose();
  ASSERT_TRUE(pose);
  EXPECT_LT((pose->position - goal_pose.position).norm(), 1e-6);

  // Beyond the joint limits: refused by the model, before the device is asked.
  const auto refused = arm.move_joints({170 * kDeg, std::nullopt});
  ASSERT_FALSE(refused);
  EXPECT_THAT(refused.error().message, HasSubstr("shoulder"));
  EXPECT_EQ(bench_of(*s).moves.size(), 2u);
}

TEST(OpenSeam, RegistriesRefuseDuplicatesAndNameWhatTheyKnow) {
  register_fakes();
  const auto twice = register_device_kind("fake", [](const DeviceRequest&) -> Result<OpenedDevice> {
    return Error{ErrorKind::unsupported, "never"};
  });
  ASSERT_FALSE(twice);
  EXPECT_THAT(twice.error().message, HasSubstr("device kind 'fake' is already registered"));
  EXPECT_FALSE(arm::register_arm_family({"xarm", make_planar2, {}}));
  EXPECT_FALSE(arm::register_protocol({"joint_bus", "number", 7, {0, 1}, "counts", {}}));

  const auto unknown = open_arm_session(kArmFile, "nowhere:x");
  ASSERT_FALSE(unknown);
  EXPECT_THAT(unknown.error().message, HasSubstr("unknown device kind 'nowhere' (known: sim, unix, serial, hid, fake)"));
  // The shipped xArm has no fake_bus mapping: the fake kind's own refusal.
  const auto xarm = open_arm_session("xarm", "fake:x");
  ASSERT_FALSE(xarm);
  EXPECT_THAT(xarm.error().message, HasSubstr("no fake_bus mapping"));
  EXPECT_THAT(arm::find_arm_family("delta").error().message, HasSubstr("known: xarm, scara, planar2"));
}

}  // namespace
}  // namespace armctl::session
