// Stall protection: a joint that is driven but does not move — held by something the scene
// does not know (a hand, a part left in the way, a cable) — must be stopped and its torque
// released: the xArm's bus servos overheat when held stalled, and a motor pushing into an
// obstacle gains nothing. The watch decides which joint stalled; its callers (the motion
// executor's read-backs, Arm::wait) stop the arm and release the joint. Pure: reads and
// times in, a verdict out, on whatever clock the caller reads (simulated in tests).
// Docs: docs/motion.md "Stall protection".
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/clock.hpp"
#include "core/error.hpp"

namespace armctl::arm {

// How long a joint may be driven without moving before it counts as stalled: longer than a
// healthy joint ever stands still behind where it is driven (a servo starting a move, a
// board's acceleration), far shorter than a bus servo takes to overheat (seconds).
inline constexpr Duration kStallTime = std::chrono::milliseconds(500);

// Driven, and standing still (Arm::stall_watch takes at least two and one and a half device
// units: a SCARA joint through the arm controller reads in 1.42 deg steps). A healthy joint
// this far behind where it is driven is catching up, so it moves.
inline constexpr double kStallDrivenAngle = 0.035;   // rad (2 deg)
inline constexpr double kStallDrivenLength = 0.002;  // m
inline constexpr double kStallMovesAngle = 0.0175;   // rad (1 deg: four xArm servo units)
inline constexpr double kStallMovesLength = 0.001;   // m

// Per joint, SI (rad or m).
struct StallThresholds {
  // Driven: where it is driven to now is farther than this from where it is. 0: never
  // watched (the gripper, which stops on a part by design).
  double driven = 0;
  // Moves: it went farther than this since it began to stand still.
  double moves = 0;
};

// The detail of the error when a joint stalled (kind device; the arm was stopped and the
// joint's torque released): which joint, where it stood, where it was driven to, for how
// long, SI. Apps map it to their own form (ROS PATH_TOLERANCE_VIOLATED, Python's
// e.detail == "stall").
struct JointStall {
  int joint = 0;         // index in the arm's joints
  std::string name;      // the joint's name
  double position = 0;   // where it stood
  double driven_to = 0;  // where it was driven to at the last read
  double seconds = 0;    // how long it stood still while driven
};
inline const JointStall* stall_of(const Error& error) { return error.detail_as<JointStall>(); }

class StallWatch {
 public:
  // `time`: how long a driven joint may stand still (kStallTime; 0 turns the watch off).
  StallWatch(std::vector<StallThresholds> joints, Duration time = kStallTime);

  // One read at `now`: where every joint is, and where each is driven to now (nothing: not
  // driven, e.g. a joint the move leaves alone). The first joint that has stood still while
  // driven for the watch's time, with how long (its name left for the caller), or nothing.
  std::optional<JointStall> read(TimePoint now, std::span<const double> positions,
                                 std::span<const std::optional<double>> driven_to);

 private:
  struct Joint {
    bool standing = false;  // driven and standing still since `since`, at `at`
    TimePoint since{};
    double at = 0;
  };
  std::vector<StallThresholds> limits_;
  Duration time_;
  std::vector<Joint> joints_;
};

}  // namespace armctl::arm
