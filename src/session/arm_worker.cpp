#include "session/arm_worker.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <exception>
#include <utility>

#include "core/source_place.hpp"

namespace armctl::session {

namespace {

// Between looks at the queue while idle: a stop or a new job waits at most this long.
constexpr Duration kIdleSlice = std::chrono::milliseconds(10);

bool ends_job(arm::MotionCommand c) { return c == arm::MotionCommand::stop || c == arm::MotionCommand::abort; }

Error closing(const std::string& job) {
  return Error{ErrorKind::device, "the arm is closing", JobRefused{JobRefused::Reason::closing, job, ""}};
}

}  // namespace

arm::MotionCommand JobContext::command() {
  std::lock_guard lock(worker_.mutex_);
  const arm::MotionCommand c = worker_.pending_;
  if (!ends_job(c)) worker_.pending_ = arm::MotionCommand::none;
  return c;
}

bool JobContext::stopping() const {
  std::lock_guard lock(worker_.mutex_);
  return ends_job(worker_.pending_);
}

void JobContext::positions(const arm::JointState& state) { worker_.publish(state); }

void JobContext::progress(const arm::MotionProgress& progress) {
  std::lock_guard lock(worker_.mutex_);
  worker_.snapshot_.progress = progress;
  ++worker_.snapshot_.sequence;
  worker_.changed_.notify_all();
}

void JobContext::status_changed() {
  std::lock_guard lock(worker_.mutex_);
  worker_.status_changed_ = true;
}

Status clear_faults(arm::Arm& arm, JobContext& context) {
  context.status_changed();
  return arm.device().clear_faults();
}

arm::ExecutorOptions JobContext::executor_options(arm::ExecutorOptions base) {
  base.command = [this, outer = base.command](const arm::MotionProgress& p) {
    const arm::MotionCommand mine = command();
    if (mine != arm::MotionCommand::none || !outer) return mine;
    return outer(p);
  };
  base.on_point = [this, outer = base.on_point](const arm::MotionProgress& p) {
    progress(p);
    if (outer) outer(p);
  };
  base.on_read = [this, outer = base.on_read](const arm::JointState& s) {
    positions(s);
    if (outer) outer(s);
  };
  return base;
}

arm::WaitOptions JobContext::wait_options(arm::WaitOptions base) {
  base.interrupted = [this, outer = base.interrupted] { return stopping() || (outer && outer()); };
  base.on_read = [this, outer = base.on_read](const arm::JointState& s) {
    positions(s);
    if (outer) outer(s);
  };
  return base;
}

ArmWorker::ArmWorker(std::unique_ptr<ArmSession> session, ArmWorkerOptions options)
    : session_(std::move(session)), options_(std::move(options)) {
  if (!options_.read_status) options_.read_status = read_arm_status;
  thread_ = std::thread([this] { loop(); });
}

ArmWorker::~ArmWorker() {
  {
    std::lock_guard lock(mutex_);
    quit_ = true;
    pending_ = arm::MotionCommand::stop;
  }
  work_.notify_all();
  thread_.join();
}

ArmSnapshot ArmWorker::snapshot() const {
  std::lock_guard lock(mutex_);
  return snapshot_;
}

ArmSnapshot ArmWorker::wait_for_update(std::uint64_t after, std::chrono::milliseconds timeout) const {
  std::unique_lock lock(mutex_);
  changed_.wait_for(lock, timeout, [&] { return snapshot_.sequence > after || quit_; });
  return snapshot_;
}

std::future<Status> ArmWorker::run(std::string what, Job job, bool queue_behind) {
  std::promise<Status> done;
  std::future<Status> result = done.get_future();
  {
    std::lock_guard lock(mutex_);
    if (quit_) {
      done.set_value(closing(what));
      return result;
    }
    if (!queue_behind && (running_job_ || !queue_.empty())) {
      const std::string& busy_with = running_job_ ? snapshot_.job : queue_.back().what;
      done.set_value(Error{ErrorKind::device, fmt::format("busy: {} (stop it first)", busy_with),
                           JobRefused{JobRefused::Reason::busy, what, busy_with}});
      return result;
    }
    queue_.push_back(Queued{std::move(what), std::move(job), std::move(done)});
  }
  work_.notify_all();
  return result;
}

void ArmWorker::command(arm::MotionCommand command) {
  std::deque<Queued> dropped;
  {
    std::lock_guard lock(mutex_);
    if (command == arm::MotionCommand::none) return;
    if (ends_job(command)) {
      dropped.swap(queue_);
      if (running_job_) {
        // abort wins over stop; a stop does not soften an abort already asked.
        if (pending_ != arm::MotionCommand::abort) pending_ = command;
      } else {
        halt_ = true;
      }
    } else if (running_job_) {
      pending_ = command;
    }
  }
  for (auto& q : dropped)
    q.done.set_value(Error{ErrorKind::device, fmt::format("{}: stopped before it started", q.what),
                           JobRefused{JobRefused::Reason::dropped, q.what, ""}});
  work_.notify_all();
}

bool ArmWorker::busy() const {
  std::lock_guard lock(mutex_);
  return running_job_ || !queue_.empty();
}

void ArmWorker::publish(const arm::JointState& state) {
  const arm::Arm& arm = *session_->arm;
  std::optional<motion::Pose> pose;
  if (arm.model().chain_joints() > 0) pose = arm.forward(arm.chain_of(state.positions));
  std::lock_guard lock(mutex_);
  ArmSnapshot& s = snapshot_;
  const double dt = std::chrono::duration<double>(state.time - s.time).count();
  if (s.positions.size() == state.positions.size() && dt > 0) {
    s.velocities.resize(state.positions.size());
    for (std::size_t i = 0; i < state.positions.size(); ++i)
      s.velocities[i] = (state.positions[i] - s.positions[i]) / dt;
  } else {
    s.velocities.assign(state.positions.size(), 0.0);
  }
  s.time = state.time;
  s.positions = state.positions;
  s.device = state.device;
  s.pose = pose;
  s.link_ok = true;
  s.link_error.clear();
  ++s.sequence;
  changed_.notify_all();
}

void ArmWorker::publish_error(const std::string& error) {
  std::lock_guard lock(mutex_);
  if (!snapshot_.link_ok && snapshot_.link_error == error && snapshot_.sequence > 0) return;
  snapshot_.link_ok = false;
  snapshot_.link_error = error;
  snapshot_.velocities.assign(snapshot_.positions.size(), 0.0);
  ++snapshot_.sequence;
  changed_.notify_all();
}

void ArmWorker::poll_once() {
  // A byte pipe under a device may throw (a closed socket): the worker thread must outlive it.
  auto state = catch_error([&] { return session_->arm->read(); });
  if (state) {
    publish(*state);
  } else {
    publish_error(state.error().message);
  }
}

void ArmWorker::loop() {
  arm::Arm& arm = *session_->arm;
  const Duration poll = options_.poll.value_or(arm.device().poll_interval());
  TimePoint next_read = arm.clock().now();
  TimePoint next_status = next_read;
  for (;;) {
    std::unique_lock lock(mutex_);
    if (quit_) break;
    if (halt_) {
      halt_ = false;
      lock.unlock();
      if (auto s = arm.stop(); !s) publish_error(s.error().message);
      continue;
    }
    if (!queue_.empty()) {
      Queued q = std::move(queue_.front());
      queue_.pop_front();
      running_job_ = true;
      pending_ = arm::MotionCommand::none;
      snapshot_.job = q.what;
      ++snapshot_.sequence;
      changed_.notify_all();
      lock.unlock();

      JobContext context(*this);
      Status result = Ok{};
      try {
        result = q.job(arm, context);
      } catch (const std::exception& e) {
        result = Error{ErrorKind::device, fmt::format("{}: {}", q.what, e.what())};
      }

      lock.lock();
      running_job_ = false;
      const bool stopped = ends_job(pending_);
      pending_ = arm::MotionCommand::none;
      // A stopped job may have left a device move running (a wait cut short): halt it.
      if (stopped) halt_ = true;
      snapshot_.job.clear();
      snapshot_.progress.reset();
      snapshot_.last_error = result ? std::string() : result.error().message;
      snapshot_.last_collision.reset();
      if (!result)
        if (const auto* c = detail_or_cause<arm::CollisionDetail>(result.error())) snapshot_.last_collision = *c;
      ++snapshot_.sequence;
      changed_.notify_all();
      lock.unlock();
      q.done.set_value(std::move(result));
      next_read = arm.clock().now();  // where it ended, at once
      lock.lock();
      if (std::exchange(status_changed_, false)) next_status = next_read;
      lock.unlock();
      continue;
    }
    lock.unlock();

    const TimePoint now = arm.clock().now();
    if (now >= next_read) {
      poll_once();
      next_read = arm.clock().now() + poll;
    }
    if (now >= next_status) {
      ArmStatus status;
      try {
        status = options_.read_status(*session_);
      } catch (const std::exception& e) {
        publish_error(e.what());
      }
      std::lock_guard guard(mutex_);
      if (status.battery_volts != snapshot_.status.battery_volts || status.faults != snapshot_.status.faults) {
        snapshot_.status = std::move(status);
        ++snapshot_.sequence;
        changed_.notify_all();
      }
      next_status = arm.clock().now() + options_.status_interval;
    }
    // Time passes on the device's clock (a simulated arm moves on), a slice at a time so
    // that a job or a stop is taken up quickly.
    const Duration wait = std::clamp(next_read - arm.clock().now(), Duration{0}, kIdleSlice);
    if (wait > Duration{0}) {
      if (const Status s = arm.device().idle(wait); !s) publish_error(s.error().message);
    }
  }
  // Closing: whatever the last job left moving stops.
  (void)arm.stop();
  std::deque<Queued> left;
  {
    std::lock_guard lock(mutex_);
    left.swap(queue_);
  }
  for (auto& q : left) q.done.set_value(closing(q.what));
}

ArmStatus read_arm_status(ArmSession& session) {
  return session.arm->device().health();
}

}  // namespace armctl::session
