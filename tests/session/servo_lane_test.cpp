// The servo lane (session/servo_lane.hpp) on the embedded simulated SCARA (simulated time on
// the worker's thread): a command starts a servo session on the worker, which comes to rest
// when commands stop and then ends by itself; a bad command starts nothing; another job keeps
// the lane out; a worker stop ends the session.
#include "session/servo_lane.hpp"

#include <gtest/gtest.h>

#include <thread>

namespace armctl::session {
namespace {

using namespace std::chrono_literals;
constexpr std::size_t kShoulder = 1;

arm::ServoCommand shoulder_at(const ArmWorker& w, double velocity) {
  std::vector<double> v(w.model().joints.size(), 0.0);
  v[kShoulder] = velocity;
  return arm::ServoCommand{arm::JointVelocities{v}, std::nullopt};
}

ArmSnapshot first_reading(const ArmWorker& w) {
  ArmSnapshot s = w.snapshot();
  while (s.positions.empty()) s = w.wait_for_update(s.sequence, 5s);
  return s;
}

// Until the worker has no job (the session ended by itself), or 30 s.
ArmSnapshot idle_again(const ArmWorker& w) {
  ArmSnapshot s = w.snapshot();
  const auto end = std::chrono::steady_clock::now() + 30s;
  while ((!s.job.empty() || w.busy()) && std::chrono::steady_clock::now() < end) s = w.wait_for_update(s.sequence, 1s);
  return w.wait_for_update(s.sequence, 5s);  // a reading after the job
}

TEST(ServoLane, ACommandMovesTheJointUntilItTimesOutThenTheSessionEnds) {
  ArmWorker w(open_arm_session("scara", "").value());
  const double before = first_reading(w).positions[kShoulder];
  ServoLane lane(w);
  ASSERT_TRUE(lane.send(shoulder_at(w, 0.2)));
  EXPECT_TRUE(w.busy());
  const ArmSnapshot after = idle_again(w);
  EXPECT_FALSE(w.busy());
  // 0.2 rad/s until the command timed out (0.2 s) and the braking after it.
  const double moved = after.positions[kShoulder] - before;
  EXPECT_GT(moved, 0.2 * 0.2 * 0.5);
  EXPECT_LT(moved, 0.2 * 0.6);
  EXPECT_FALSE(lane.status().commanded);
  EXPECT_TRUE(lane.status().at_rest);
  EXPECT_FALSE(lane.running());
  // A new command starts a new session.
  ASSERT_TRUE(lane.send(shoulder_at(w, -0.2)));
  idle_again(w);
}

TEST(ServoLane, ABadCommandStartsNothingAndAnotherJobKeepsTheLaneOut) {
  ArmWorker w(open_arm_session("scara", "").value());
  first_reading(w);
  ServoLane lane(w);
  auto bad = lane.send(shoulder_at(w, NAN));
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("finite"), std::string::npos);
  EXPECT_FALSE(w.busy());
  std::promise<void> release;
  auto job = w.run("a long job", [f = release.get_future().share()](arm::Arm&, JobContext&) -> Status {
    f.wait();
    return Ok{};
  });
  auto busy = lane.send(shoulder_at(w, 0.1));
  ASSERT_FALSE(busy);
  ASSERT_NE(job_refusal(busy.error()), nullptr) << busy.error().message;
  release.set_value();
  ASSERT_TRUE(job.get());
}

TEST(ServoLane, AWorkerStopEndsTheSessionAtRest) {
  ArmWorker w(open_arm_session("scara", "").value());
  first_reading(w);
  arm::ServoOptions o;
  o.command_timeout = std::chrono::seconds(30);  // the command alone would keep it moving
  ServoLane lane(w, o, std::chrono::seconds(60));
  ASSERT_TRUE(lane.send(shoulder_at(w, 0.05)));
  // Once the session runs (a stop before would drop the job before it starts).
  for (int k = 0; k < 5000 && lane.status().commands == 0; ++k) std::this_thread::sleep_for(1ms);
  ASSERT_GT(lane.status().commands, 0u);
  EXPECT_TRUE(lane.running());
  w.command(arm::MotionCommand::stop);
  const ArmSnapshot after = idle_again(w);
  EXPECT_FALSE(w.busy());
  EXPECT_TRUE(lane.status().at_rest);
  EXPECT_FALSE(lane.running());
  (void)after;
}

}  // namespace
}  // namespace armctl::session
