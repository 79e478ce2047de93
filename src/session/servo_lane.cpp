#include "session/servo_lane.hpp"

#include <atomic>

namespace armctl::session {

struct ServoLane::Session {
  explicit Session(const arm::ArmModel& model) : input(model) {}
  arm::ServoInput input;
  std::mutex mutex;  // guards status
  arm::ServoStatus status;
};

ServoLane::ServoLane(ArmWorker& worker, arm::ServoOptions options, Duration idle_end)
    : worker_(worker), options_(std::move(options)), idle_end_(idle_end) {}

ServoLane::~ServoLane() {
  finish();
  std::lock_guard lock(mutex_);
  if (job_.valid()) job_.wait();
}

Status ServoLane::send(arm::ServoCommand command) {
  std::lock_guard lock(mutex_);
  if (session_ && !session_->input.finishing()) return session_->input.send(std::move(command));
  // The last session ends at rest on its own (idle, stopped) or failed: wait for its job,
  // and say once why it failed.
  if (job_.valid()) {
    const Status last = job_.get();
    session_.reset();
    if (!last && !job_refusal(last.error())) return last;
  }
  auto s = std::make_shared<Session>(worker_.model());
  if (auto ok = s->input.send(std::move(command)); !ok) return ok;  // nothing starts for a bad one
  const arm::ServoOptions base = options_;
  const Duration idle_end = idle_end_;
  auto job = worker_.run("servo", [s, base, idle_end](arm::Arm& arm, JobContext& context) -> Status {
    arm::ServoOptions o = base;
    o.executor = context.executor_options(o.executor);  // read-backs published as positions
    std::uint64_t seen = 0;
    TimePoint last_command{};
    o.before_cycle = [&](TimePoint now) {
      const arm::MotionCommand c = context.command();
      if (c == arm::MotionCommand::stop || c == arm::MotionCommand::abort) s->input.finish();
      const std::uint64_t sequence = s->input.take(seen).sequence;
      if (sequence != seen || seen == 0) {
        seen = sequence;
        last_command = now;
      }
      // No command for a while: the arm came to rest after the command timeout; end.
      if (now - last_command > idle_end) s->input.finish();
    };
    o.on_cycle = [&](const arm::ServoStatus& status) {
      std::lock_guard status_lock(s->mutex);
      s->status = status;
    };
    auto r = arm::run_servo(arm, s->input, o);
    if (!r) return r.error();
    return Ok{};
  });
  // Refused at once (another job runs): say so now, nothing started.
  if (job.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
    const Status refused = job.get();
    if (!refused) return refused;
  }
  job_ = std::move(job);
  session_ = s;
  return Ok{};
}

void ServoLane::finish() {
  std::lock_guard lock(mutex_);
  if (session_) session_->input.finish();
}

bool ServoLane::running() const {
  std::lock_guard lock(mutex_);
  // A job dropped before it started (a stop right after the first command) never finishes
  // its input: the job's end says it is over.
  return session_ && !session_->input.finishing() && job_.valid() &&
         job_.wait_for(std::chrono::seconds(0)) != std::future_status::ready;
}

arm::ServoStatus ServoLane::status() const {
  std::lock_guard lock(mutex_);
  if (!session_) return {};
  std::lock_guard status_lock(session_->mutex);
  return session_->status;
}

}  // namespace armctl::session
