// Leader and follower (`armctl follow`, docs/servo.md): the leader's torque off (moved by
// hand) and read as fast as its link allows; the follower tracks it through the servo mode
// (arm/run_servo.hpp), so it moves within its limits, slows near the ends of its ranges, the
// scene and singularities, and holds at a boundary instead of jumping. A lost leader (a
// failed read, no reading for leader_timeout) stops the commands: the follower slows to rest
// and holds until the leader answers again. At the end the follower rests and the leader's
// torque comes back on, holding it where it stands (also on errors).
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "arm/arm.hpp"
#include "arm/run_servo.hpp"
#include "core/error.hpp"
#include "jog/follow_mapping.hpp"
#include "motion/recording.hpp"

namespace armctl::jog {

struct FollowStatus {
  arm::ServoStatus follower;
  std::vector<double> leader;  // the newest reading (SI)
  double tracking_error = 0;   // m: the follower's tool from where the mapping puts it
  std::string leader_lost;     // why, while the leader is lost
};

struct FollowRunOptions {
  FollowOptions mapping;
  arm::ServoOptions servo;  // the follower's; its before_cycle and on_cycle are run_follow's
  // The leader read on a thread of its own, as fast as its link allows (off: once per
  // follower cycle on the caller's thread, as the tests on simulated time do).
  bool leader_thread = true;
  Duration leader_timeout = std::chrono::milliseconds(250);
  // Asked every cycle: true ends the session (Ctrl-C).
  std::function<bool()> stop;
  // Every cycle, and at `record_rate` samples of both arms (0: none).
  std::function<void(const FollowStatus&)> on_cycle;
  double record_rate = 0;  // Hz
  // On the caller's thread before every follower cycle when the leader is polled (a test
  // moving the leader by hand).
  std::function<void(TimePoint now)> before_cycle;
};

struct FollowReport {
  arm::ServoReport follower;
  std::size_t leader_reads = 0;
  double largest_tracking_error = 0;  // m, while the leader answered and the follower was not held
  double mean_tracking_error = 0;
  bool leader_was_lost = false;
  motion::Recording leader_recording, follower_recording;  // at record_rate
};

Result<FollowReport> run_follow(arm::Arm& leader, arm::Arm& follower, const FollowRunOptions& options);

}  // namespace armctl::jog
