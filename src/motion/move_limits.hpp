// What people may ask of a move, in every app (the CLI, path files, programs, Python, the
// HTTP API): outside these a request is refused, naming the value as it was given and the
// range (docs/motion.md "Limits of a request"). Within them the arm file's limits still
// rule: a move is never faster than they allow (a duration too short is stretched,
// arm/motion_planning.hpp joint_move_duration; a path is slowed where a joint needs it).
// C++17 too: the ROS node (built as C++17, ROS 1's headers) takes its defaults from here.
#pragma once

namespace armctl::motion {

inline constexpr double kDegree = 3.14159265358979323846 / 180;  // rad

// A fraction of the joints' velocity limits (a PTP's speed) or of the programmed speeds (an
// override): 0.1 % up to 100 %. Below 0.1 % a move of one degree would take many minutes.
inline constexpr double kMinSpeedFraction = 0.001;
inline constexpr double kMaxSpeedFraction = 1.0;
// The tool point's speed along a LIN or CIRC (m/s): 0.1 mm/s up to 500 mm/s.
inline constexpr double kMinToolSpeed = 1e-4;
inline constexpr double kMaxToolSpeed = 0.5;
// The tool's turning speed (rad/s): 0.1 deg/s up to 720 deg/s.
inline constexpr double kMinToolAngularSpeed = 0.1 * kDegree;
inline constexpr double kMaxToolAngularSpeed = 720 * kDegree;
// A joint move's duration (s): 0 (as fast as the limits allow) up to 600 s.
inline constexpr double kMaxMoveDuration = 600;

// What a move that names none gets, in every app (defined here once: the CLI, path files,
// programs, Python, the HTTP API, ROS and the planner use these).
inline constexpr double kDefaultJointSpeed = 0.25;   // PTP: of the joints' velocity limits
inline constexpr double kDefaultGripperSpeed = 0.5;  // of the gripper's velocity limit
inline constexpr double kDefaultToolSpeed = 0.05;    // LIN/CIRC: m/s of the tool point
inline constexpr double kDefaultToolAngularSpeed = 45 * kDegree;  // rad/s of the tool
inline constexpr double kDefaultToolAcceleration = 0.5;         // m/s^2 of the tool point along a path
inline constexpr double kDefaultToolAngularAcceleration = 3.0;  // rad/s^2 of the tool along a path

}  // namespace armctl::motion
