// One thread that owns an arm (arm/arm.hpp is not thread-safe), for the applications that
// serve it to many callers at once: the ROS node and the web dashboard. It reads the
// positions at the link's pace and publishes them as snapshots; other threads read
// snapshots, queue jobs that run on the worker thread (a move, a streamed motion, a
// program), and send commands (pause, resume, stop, abort) that the running job sees
// through its JobContext. A stop always reaches the arm: the running job is told, queued
// jobs are dropped, and the arm is halted (Arm::stop) when the job has ended.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "arm/arm.hpp"
#include "arm/collision_detail.hpp"
#include "arm/motion_executor.hpp"
#include "core/error.hpp"
#include "session/arm_session.hpp"

namespace armctl::session {

// Slower-changing state, read every `status_interval` while no job runs.
// The slower state: the device's health (battery of a Robot Commands board, one line per
// joint fault: "joint 3: runaway").
using ArmStatus = arm::DeviceHealth;

struct ArmSnapshot {
  std::uint64_t sequence = 0;  // +1 per published change; 0 = nothing read yet
  TimePoint time{};            // device clock, when the positions were read
  bool link_ok = false;        // the last read succeeded
  std::string link_error;      // why not, when !link_ok
  std::vector<double> positions;   // SI, every joint (empty until the first read)
  std::vector<double> velocities;  // SI per s, from the last two reads
  std::vector<double> device;      // device units, as read
  std::optional<motion::Pose> pose;  // the tool, from the positions
  ArmStatus status;
  std::string job;                 // what runs now ("" = idle)
  std::optional<arm::MotionProgress> progress;  // of the running streamed motion
  std::string last_error;          // of the last job that failed ("" after a success)
  // That job's collision or broken limit, when it failed on one (refused before moving, or
  // stopped before contact by the look-ahead: while_moving), for apps to draw.
  std::optional<arm::CollisionDetail> last_collision;
};

// The detail of an error from ArmWorker::run's future when the job never ran: refused at
// once because another job runs or waits (busy), dropped from the queue by a stop or an
// abort (dropped), or refused because the worker is shutting down (closing). Apps map it to
// their own form (HTTP 409, a ROS "stopped" outcome) with job_refusal(error).
struct JobRefused {
  enum class Reason { busy, dropped, closing };
  Reason reason = Reason::busy;
  std::string job;      // the job that was refused or dropped
  std::string running;  // busy: the job that runs (or waits) instead
};
// The JobRefused behind an error, or nullptr.
inline const JobRefused* job_refusal(const Error& error) { return error.detail_as<JobRefused>(); }

class ArmWorker;

// Handed to a job: the commands sent to it, and publishing what it learns.
class JobContext {
 public:
  // The command waiting for this job (none, pause, resume, stop, abort); taking it clears
  // it, except stop and abort, which stay until the job ends. Pass as the executor's
  // and the program runner's `command`.
  arm::MotionCommand command();
  // True once stop or abort was asked (Arm::wait's `interrupted`).
  bool stopping() const;
  // Publishes positions the job read (Arm::wait's `on_read`, the executor's `on_read`).
  void positions(const arm::JointState& state);
  // Publishes a streamed motion's progress (the executor's `on_point`).
  void progress(const arm::MotionProgress& progress);
  // The job changed what the slower state says (it cleared the joints' faults): it is read
  // again as soon as the job ends, not at the next status_interval.
  void status_changed();
  // ExecutorOptions/WaitOptions with command, on_point and on_read wired to this context.
  arm::ExecutorOptions executor_options(arm::ExecutorOptions base = {});
  arm::WaitOptions wait_options(arm::WaitOptions base = {});

 private:
  friend class ArmWorker;
  explicit JobContext(ArmWorker& worker) : worker_(worker) {}
  ArmWorker& worker_;
};

// The job that clears the faults the joints hold (ArmDevice::clear_faults), for the apps
// that serve the arm (HTTP, ROS): the faults are read again as soon as it ends.
Status clear_faults(arm::Arm& arm, JobContext& context);

struct ArmWorkerOptions {
  // Between position reads while idle; empty: the device's poll interval.
  std::optional<Duration> poll;
  Duration status_interval = std::chrono::seconds(2);
  // Reads the slower state; empty: read_arm_status (battery, joint faults).
  std::function<ArmStatus(ArmSession&)> read_status;
};

class ArmWorker {
 public:
  using Job = std::function<Status(arm::Arm&, JobContext&)>;

  explicit ArmWorker(std::unique_ptr<ArmSession> session, ArmWorkerOptions options = {});
  ~ArmWorker();  // stops a running job, halts the arm, joins the thread
  ArmWorker(const ArmWorker&) = delete;
  ArmWorker& operator=(const ArmWorker&) = delete;

  const arm::ArmModel& model() const { return session_->arm->model(); }
  // What plans are made with: the arm's kinematics with its scene (arm::Arm::kinematics).
  std::shared_ptr<const arm::ArmKinematics> kinematics() const { return session_->arm->kinematics(); }
  // The session, for what only the worker thread may use (jobs run on it).
  ArmSession& session() { return *session_; }

  ArmSnapshot snapshot() const;
  // Blocks until a snapshot newer than `after` is published, or `timeout` passes (wall
  // clock); returns the newest either way.
  ArmSnapshot wait_for_update(std::uint64_t after, std::chrono::milliseconds timeout) const;

  // Queues `job`; its result arrives in the future. Refused at once (device, "busy: <job>",
  // detail JobRefused::busy) when a job runs or waits and `queue_behind` is false.
  std::future<Status> run(std::string what, Job job, bool queue_behind = false);
  // For the running job (pause, resume, stop, abort). stop and abort drop queued jobs
  // (their futures get "stopped before it started", detail JobRefused::dropped) and halt the arm once the running job returns, or at
  // once when none runs.
  void command(arm::MotionCommand command);
  bool busy() const;

 private:
  friend class JobContext;
  struct Queued {
    std::string what;
    Job job;
    std::promise<Status> done;
  };
  void loop();
  void poll_once();
  void publish(const arm::JointState& state);
  void publish_error(const std::string& error);

  std::unique_ptr<ArmSession> session_;
  ArmWorkerOptions options_;
  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;  // snapshot published
  std::condition_variable work_;             // job queued, command or shutdown
  ArmSnapshot snapshot_;
  std::deque<Queued> queue_;
  bool running_job_ = false;
  bool status_changed_ = false;  // read the slower state when the running job ends
  arm::MotionCommand pending_ = arm::MotionCommand::none;
  bool halt_ = false;  // Arm::stop wanted on the worker thread
  bool quit_ = false;
  std::thread thread_;  // last: starts after everything above exists
};

// The default ArmWorkerOptions::read_status: battery on Robot Commands boards, fault
// diagnostics of every joint on the joint bus. Errors leave the field empty.
ArmStatus read_arm_status(ArmSession& session);

}  // namespace armctl::session
