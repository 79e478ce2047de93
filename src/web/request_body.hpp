// Request bodies of the HTTP API (docs/http-api.md): JSON objects parsed strictly, every
// field range-checked, unknown fields refused. Every error is an ApiError (400, 413) whose
// message names the field, the value found and what is allowed. Pure code: no I/O, no arm;
// fuzzed by fuzz/web/fuzz_request_body.cpp.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "arm/arm_model.hpp"
#include "arm/servo_commands.hpp"
#include "motion/move_limits.hpp"

namespace armctl::web {

using json = nlohmann::json;

inline constexpr std::size_t kMaxBodyBytes = 1 << 20;  // larger: 413
inline constexpr int kMaxBodyDepth = 16;

// The body as a JSON object; an empty body is {}. 413 above kMaxBodyBytes; 400 when it is
// not JSON, not an object, or nested deeper than kMaxBodyDepth.
json parse_body(std::string_view text);

// One JSON object of a request. Reading a field marks it known; finish() refuses the rest.
class BodyReader {
 public:
  // `path` prefixes field names in messages ("frames[2].").
  explicit BodyReader(const json& object, std::string path = "");

  bool has(const std::string& key) const { return object_.contains(key); }
  const json* find(const std::string& key);
  const json& require(const std::string& key, const std::string& allowed);
  std::string name(const std::string& key) const { return path_ + key; }

  // A finite number in [min, max] (with above_min: (min, max]); `allowed` says it for people.
  double number(const std::string& key, double min, double max, const std::string& allowed, bool above_min = false);
  std::optional<double> optional_number(const std::string& key, double min, double max, const std::string& allowed,
                                        bool above_min = false);
  std::int64_t integer(const std::string& key, std::int64_t min, std::int64_t max);
  bool boolean(const std::string& key);
  std::optional<bool> optional_boolean(const std::string& key);
  std::string string(const std::string& key, std::size_t max_bytes);
  std::optional<std::string> optional_string(const std::string& key, std::size_t max_bytes);
  // One of `words`.
  std::string word(const std::string& key, const std::vector<std::string>& words);

  void finish() const;

 private:
  const json& object_;
  std::string path_;
  std::set<std::string> known_;
};

// `value` as a short text for messages (strings quoted and escaped, long values cut).
std::string shown(const json& value);

[[noreturn]] void bad_value(const std::string& field, const std::string& why);

// POST /api/v1/control
struct ControlRequest {
  bool take = false;  // else release
};
ControlRequest parse_control_request(const json& body);

// POST /api/v1/joints: targets in SI, one entry per joint of the model (empty = stays).
struct JointsRequest {
  std::vector<std::optional<double>> targets;
  double speed = motion::kDefaultJointSpeed;  // of the velocity limits, (0, 1]
  std::optional<double> duration;   // s, (0, motion::kMaxMoveDuration]: at least this long
};
JointsRequest parse_joints_request(const arm::ArmModel& model, const json& body);

// POST /api/v1/tool: a tool target (m, rad).
struct ToolRequest {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  std::optional<double> roll, pitch, yaw;
  bool linear = false;
  double speed = motion::kDefaultJointSpeed;  // (0, 1]: of the joints' velocity limits, or linear of kMaxLinearSpeed
  // "avoid": true: when the direct PTP would collide, around the obstacles (arm/avoid_path.hpp),
  // searching for at most "avoid_time" s. A PTP only: a straight line has no detour.
  std::optional<double> avoid_time;  // s; nothing: no avoiding
};
inline constexpr double kMaxLinearSpeed = 0.2;  // m/s of the tool at speed 1
inline constexpr double kMaxReach = 2.0;          // m: no target further from the base
ToolRequest parse_tool_request(const json& body);

// POST /api/v1/jog: one step of the tool along or about one base axis.
struct JogRequest {
  int axis = 0;        // x y z roll pitch yaw
  double step = 0;     // m or rad, signed
  bool linear = false;
  double speed = motion::kDefaultJointSpeed;
};
inline constexpr double kMaxJogLength = 0.1;          // m
inline constexpr double kMaxJogAngle = 1.5707963267948966;  // rad (90 deg)
JogRequest parse_jog_request(const json& body);

// POST /api/v1/servo, hold-to-jog: {"axis": x|y|z|roll|pitch|yaw, "speed": signed mm/s or
// deg/s (0: come to rest), "frame": "base"|"tool"}: the tool twist the servo mode follows
// (docs/servo.md) until the next one, or for 0.2 s; or {"joint": name, "speed": signed deg/s
// or mm/s within the joint's velocity limit}: that joint at that velocity, the others still.
arm::ServoCommand parse_servo_request(const arm::ArmModel& model, const json& body);

// POST /api/v1/gripper
double parse_gripper_request(const json& body);
// POST /api/v1/torque
bool parse_torque_request(const json& body);
// POST /api/v1/points: the point's name (a valid points-file name).
std::string parse_point_request(const json& body);
// A point's name from a URL (DELETE /api/v1/points/<name>).
std::string check_point_name(std::string_view name);

// Programs: POST /api/v1/program/check and /run.
struct ProgramRequest {
  std::string source;
  std::string points;  // a points file's text, may be empty
  double speed = 1.0;  // run: override of the programmed speeds, (0, 1]
  // "avoid": true: a PTP whose direct motion would collide goes around (as move-to's
  // "avoid"), each search given this long at most (s; "avoid_time", default 1).
  std::optional<double> avoid_time;
};
ProgramRequest parse_program_request(const json& body, bool run);

// An empty object ({} or no body) for the requests that take nothing.
void parse_empty_request(const json& body);

}  // namespace armctl::web
