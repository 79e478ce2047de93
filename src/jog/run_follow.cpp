#include "jog/run_follow.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>
#include <thread>

#include <fmt/format.h>

#include "files/recording_file.hpp"

namespace armctl::jog {
namespace {

// The leader's newest reading, from whichever thread reads it.
class LeaderReadings {
 public:
  void put(std::vector<double> positions) {
    std::lock_guard lock(mutex_);
    positions_ = std::move(positions);
    lost_.clear();
    ++count_;
  }
  void lose(std::string why) {
    std::lock_guard lock(mutex_);
    lost_ = std::move(why);
  }
  // The newest reading when it is newer than `seen`.
  std::optional<std::vector<double>> take(std::size_t& seen, std::string& lost) const {
    std::lock_guard lock(mutex_);
    lost = lost_;
    if (count_ == seen) return std::nullopt;
    seen = count_;
    return positions_;
  }
  std::size_t count() const {
    std::lock_guard lock(mutex_);
    return count_;
  }

 private:
  mutable std::mutex mutex_;
  std::vector<double> positions_;
  std::string lost_;
  std::size_t count_ = 0;
};

motion::Recording recording_of(const arm::ArmModel& model, double rate) {
  motion::Recording r;
  r.arm = model.name;
  r.rate = rate;
  for (const auto& j : model.joints) r.joints.push_back({j.name, j.dimension});
  return r;
}

}  // namespace

Result<FollowReport> run_follow(arm::Arm& leader, arm::Arm& follower, const FollowRunOptions& options) {
  if (options.record_rate != 0 && !(options.record_rate >= 1 && options.record_rate <= files::kRecordingMaxRate))
    return Error{ErrorKind::invalid_argument,
                 fmt::format("record rate {} Hz: allowed is 1..{:g} Hz", options.record_rate, files::kRecordingMaxRate)};
  if (options.leader_timeout <= Duration{0})
    return Error{ErrorKind::invalid_argument, "leader timeout: a time above 0 is needed"};
  auto leader_start = leader.read();
  if (!leader_start) return leader_start.error();
  auto follower_start = follower.read();
  if (!follower_start) return follower_start.error();
  auto mapping = FollowMapping::make(leader.kinematics(), follower.kinematics(), options.mapping,
                                     leader_start->positions, follower_start->positions);
  if (!mapping) return mapping.error();
  if (auto off = leader.set_torque(false); !off) return off.error();

  LeaderReadings readings;
  readings.put(leader_start->positions);
  std::atomic<bool> done{false};
  auto read_once = [&] {
    if (auto r = leader.read()) readings.put(std::move(r->positions));
    else readings.lose(r.error().message);
  };
  std::thread reader;
  if (options.leader_thread)
    reader = std::thread([&] {
      while (!done) read_once();  // as fast as the link answers
    });

  FollowReport report;
  report.leader_recording = recording_of(leader.model(), options.record_rate);
  report.follower_recording = recording_of(follower.model(), options.record_rate);
  arm::ServoInput input(follower.model());
  const auto& map = *mapping;
  const auto kinematics = follower.kinematics();
  std::size_t seen = 0, tracked = 0;
  double tracking_sum = 0;
  std::vector<double> newest = leader_start->positions;
  std::optional<TimePoint> start, last_reading, next_sample, first_sample;
  std::string lost;

  arm::ServoOptions servo = options.servo;
  servo.before_cycle = [&](TimePoint now) {
    if (!start) start = last_reading = next_sample = now;
    if (options.before_cycle) options.before_cycle(now);
    if (!options.leader_thread) read_once();
    if (auto r = readings.take(seen, lost)) {
      newest = std::move(*r);
      last_reading = now;
    }
    if (lost.empty() && now - *last_reading > options.leader_timeout)
      lost = fmt::format("no reading from the leader for {:.0f} ms",
                         std::chrono::duration<double, std::milli>(now - *last_reading).count());
    report.leader_was_lost = report.leader_was_lost || !lost.empty();
    if ((options.stop && options.stop()) || input.finishing()) {
      input.finish();
      return;
    }
    // A lost leader sends nothing: the follower's command timeout brings it to rest.
    if (lost.empty()) (void)input.send(map.command(newest));  // from the arms' own models: valid
  };
  servo.on_cycle = [&](const arm::ServoStatus& s) {
    FollowStatus f{s, newest, 0, lost};
    f.tracking_error = (kinematics->pose_at(s.positions).position - map.tool_target(newest)).norm();
    if (lost.empty() && s.commanded && s.slowdown == arm::ServoSlowdown::none) {
      report.largest_tracking_error = std::max(report.largest_tracking_error, f.tracking_error);
      tracking_sum += f.tracking_error;
      ++tracked;
    }
    const TimePoint now = follower.clock().now();
    if (options.record_rate > 0 && start && now >= *next_sample) {
      if (!first_sample) first_sample = now;
      const double t = std::chrono::duration<double>(now - *first_sample).count();
      report.leader_recording.samples.push_back({t, newest});
      report.follower_recording.samples.push_back({t, s.positions});
      // A follower whose link is slower than the rate samples once a cycle (the header then
      // says the rate it reached).
      const auto step = std::chrono::duration_cast<Duration>(std::chrono::duration<double>(1.0 / options.record_rate));
      *next_sample = std::max(*next_sample + step, now);
    }
    if (options.on_cycle) options.on_cycle(f);
  };
  auto r = arm::run_servo(follower, input, servo);
  done = true;
  if (reader.joinable()) reader.join();
  // The leader holds where the hand left it (also after an error of the follower's).
  const Status on = leader.set_torque(true);
  if (!r) return r.error();
  if (!on) return on.error();
  report.follower = std::move(*r);
  report.leader_reads = readings.count();
  report.mean_tracking_error = tracked ? tracking_sum / double(tracked) : 0;
  const auto& samples = report.follower_recording.samples;
  if (samples.size() > 1) {
    const double reached = double(samples.size() - 1) / samples.back().time;
    const double rate = std::clamp(std::floor(std::min(options.record_rate, reached)), 1.0, files::kRecordingMaxRate);
    report.follower_recording.rate = report.leader_recording.rate = rate;
  }
  return report;
}

}  // namespace armctl::jog
