// Leader and follower (jog/run_follow.hpp) on simulated arms and simulated time: the leader's
// servos moved by hand along a recorded-like motion, the follower tracking it joint to joint
// (xArm to xArm) and tool to tool (xArm to SCARA), a leader that falls silent, a leader past
// the follower's limits, the recording of the session, and bad mapping options.
#include "jog/run_follow.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "arm/arm.hpp"
#include "arm/arm_files.hpp"
#include "arm/bus_arm_device.hpp"
#include "arm/rc_arm_device.hpp"
#include "files/recording_file.hpp"
#include "joint_bus/sim_fixture.hpp"
#include "robot_commands/sim_links.hpp"

namespace armctl::jog {
namespace {

using arm::testing::shipped;
constexpr double kDeg = std::numbers::pi / 180;
double seconds(Duration d) { return std::chrono::duration<double>(d).count(); }

// An xArm on its emulated board whose servos a hand can move (torque off).
struct HandXarm {
  robot_commands::testing::EmulatedLink link{115200};
  robot_commands::Client client{link};
  arm::Arm arm{shipped("xarm"), std::make_unique<arm::RcArmDevice>(shipped("xarm"), client)};
  bool hand(int joint, double si) {
    const auto& map = *arm.model().joints[std::size_t(joint)].map(arm::Protocol::robot_commands);
    return link.emulator().servos().move_by_hand(std::uint8_t(map.id), std::round(map.to_device(si)));
  }
};

// The hand's motion: from `from` (every joint, SI) by `by` over `seconds`, smoothly, then still.
std::vector<double> hand_at(const std::vector<double>& from, const std::vector<double>& by, double t, double seconds) {
  const double s = t >= seconds ? 1.0 : 0.5 - 0.5 * std::cos(std::numbers::pi * t / seconds);
  std::vector<double> q = from;
  for (std::size_t i = 0; i < q.size(); ++i) q[i] += s * by[i];
  return q;
}

FollowRunOptions polled(double end_s, std::function<void(double)> hand) {
  FollowRunOptions o;
  o.leader_thread = false;
  o.record_rate = 50;
  auto start = std::make_shared<std::optional<TimePoint>>();
  auto t = std::make_shared<double>(0);
  o.before_cycle = [start, t, hand](TimePoint now) {
    if (!*start) *start = now;
    *t = seconds(now - **start);
    hand(*t);
  };
  o.stop = [t, end_s] { return *t >= end_s; };
  return o;
}

void bend(arm::Arm& a, std::vector<std::optional<double>> q) {
  ASSERT_TRUE(a.move_joints(q));
  ASSERT_TRUE(a.wait());
}

TEST(Follow, AnXarmFollowsAnXarmMovedByHandJointToJoint) {
  HandXarm leader, follower;
  bend(follower.arm, {0.0, 0.5, 1.0, 1.0, 0.0, std::nullopt});
  bend(leader.arm, {0.0, 0.5, 1.0, 1.0, 0.0, std::nullopt});
  const auto from = leader.arm.read().value().positions;
  const std::vector<double> by{0.5, -0.2, 0.3, 0.0, 0.4, 0.0};
  auto o = polled(2.5, [&](double t) {
    const auto q = hand_at(from, by, t, 1.5);
    for (int j = 0; j < 5; ++j) ASSERT_TRUE(leader.hand(j, q[std::size_t(j)]));
  });
  auto r = run_follow(leader.arm, follower.arm, o);
  ASSERT_TRUE(r) << r.error().message;
  ASSERT_TRUE(follower.arm.wait());
  const auto end = follower.arm.read().value().positions;
  for (int j = 0; j < 5; ++j) EXPECT_NEAR(end[std::size_t(j)], from[std::size_t(j)] + by[std::size_t(j)], 0.6 * kDeg) << j;
  EXPECT_FALSE(r->leader_was_lost);
  EXPECT_GT(r->leader_reads, 100u);
  std::printf("xarm -> xarm: tracking error largest %.1f mm, mean %.1f mm\n", r->largest_tracking_error * 1000,
              r->mean_tracking_error * 1000);
  EXPECT_LT(r->largest_tracking_error, 0.03);
  // The leader's torque is back on (once the frame has crossed the line): a hand can no
  // longer move it.
  ASSERT_TRUE(leader.arm.read());
  EXPECT_FALSE(leader.hand(0, 0.0));
  // The session as recordings a replay reads.
  EXPECT_GT(r->follower_recording.samples.size(), 100u);
  auto back = files::parse_recording(files::format_recording(r->follower_recording));
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_EQ(back->arm, "xarm");
}

TEST(Follow, TheScaraFollowsAnXarmsToolAlongAHandMotion) {
  HandXarm leader;
  bend(leader.arm, {0.0, 0.5, 1.0, 1.0, 0.0, std::nullopt});
  std::unique_ptr<joint_sim::SimArm> sim = test::make_arm(115200);
  joint_bus::BusMaster master{sim->link()};
  arm::Arm follower{shipped("scara"),
                    std::make_unique<arm::BusArmDevice>(shipped("scara"), master, sim->link(), "simulated SCARA")};
  bend(follower, {0.15, 0.0, 60 * kDeg, std::nullopt, std::nullopt, std::nullopt, std::nullopt});
  const auto from = leader.arm.read().value().positions;
  const Eigen::Vector3d leader_tool = leader.arm.pose().value().position;
  const Eigen::Vector3d follower_tool = follower.pose().value().position;
  // The base turned by 0.3 rad and the arm lowered: the tool moves some 60 mm around and down.
  const std::vector<double> by{0.3, 0.15, 0.0, 0.0, 0.0, 0.0};
  auto o = polled(3.0, [&](double t) {
    const auto q = hand_at(from, by, t, 2.0);
    for (int j = 0; j < 5; ++j) ASSERT_TRUE(leader.hand(j, q[std::size_t(j)]));
  });
  auto r = run_follow(leader.arm, follower, o);
  ASSERT_TRUE(r) << r.error().message;
  ASSERT_TRUE(follower.wait());
  const Eigen::Vector3d leader_moved = leader.arm.pose().value().position - leader_tool;
  const Eigen::Vector3d follower_moved = follower.pose().value().position - follower_tool;
  std::printf("xarm -> scara: leader tool moved %.1f mm, follower %.1f mm, %.2f mm apart; tracking error largest "
              "%.1f mm, mean %.1f mm\n",
              leader_moved.norm() * 1000, follower_moved.norm() * 1000, (leader_moved - follower_moved).norm() * 1000,
              r->largest_tracking_error * 1000, r->mean_tracking_error * 1000);
  EXPECT_GT(leader_moved.norm(), 0.03);
  EXPECT_LT((leader_moved - follower_moved).norm(), 0.002);
}

TEST(Follow, ALeaderThatFallsSilentLeavesTheFollowerAtRest) {
  HandXarm leader, follower;
  bend(follower.arm, {0.0, 0.5, 1.0, 1.0, 0.0, std::nullopt});
  bend(leader.arm, {0.0, 0.5, 1.0, 1.0, 0.0, std::nullopt});
  const auto from = leader.arm.read().value().positions;
  const std::vector<double> by{0.6, 0.0, 0.0, 0.0, 0.0, 0.0};
  bool cut = false;
  std::vector<std::vector<double>> after_cut;
  auto o = polled(3.0, [&](double t) {
    const auto q = hand_at(from, by, t, 2.0);
    ASSERT_TRUE(leader.hand(0, q[0]));
    if (t >= 0.8 && !cut) {
      cut = true;
      leader.link.set_deaf(true);  // the cable is pulled: no more replies
    }
  });
  o.on_cycle = [&](const FollowStatus& s) {
    if (!s.leader_lost.empty()) after_cut.push_back(s.follower.positions);
  };
  auto r = run_follow(leader.arm, follower.arm, o);
  // The leader cannot take its torque back without its link: that is the error.
  ASSERT_FALSE(r);
  ASSERT_FALSE(after_cut.empty());
  // Once lost, the follower slowed to rest and held: its last points are all one.
  ASSERT_GT(after_cut.size(), 20u);
  const auto& last = after_cut.back();
  const auto& before_last = after_cut[after_cut.size() - 10];
  for (std::size_t i = 0; i < last.size(); ++i) EXPECT_NEAR(last[i], before_last[i], 1e-9);
  // And it had stopped short of where the hand went on to.
  EXPECT_LT(last[0], from[0] + 0.6 - 0.1);
}

TEST(Follow, ALeaderBeyondTheFollowersRangeHoldsItAtTheEnd) {
  HandXarm leader, follower;
  // The follower's base offset so that the leader's turn takes it past its upper limit.
  bend(follower.arm, {0.0, 0.5, 1.0, 1.0, 0.0, std::nullopt});
  bend(leader.arm, {0.0, 0.5, 1.0, 1.0, 0.0, std::nullopt});
  const auto from = leader.arm.read().value().positions;
  const double upper = follower.arm.model().joints[0].limits.upper;
  auto o = polled(3.0, [&](double t) { ASSERT_TRUE(leader.hand(0, hand_at(from, {1.2, 0, 0, 0, 0, 0}, t, 1.5)[0])); });
  o.mapping.joint_offset = {upper - 0.5, 0, 0, 0, 0};
  std::vector<double> base;
  o.on_cycle = [&](const FollowStatus& s) { base.push_back(s.follower.positions[0]); };
  auto r = run_follow(leader.arm, follower.arm, o);
  ASSERT_TRUE(r) << r.error().message;
  for (double b : base) ASSERT_LE(b, upper + 1e-9);
  EXPECT_NEAR(base.back(), upper, 0.5 * kDeg);
}

TEST(Follow, BadMappingOptionsAreRefusedBeforeAnythingMoves) {
  HandXarm leader, follower;
  FollowRunOptions o;
  o.leader_thread = false;
  o.mapping.joint_scale = {1, 1};
  auto r = run_follow(leader.arm, follower.arm, o);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("one per joint of 'xarm' (5)"), std::string::npos) << r.error().message;
  o.mapping.joint_scale = {1, 0, 1, 1, 1};
  r = run_follow(leader.arm, follower.arm, o);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("not 0"), std::string::npos);
  // Torque was never switched off.
  EXPECT_FALSE(leader.hand(0, 0.2));
}

}  // namespace
}  // namespace armctl::jog
