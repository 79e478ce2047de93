// Cartesian paths: straight lines (LIN) and circular arcs (CIRC) of the tool, joined at
// corners either at rest or blended (fly-by within a zone). Pure code, value types, no I/O;
// the model and its bounds: docs/paths.md.
//
// The path is parametrized by "nominal time" s in [0, duration()]: at ds/dt = 1 the tool
// moves at each segment's programmed speed (a segment's nominal time is the larger of
// length / speed and rotation angle / angular_speed), so a speed override or a stop is only
// a change of ds/dt: the executor times s, the path stays the same.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "core/error.hpp"
#include "motion/kinematics.hpp"
#include "motion/move_limits.hpp"

namespace armctl::motion {

enum class SegmentKind { lin, circ };
const char* to_string(SegmentKind kind);  // "LIN", "CIRC" (as people write them)

// The detail of an error that refuses a path at one of its segments (build_cartesian_path,
// check_path, arm::plan_path; kind invalid_argument): which segment, and where on it when the
// refusal is at a point along it (the tool point there and the joint that refused). Its
// message is "segment N (KIND): " + reason. Apps map it to their own places (a program's
// line, a path file's move).
struct PathRefusal {
  int segment = 0;                         // 0-based, in the segments given
  SegmentKind kind = SegmentKind::lin;
  std::optional<double> fraction;          // where along the segment, 0..1
  std::optional<Eigen::Vector3d> point;    // the tool point there, base frame, m
  int joint = -1;                          // the chain joint that refused; -1: none named
  std::string joint_name;
  std::string reason;                      // the message without "segment N (KIND): "
};
// The Error for `refusal`, with its message built from it.
Error path_refusal(PathRefusal refusal);
inline const PathRefusal* path_refusal_of(const Error& error) { return error.detail_as<PathRefusal>(); }

struct PathSegment {
  SegmentKind kind = SegmentKind::lin;
  Pose target;                 // end pose of the tool (base frame, m)
  Eigen::Vector3d via{0, 0, 0};  // circ: a point on the arc between start and target
  double speed = kDefaultToolSpeed;                 // m/s of the tool point, > 0
  double angular_speed = kDefaultToolAngularSpeed;  // rad/s of the tool orientation, > 0
  double zone = 0;             // m: fly-by radius at this segment's end; 0 = stop exactly there
};

// d/ds of the tool at one s: velocity of the tool point (m per nominal s), angular velocity
// (rad per nominal s, base frame) and their derivatives.
struct PathRates {
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d acceleration = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_acceleration = Eigen::Vector3d::Zero();
};

// One segment as built: where it lies in s, its geometry, and the blend at its end.
struct BuiltSegment {
  SegmentKind kind = SegmentKind::lin;
  double start_s = 0, end_s = 0;  // nominal time of its start and end corner
  Pose start, target;
  double length = 0;  // m along the tool point's path (the arc for circ)
  double angle = 0;   // rad of tool rotation, start to target
  double speed = 0, angular_speed = 0;  // as programmed
  double blend = 0;   // tau: half-width (nominal s) of the blend window at its end, 0 = rest
  // circ only: centre, radius, the in-plane unit vectors (start direction, then 90 deg on
  // towards the via) and the arc's angle.
  Eigen::Vector3d centre = Eigen::Vector3d::Zero(), e1 = Eigen::Vector3d::Zero(), e2 = Eigen::Vector3d::Zero();
  double radius = 0, arc = 0;
};

class CartesianPath {
 public:
  double duration() const;   // nominal seconds
  Pose at(double s) const;   // s clamped to [0, duration()]
  PathRates rates(double s) const;  // s clamped; at a rest, the rates of the segment after it
  // Where the path comes to rest: corners without a blend and the end (ascending).
  std::vector<double> rests() const;
  int segment_at(double s) const;       // 0-based; a corner belongs to the segment it ends
  double segment_fraction(double s) const;  // 0..1 along segment_at(s), in its nominal time
  const std::vector<BuiltSegment>& segments() const { return segments_; }
  // The corner deviation of the blend at the end of segment `index`: the distance from the
  // corner point to the path in the middle of the window (3/16 tau |v2 - v1| between two
  // LINs), 0 at a rest.
  double corner_deviation(int index) const;

 private:
  friend Result<CartesianPath> build_cartesian_path(const Pose& start, std::span<const PathSegment> segments);
  std::vector<BuiltSegment> segments_;
};

// Validates and builds. Errors (invalid_argument) name the segment (1-based) and what is
// allowed: non-finite values, speeds <= 0, zone < 0, orientations that are not unit
// quaternions (within 1e-6 they are normalized), a segment that neither moves nor turns the
// tool, CIRC points that coincide or lie on one line. A zone on the last segment is ignored:
// the path ends at rest.
Result<CartesianPath> build_cartesian_path(const Pose& start, std::span<const PathSegment> segments);

}  // namespace armctl::motion
