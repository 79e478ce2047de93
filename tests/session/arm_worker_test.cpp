// The arm worker on the embedded simulated SCARA arm (simulated time: the worker's idle
// slices move it on, so nothing here waits on the wall clock except for the other thread).
#include "session/arm_worker.hpp"

#include <gtest/gtest.h>

#include <latch>

#include "arm/motion_planning.hpp"

namespace armctl::session {
namespace {

using namespace std::chrono_literals;

// SHOULDER: revolute, +-150 deg, starts near 0.
constexpr std::size_t kJoint = 1;

std::unique_ptr<ArmWorker> scara_worker() { return std::make_unique<ArmWorker>(open_arm_session("scara", "").value()); }

// The first snapshot with positions.
ArmSnapshot first_reading(const ArmWorker& w) {
  ArmSnapshot s = w.snapshot();
  while (s.positions.empty()) s = w.wait_for_update(s.sequence, 5s);
  return s;
}

// True once `latch` is open; false if `job` ended first (it failed before getting there).
bool reached(std::latch& latch, std::future<Status>& job) {
  while (!latch.try_wait())
    if (job.wait_for(std::chrono::milliseconds(1)) == std::future_status::ready) return false;
  return true;
}

// A streamed joint move of SHOULDER by `delta` from where the arm is.
ArmWorker::Job joint_move_job(double delta, arm::MotionReport* report, arm::ExecutorOptions extra = {}) {
  return [=](arm::Arm& arm, JobContext& ctx) -> Status {
    auto now = arm.read();
    if (!now) return now.error();
    arm::JointMove move;
    move.target = now->positions;
    move.target[kJoint] += delta;
    auto motion = arm::plan_joint_move(arm.model(), now->positions, move);
    if (!motion) return motion.error();
    auto r = arm::execute_motion(arm, *motion, ctx.executor_options(extra));
    if (!r) return r.error();
    *report = *r;
    return Ok{};
  };
}

TEST(ArmWorker, PublishesPositionsPoseAndStatus) {
  auto w = scara_worker();
  const ArmSnapshot s = first_reading(*w);
  EXPECT_TRUE(s.link_ok);
  EXPECT_EQ(s.positions.size(), w->model().joints.size());
  EXPECT_EQ(s.device.size(), s.positions.size());
  ASSERT_TRUE(s.pose.has_value());
  EXPECT_TRUE(s.job.empty());
  // The readings keep coming while idle.
  const ArmSnapshot later = w->wait_for_update(s.sequence, 5s);
  EXPECT_GT(later.sequence, s.sequence);
  EXPECT_GE(later.time, s.time);
}

TEST(ArmWorker, RunsAJobAndPublishesItsPositionsWhileItMoves) {
  auto w = scara_worker();
  const ArmSnapshot start = first_reading(*w);
  arm::MotionReport report;
  std::vector<double> seen;  // joint 1 as published while the job ran
  std::atomic<bool> done{false};
  std::thread watcher([&] {
    ArmSnapshot s = w->snapshot();
    while (!done) {
      s = w->wait_for_update(s.sequence, 200ms);
      if (!s.job.empty() && !s.positions.empty()) seen.push_back(s.positions[kJoint]);
    }
  });
  auto result = w->run("move joint 1", joint_move_job(0.5, &report));
  ASSERT_EQ(result.wait_for(60s), std::future_status::ready);
  done = true;
  watcher.join();
  const Status st = result.get();
  ASSERT_TRUE(st) << st.error().message;
  EXPECT_TRUE(report.completed);
  EXPECT_GT(report.reads, 0u);
  ASSERT_FALSE(seen.empty());
  EXPECT_GT(seen.back(), start.positions[kJoint] + 0.1);  // read-backs during the motion were published
  const ArmSnapshot after = w->snapshot();
  EXPECT_TRUE(after.job.empty());
  EXPECT_TRUE(after.last_error.empty());
  EXPECT_FALSE(after.progress.has_value());
}

TEST(ArmWorker, RefusesASecondJobWhileOneRunsUnlessQueued) {
  auto w = scara_worker();
  first_reading(*w);
  std::latch started(1), release(1);
  auto first = w->run("hold", [&](arm::Arm&, JobContext&) -> Status {
    started.count_down();
    release.wait();
    return Ok{};
  });
  ASSERT_TRUE(reached(started, first));
  EXPECT_TRUE(w->busy());
  EXPECT_EQ(w->snapshot().job, "hold");
  auto second = w->run("other", [](arm::Arm&, JobContext&) -> Status { return Ok{}; });
  const Status refused = second.get();
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().message, "busy: hold (stop it first)");
  // What apps branch on: the typed detail.
  const JobRefused* why = job_refusal(refused.error());
  ASSERT_NE(why, nullptr);
  EXPECT_EQ(why->reason, JobRefused::Reason::busy);
  EXPECT_EQ(why->job, "other");
  EXPECT_EQ(why->running, "hold");
  auto queued = w->run("after", [](arm::Arm&, JobContext&) -> Status { return Ok{}; }, true);
  release.count_down();
  EXPECT_TRUE(first.get());
  EXPECT_TRUE(queued.get());
}

TEST(ArmWorker, StopSlowsTheMotionDownOnItsPathAndDropsQueuedJobs) {
  auto w = scara_worker();
  const ArmSnapshot start = first_reading(*w);
  arm::MotionReport report;
  std::latch underway(1), stop_sent(1);
  arm::ExecutorOptions extra;
  bool once = false;
  // Holds the motion at 0.5 s of nominal time until the stop is in: deterministic whatever
  // the two threads' speeds.
  extra.command = [&](const arm::MotionProgress& p) {
    if (p.t > 0.5 && !once) {
      once = true;
      underway.count_down();
      stop_sent.wait();
    }
    return arm::MotionCommand::none;
  };
  auto moving = w->run("long move", joint_move_job(1.5, &report, extra));
  auto queued = w->run("next", [](arm::Arm&, JobContext&) -> Status { return Ok{}; }, true);
  ASSERT_TRUE(reached(underway, moving)) << moving.get().error().message;
  w->command(arm::MotionCommand::stop);
  stop_sent.count_down();
  const Status st = moving.get();
  ASSERT_TRUE(st) << st.error().message;
  EXPECT_TRUE(report.stopped);
  EXPECT_FALSE(report.completed);
  const Status dropped = queued.get();
  ASSERT_FALSE(dropped);
  EXPECT_EQ(dropped.error().message, "next: stopped before it started");
  ASSERT_NE(job_refusal(dropped.error()), nullptr);
  EXPECT_EQ(job_refusal(dropped.error())->reason, JobRefused::Reason::dropped);
  EXPECT_EQ(job_refusal(dropped.error())->job, "next");
  // A job's own error carries no refusal.
  EXPECT_TRUE(st);
  // The arm stays where it stopped: short of the target.
  ArmSnapshot s = w->wait_for_update(w->snapshot().sequence, 5s);
  EXPECT_LT(s.positions[kJoint], start.positions[kJoint] + 1.4);
  EXPECT_GT(s.positions[kJoint], start.positions[kJoint] + 0.01);
}

TEST(ArmWorker, StopWhileIdleHaltsTheArmAndAnAbortedWaitEndsTheJob) {
  auto w = scara_worker();
  const ArmSnapshot start = first_reading(*w);
  std::latch waiting(1);
  // A device move (no stream) whose wait the stop cuts short; the worker then halts the arm.
  auto job = w->run("device move", [&](arm::Arm& arm, JobContext& ctx) -> Status {
    std::vector<std::optional<double>> targets(arm.model().joints.size());
    targets[kJoint] = start.positions[kJoint] + 1.0;
    if (auto s = arm.move_joints(targets, {.duration = 20s}); !s) return s;
    arm::WaitOptions base;
    base.timeout = 60s;
    arm::WaitOptions o = ctx.wait_options(base);
    auto outer = o.interrupted;
    bool once = false;
    o.interrupted = [&, outer] {
      if (!once) {
        once = true;
        waiting.count_down();
        while (!ctx.stopping()) std::this_thread::yield();
      }
      return outer();
    };
    auto r = arm.wait(o);
    return r ? Status{Ok{}} : Status{r.error()};
  });
  ASSERT_TRUE(reached(waiting, job)) << job.get().error().message;
  w->command(arm::MotionCommand::stop);
  const Status st = job.get();
  ASSERT_FALSE(st);
  EXPECT_EQ(st.error().message, "wait interrupted");
  EXPECT_EQ(w->snapshot().last_error, "wait interrupted");
  // Halted: two readings a while apart agree (it is not still on its way to +1 rad).
  ArmSnapshot a = w->wait_for_update(w->snapshot().sequence, 5s);
  for (int i = 0; i < 20; ++i) a = w->wait_for_update(a.sequence, 5s);
  ArmSnapshot b = a;
  for (int i = 0; i < 20; ++i) b = w->wait_for_update(b.sequence, 5s);
  EXPECT_GT(b.time, a.time);
  EXPECT_NEAR(b.positions[kJoint], a.positions[kJoint], 0.01);
  EXPECT_LT(b.positions[kJoint], start.positions[kJoint] + 0.9);
}

TEST(ArmWorker, AJobThatThrowsIsReportedAndTheWorkerGoesOn) {
  auto w = scara_worker();
  first_reading(*w);
  auto bad = w->run("thrower", [](arm::Arm&, JobContext&) -> Status { throw std::runtime_error("boom"); });
  const Status st = bad.get();
  ASSERT_FALSE(st);
  EXPECT_EQ(st.error().message, "thrower: boom");
  EXPECT_TRUE(w->run("fine", [](arm::Arm&, JobContext&) -> Status { return Ok{}; }).get());
}

TEST(ArmWorker, ClosingStopsARunningJob) {
  arm::MotionReport report;
  std::latch underway(1);
  std::future<Status> moving;
  {
    auto w = scara_worker();
    first_reading(*w);
    arm::ExecutorOptions extra;
    extra.on_point = [&, once = false](const arm::MotionProgress&) mutable {
      if (!once) underway.count_down();
      once = true;
    };
    moving = w->run("long move", joint_move_job(1.5, &report, extra));
    ASSERT_TRUE(reached(underway, moving)) << moving.get().error().message;
  }  // the destructor stops it and joins
  const Status st = moving.get();
  ASSERT_TRUE(st) << st.error().message;
  EXPECT_FALSE(report.completed);
}

}  // namespace
}  // namespace armctl::session

namespace armctl::session {
namespace {

// The servers' option: the embedded simulated bus in step with the wall clock, as a real
// arm would be (a lower bound only: a loaded machine may run it later, never sooner).
TEST(ArmSession, WallClockOptionPacesTheEmbeddedSimulatedBus) {
  auto s = open_arm_session("scara", "", SessionOptions{.wall_clock = true}).value();
  ASSERT_TRUE(s->paced);
  const auto wall_start = std::chrono::steady_clock::now();
  const TimePoint sim_start = s->arm->clock().now();
  ASSERT_TRUE(s->arm->device().idle(std::chrono::milliseconds(300)));
  EXPECT_GE(s->arm->clock().now() - sim_start, std::chrono::milliseconds(300));
  EXPECT_GE(std::chrono::steady_clock::now() - wall_start, std::chrono::milliseconds(290));
  EXPECT_FALSE(open_arm_session("scara", "").value()->paced);  // the CLI's: as fast as the host goes
}

}  // namespace
}  // namespace armctl::session
