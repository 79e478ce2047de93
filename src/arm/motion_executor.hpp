// The motion executor: plays a motion computed on the host (a jerk-limited joint trajectory,
// a Cartesian path) to the arm as a stream of short moves, at the rate the link allows.
//
// Timing: the motion has a nominal time t in [0, duration]; the executor advances t at a
// rate r (1 = as planned; the speed override caps it). Pause, resume and stop change r
// smoothly (a quintic ramp whose length keeps every joint's extra acceleration within its
// limit), so the arm slows down and comes to rest ON the path; abort halts at once.
// Each point is sent early by the link's latency plus one period, so that the device,
// interpolating to it over one period, is there when the plan says.
// A host that falls behind (not scheduled for a while) holds nominal time rather than jump
// ahead: the arm rests at the last point it got and the motion goes on from there.
// Following error: every few points the positions are read back and compared with the plan
// at the instant of the read; beyond the threshold the arm is halted and the error names
// the joint. The same reads watch for a joint that stalls (arm/stall_watch.hpp): driven but
// standing still, it is stopped and released.
// Look-ahead: the stretch of the motion the arm will cover in the next 200 ms, plus what a
// stop from there takes, is checked against the arm's collision world as it is now (the
// plan was checked against the scene of its time; an object added since, from the
// dashboard, ROS or Python, is seen here). A contact ahead stops the motion on its path
// before it; the error names the two bodies (detail CollisionDetail). Docs: docs/motion.md,
// docs/scene.md.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "arm/arm.hpp"
#include "arm/collision_detail.hpp"
#include "core/clock.hpp"
#include "core/error.hpp"

namespace armctl::arm {

// A motion checked and timed before anything moves: every joint of the arm (SI, the model's
// order) at nominal time t in [0, duration] (clamped), with velocity and acceleration.
struct PlannedMotion {
  std::string what;   // for messages: "LIN to (200.0, 0.0, 150.0) mm"
  double duration = 0;  // nominal s
  std::function<void(double t, std::vector<double>& position, std::vector<double>& velocity,
                     std::vector<double>& acceleration)>
      sample;
};

enum class MotionCommand { none, pause, resume, stop, abort };

struct MotionProgress {
  Duration elapsed{};    // since the start, on the device's clock
  double t = 0;          // nominal time reached
  double duration = 0;   // nominal duration
  double rate = 1;       // current dt/dt_nominal
  bool paused = false;
  std::size_t points = 0;  // stream points sent
};

inline constexpr Duration kLookAhead = std::chrono::milliseconds(200);

struct ExecutorOptions {
  double speed_override = 1.0;      // (0, 1]: the rate's ceiling
  std::optional<Duration> period;   // between points; empty: the device's floor
  // Between read-backs; empty: the device's poll interval (HID boards: slowly), and at
  // least four stream periods (reads take the link from the stream).
  std::optional<Duration> read_interval;
  double following_error_angle = 0.087;   // rad (5 deg)
  double following_error_length = 0.005;  // m
  // Per joint (SI, the model's order): where given and above 0, it replaces the one above
  // for that joint (a ROS goal's path tolerance names joints one by one).
  std::vector<double> following_error;
  // Stall protection at the read-backs (arm/stall_watch.hpp): a joint standing still this
  // long while the plan has it farther away than its stall threshold is stopped and its
  // torque released (error device, detail JointStall). 0: off.
  Duration stall_time = kStallTime;
  // How far ahead of the arm the motion is checked against the collision world, in device
  // time (the stop's own length is added); 0: not checked while moving.
  Duration look_ahead = kLookAhead;
  // Asked before every point (a flag set by a signal handler, a key, a test script).
  std::function<MotionCommand(const MotionProgress&)> command;
  // After every point (progress lines, test probes).
  std::function<void(const MotionProgress&)> on_point;
  // After every read-back (live positions for a thread that publishes them).
  std::function<void(const JointState&)> on_read;
};

struct FollowingSample {
  Duration elapsed{};
  std::vector<double> planned, measured;  // SI
};

struct MotionReport {
  Duration elapsed{};
  double t_reached = 0;   // nominal time where the motion ended
  bool completed = false;  // reached the end of the motion
  bool stopped = false;    // by a stop command (at rest on the path)
  std::size_t points = 0;
  std::size_t reads = 0;
  Duration period{};
  // Loop steps the host was late for (not scheduled, a slow read) beyond what the points'
  // lead covers, and the time the motion was held for them (it ends that much later).
  std::size_t late_steps = 0;
  Duration held{};
  double largest_following_error = 0;  // SI, the largest over all joints and reads
  int largest_following_joint = -1;
  std::vector<FollowingSample> reads_log;  // every read-back
};

// The detail of execute_motion's error when a joint fell behind the plan by more than its
// threshold (kind device; the arm was halted): which joint, where it was, where it should
// have been, SI. Apps map it to their own form (ROS PATH_TOLERANCE_VIOLATED).
struct FollowingError {
  int joint = 0;         // index in the arm's joints
  std::string name;      // the joint's name
  double measured = 0;   // where it was
  double planned = 0;    // where it should have been
  double limit = 0;      // the threshold it exceeded
  double t = 0;          // nominal time in the motion
};
inline const FollowingError* following_error_of(const Error& error) { return error.detail_as<FollowingError>(); }

// Runs `motion` on `arm` from its current position (which must be the motion's start: the
// caller planned it from a fresh read). Errors: the device's (the arm is halted first),
// device "following error" naming the joint, where it is and where it should be (detail
// FollowingError), device "stalled" naming the joint and how long (detail JointStall;
// Arm::stalled), or invalid_argument naming the two bodies when the look-ahead found a
// contact ahead (detail CollisionDetail with while_moving; the arm at rest on the path
// before it, or halted at once where too near to slow down).
Result<MotionReport> execute_motion(Arm& arm, const PlannedMotion& motion, const ExecutorOptions& options = {});

// What the executor and the servo loop (arm/run_servo.hpp) share.
// Device units per joint of a stream point (SI positions `q`), and device units/s for its
// velocities `v`.
void to_device(const ArmModel& model, Protocol p, const std::vector<double>& q, const std::vector<double>& v,
               std::vector<double>& dq, std::vector<double>& dv);
// The following-error threshold of `joint` under `options` (SI).
double following_threshold(const ArmModel& model, std::size_t joint, const ExecutorOptions& options);
// A read-back `measured` against where the arm should be (`planned`, SI, every joint): the
// error execute_motion returns (kind device, detail FollowingError; `what` starts it, `t` is
// the nominal time) for the first joint beyond its threshold, else Ok. Updates the largest
// error seen and its joint. The gripper is not held to the plan (it stops on a part).
Status check_following(const ArmModel& model, const std::vector<double>& measured, const std::vector<double>& planned,
                       const ExecutorOptions& options, std::string_view what, double t, double& largest,
                       int& largest_joint);

// The smallest stop (or pause) ramp length, s of device time, that keeps every joint's extra
// acceleration |dq/dt_nominal| * |dr/dt| within `budget` of its limit, from rate `rate`.
double rate_ramp_seconds(const std::vector<double>& nominal_velocity, const std::vector<double>& accel_budget,
                         double rate_change);

}  // namespace armctl::arm
