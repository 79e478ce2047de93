// The arm controller and joint faults: a joint that stops following its plan (here one
// whose motor leads are swapped, so it runs away and stops itself) has its faults read,
// logged, counted, and kept in its status; the other joints carry on.
#include <gtest/gtest.h>

#include "controller_rig.hpp"
#include "portable/joint_bus_codes.hpp"

namespace armctl::arm_controller::testing {
namespace {

TEST(JointFaultReports, ARunawayJointIsReportedWhenItStopsFollowing) {
  Rig rig(std::nullopt, 115200, {3});
  ASSERT_TRUE(rig.client->move({{2, 700}, {3, 700}}, 1500).ok());
  rig.run_for(std::chrono::milliseconds(2500));
  const auto& s = rig.device->core().stats();
  EXPECT_EQ(s.following_lost, 1u);
  EXPECT_GE(s.fault_reads, 1u);
  EXPECT_LE(s.fault_reads, 3u) << "read when it left its plan, then every 250 ms until the fault showed";
  EXPECT_EQ(s.runaway_faults, 1u);
  EXPECT_EQ(s.following_error_faults, 0u);
  const controller::JointState& j3 = rig.state(3);
  EXPECT_FALSE(j3.following);
  EXPECT_TRUE(j3.diagnostics_read);
  EXPECT_EQ(j3.diagnostics[0], joint_bus::fault_runaway);
  EXPECT_TRUE(rig.logged("joint 3 UAE: stopped following its plan"));
  EXPECT_TRUE(rig.logged("joint 3 UAE: faults: runaway"));
  EXPECT_TRUE(rig.logged("armctl arm clear-faults"));
  // Joint 2 arrived; it never stopped following.
  EXPECT_TRUE(rig.state(2).following);
  EXPECT_FALSE(rig.state(2).diagnostics_read);
  // Once the fault is known it is not read again.
  const auto reads = rig.device->core().stats().fault_reads;
  rig.run_for(std::chrono::milliseconds(1000));
  EXPECT_EQ(rig.device->core().stats().fault_reads, reads);
}

TEST(JointFaultReports, TheSdkReadsAndClearsThemAsOnTheMegaController) {
  // JointFaultRead / JointFaultClear (CMD 40 / 41), answered by the core the Mega runs, so
  // `armctl arm health` and `clear-faults` work the same through either arm controller.
  Rig rig(std::nullopt, 115200, {3});
  ASSERT_TRUE(rig.client->move({{2, 700}, {3, 700}}, 1500).ok());
  rig.run_for(std::chrono::milliseconds(2500));
  auto report = rig.client->read_joint_faults(3);
  ASSERT_TRUE(report) << report.error().message;
  ASSERT_TRUE(report->has_value()) << "the controller answers CMD 40";
  const rc::JointFaultReport& r = **report;
  EXPECT_TRUE(r.answering);
  EXPECT_FALSE(r.following);
  EXPECT_TRUE(r.words_read);
  EXPECT_EQ(r.words[0], joint_bus::fault_runaway);
  EXPECT_EQ(r.following_lost, 1);
  auto two = rig.client->read_joint_faults(2);
  ASSERT_TRUE(two && two->has_value());
  EXPECT_TRUE((*two)->following);
  EXPECT_FALSE((*two)->words_read);

  auto cleared = rig.client->clear_joint_faults(3);
  ASSERT_TRUE(cleared) << cleared.error().message;
  ASSERT_TRUE(cleared->has_value());
  EXPECT_TRUE((*cleared)->cleared()) << (*cleared)->status;
  EXPECT_TRUE(rig.logged("joint 3 (UAE): faults cleared"));
  auto after = rig.client->read_joint_faults(3);
  ASSERT_TRUE(after && after->has_value());
  EXPECT_TRUE((*after)->following);
  EXPECT_EQ((*after)->words[0], 0);
  // Cleared, it drives again (and, its leads still swapped, runs away again).
  const int before = rig.clicks(3);
  ASSERT_TRUE(rig.client->move({{3, 400}}, 1000).ok());
  rig.run_for(std::chrono::milliseconds(1500));
  EXPECT_GT(std::abs(rig.clicks(3) - before), 500) << "driven again after the clear";
  // A servo that is not a joint here, or a malformed request: ignored (the SDK refuses 8).
  const auto ignored = rig.device->core().stats().ignored_frames;
  rig.device->handle(rc::Frame{rc::kJointFaultClearCmd, {8}});
  EXPECT_EQ(rig.device->core().stats().ignored_frames, ignored + 1);
}

TEST(JointFaultReports, HealthyArmNeverReadsFaults) {
  Rig rig(std::nullopt, 115200);
  ASSERT_TRUE(rig.client->move({{1, 300}, {2, 700}, {3, 700}}, 1500).ok());
  rig.run_for(std::chrono::milliseconds(2500));
  EXPECT_EQ(rig.device->core().stats().following_lost, 0u);
  EXPECT_EQ(rig.device->core().stats().fault_reads, 0u);
}

}  // namespace
}  // namespace armctl::arm_controller::testing
