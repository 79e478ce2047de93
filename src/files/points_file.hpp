// Points files: named arm positions kept apart from a program's code, typed by hand or
// written by `armctl teach` (format reference with examples: docs/programs.md "Points").
//
//   # xArm pick-and-place points
//   home   joints=0deg,30deg,-45deg,-60deg,0deg
//   pick   x=200mm y=0mm z=40mm pitch=90deg
//   place  x=120mm y=150mm z=40mm pitch=90deg elbow=up
//
// A line is a name and key=value fields that read exactly as a path file's ptp target
// (files/path_file.hpp): joints=... (one value per joint, chain then gripper, fewer leaves
// the rest as they are) or a tool pose x, y, z (and optionally roll, pitch, yaw, elbow).
// Values carry their unit. Names: a letter or '_' then letters, digits, '_' (at most 64),
// case-sensitive, each once, not a word of the program language. '#' starts a comment.
// Errors name the file, line and column, what was found and what is expected; nothing is
// returned on error.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "core/error.hpp"
#include "motion/kinematics.hpp"
#include "files/path_file.hpp"

namespace armctl::files {

inline constexpr std::size_t kPointsFileMaxPoints = 10'000;
inline constexpr std::size_t kPointNameMaxLength = 64;

struct Point {
  std::string name;
  std::size_t line = 0;  // 1-based, for messages (0: made in code)
  // Joint values (SI) in the arm's order, or empty for a pose.
  std::vector<JointValue> joints;
  // A tool pose (m, rad, base frame) when `joints` is empty. Orientation angles left out
  // keep the tool's current ones when the point is reached (as in path files).
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  std::optional<double> roll, pitch, yaw;
  std::optional<motion::Elbow> elbow;
  bool is_joints() const { return !joints.empty(); }
  bool operator==(const Point&) const = default;
};

struct PointsFile {
  std::vector<Point> points;
  const Point* find(std::string_view name) const;
  bool operator==(const PointsFile&) const = default;
};

// `source` names the text in errors ("pick.points:3:8: ..."). An empty file is allowed
// (a program without points).
Result<PointsFile> parse_points_file(std::string_view text, std::string_view source = "<points>");
// Reads a regular file of at most 1 MiB (as config files are read), then parses it.
Result<PointsFile> read_points_file(const std::filesystem::path& path);

// Text people read: lengths in mm, angles in deg, shortest round-trip digits, so
// parse_points_file(format_points_file(f)) gives f back (values to within 1e-12 relative).
std::string format_points_file(const PointsFile& file);
// One point's fields as format_points_file writes them ("joints=10deg,20deg").
std::string format_point_fields(const Point& point);

// `text` (a points file as it is on disk, a UTF-8 byte-order mark allowed and kept) made to
// hold `file` while keeping what a person wrote: comments, blank lines, line endings, the
// order, and the exact line of every point whose value did not change. A changed point gets
// new fields in its own line (its indentation, alignment and trailing comment kept); a point
// not in `file` loses its line; a point new to the text is appended. Text that does not
// parse is an error (`source` names it): nothing of it is guessed at.
Result<std::string> update_points_text(std::string_view text, const PointsFile& file, std::string_view source);

// Writes `file` to `path`: an existing file through update_points_text (so teaching or
// saving one point changes that point's line only), a new one as format_points_file.
// Atomically (core/atomic_file.hpp: a crash leaves the old file; a symlink is written
// through, the mode kept, a read-only file refused).
Status write_points_file(const std::filesystem::path& path, const PointsFile& file);

// Whether `name` may name a point (or a variable, or a subroutine) of a program, and if
// not, why ("'lin' is a word of the language").
std::optional<std::string> bad_name(std::string_view name);

}  // namespace armctl::files
