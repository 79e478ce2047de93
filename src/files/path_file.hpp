// Path files: the moves of `armctl arm ... path FILE`, one a line, written by hand (format
// reference with an example of every form: docs/paths.md).
//
//   # pick and place
//   ptp  joints=0deg,30deg,-45deg,0deg,0deg        speed=50%
//   ptp  x=200mm y=0mm z=150mm pitch=90deg elbow=up  speed=30%
//   lin  x=200mm y=100mm z=150mm                    speed=50mm/s zone=5mm
//   circ via=250mm,150mm,150mm x=300mm y=100mm z=150mm speed=40mm/s angular_speed=30deg/s
//
// A line is a move (ptp, lin or circ) and key=value fields in any order; values carry their
// unit as on the command line (core/quantity.hpp). '#' starts a comment; blank lines are
// ignored (files/line_reader.hpp). Errors name the file, line and column, what was found and what is expected;
// nothing is returned on error.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "core/error.hpp"
#include "core/quantity.hpp"
#include "files/line_reader.hpp"
#include "motion/kinematics.hpp"

namespace armctl::files {

inline constexpr std::size_t kPathFileMaxMoves = 100'000;
inline constexpr std::size_t kPathFileMaxJoints = motion::kMaxChainJoints + 1;  // the chain and a gripper

enum class MoveKind { ptp, lin, circ };
const char* to_string(MoveKind kind);  // "ptp", "lin", "circ" (as written in the file)

// A joint value as written: SI (rad or m) and which of the two it is; the arm decides
// whether that fits the joint.
struct JointValue {
  double value = 0;
  Dimension dimension = Dimension::angle;
  bool operator==(const JointValue&) const = default;
};

struct PathMove {
  MoveKind kind = MoveKind::lin;
  std::size_t line = 0;  // 1-based, for messages
  // ptp to joint values: one per joint in the arm's order (chain, then gripper; fewer
  // leaves the rest where they are). Empty for a move to a pose.
  std::vector<JointValue> joints;
  // The tool pose (m, base frame) of a ptp to a pose, a lin or a circ. Orientation angles
  // left out keep the tool's current ones (on the xArm a left-out yaw follows the position,
  // as `armctl arm move` does).
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  std::optional<double> roll, pitch, yaw;  // rad
  std::optional<motion::Elbow> elbow;               // ptp to a pose: only solutions in this configuration
  Eigen::Vector3d via = Eigen::Vector3d::Zero();  // circ: a point on the arc (m)
  std::optional<double> speed;          // lin, circ: the tool point's speed, m/s (> 0)
  std::optional<double> angular_speed;  // lin, circ: the tool's turning speed, rad/s (> 0)
  std::optional<double> speed_fraction;  // ptp: of the joints' velocity limits, (0, 1]
  double zone = 0;                       // lin, circ: fly-by radius at the end, m (>= 0)
  bool operator==(const PathMove&) const = default;
};

struct PathFile {
  std::vector<PathMove> moves;
  bool operator==(const PathFile&) const = default;
};

// `source` names the text in errors ("pick.path:12:5: ...").
Result<PathFile> parse_path_file(std::string_view text, std::string_view source = "<path>");
// One move line's fields (the first the move's kind: ptp, lin, circ), the line numbered
// `line` of `source`. What a points file reads its points' fields with.
Result<PathMove> parse_path_move(std::span<const TextField> fields, std::size_t line, std::string_view source);
// Reads a regular file of at most 1 MiB (as config files are read), then parses it.
Result<PathFile> read_path_file(const std::filesystem::path& path);

// Canonical text in SI units (m, rad, m/s, rad/s, %): parse_path_file(format_path_file(f))
// gives f back (speed fractions to within rounding of the percent).
std::string format_path_file(const PathFile& file);

}  // namespace armctl::files
