// Cartesian paths: LIN on its line at a constant rate, CIRC on its circle, blended corners
// within their zone with continuous velocity and acceleration and the stated deviation,
// nominal time, rests, and every validation error.
#include "motion/cartesian_path.hpp"

#include <cmath>
#include <numbers>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace armctl::motion {
namespace {

using ::testing::HasSubstr;
constexpr double kPi = std::numbers::pi;

Pose pose(double x, double y, double z, Rpy rpy = {}) {
  Pose p;
  p.position = {x, y, z};
  p.orientation = from_rpy(rpy);
  return p;
}

PathSegment lin(const Pose& target, double speed = 0.05, double zone = 0) {
  PathSegment s;
  s.target = target;
  s.speed = speed;
  s.zone = zone;
  return s;
}

PathSegment circ(const Eigen::Vector3d& via, const Pose& target, double speed = 0.05, double zone = 0) {
  PathSegment s = lin(target, speed, zone);
  s.kind = SegmentKind::circ;
  s.via = via;
  return s;
}

CartesianPath built(const Pose& start, const std::vector<PathSegment>& segments) {
  auto path = build_cartesian_path(start, segments);
  if (!path) throw std::runtime_error(path.error().message);
  return std::move(path).value();
}

double angle_between(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) { return a.angularDistance(b); }

double distance_to_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d d = b - a;
  const double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (a + t * d - p).norm();
}

TEST(CartesianPath, LinStaysOnItsLineAtAConstantRate) {
  const Pose start = pose(0.2, -0.1, 0.15, {kPi, 0, 0});
  const Pose target = pose(0.25, 0.1, 0.05, {kPi, 0.3, 0.2});
  const CartesianPath path = built(start, {lin(target, 0.04)});
  const double length = (target.position - start.position).norm();
  const double angle = angle_between(start.orientation, target.orientation);
  // Nominal time: the larger of length / speed and angle / angular speed (0.5 rad/s).
  ASSERT_NEAR(path.duration(), std::max(length / 0.04, angle / 0.5), 1e-12);
  const Eigen::Vector3d v = (target.position - start.position) / path.duration();
  for (int i = 0; i <= 1000; ++i) {
    const double s = path.duration() * i / 1000;
    const Pose p = path.at(s);
    EXPECT_LT(distance_to_segment(p.position, start.position, target.position), 1e-9) << s;
    EXPECT_LT((p.position - (start.position + v * s)).norm(), 1e-9) << s;  // constant rate
    EXPECT_NEAR(angle_between(start.orientation, p.orientation), angle * s / path.duration(), 1e-9) << s;
    EXPECT_NEAR(angle_between(p.orientation, target.orientation), angle * (1 - s / path.duration()), 1e-9) << s;
    const PathRates r = path.rates(s);
    EXPECT_LT((r.velocity - v).norm(), 1e-12);
    EXPECT_NEAR(r.angular_velocity.norm(), angle / path.duration(), 1e-12);
    EXPECT_LT(r.acceleration.norm(), 1e-12);
  }
  EXPECT_LT((path.at(path.duration()).position - target.position).norm(), 1e-15);
  EXPECT_LT((path.at(1e9).position - target.position).norm(), 1e-15);  // clamped
  EXPECT_LT((path.at(-1).position - start.position).norm(), 1e-15);
}

TEST(CartesianPath, TheSlowerOfLengthAndTurnSetsTheNominalTime) {
  const Pose start = pose(0.2, 0, 0.1);
  PathSegment turn = lin(pose(0.201, 0, 0.1, {0, 0, 1.0}), 0.05);
  turn.angular_speed = 0.25;
  const CartesianPath path = built(start, {turn});
  EXPECT_NEAR(path.duration(), 1.0 / 0.25, 1e-12);  // 4 s for the turn, 0.02 s for the 1 mm
  // A pure turn (no motion of the tool point) is a segment too.
  const CartesianPath spin = built(start, {lin(pose(0.2, 0, 0.1, {0.5, 0, 0}))});
  EXPECT_NEAR(spin.duration(), 0.5 / kDefaultToolAngularSpeed, 1e-12);  // at the default 45 deg/s
  EXPECT_LT((spin.at(0.5).position - start.position).norm(), 1e-15);
}

TEST(CartesianPath, CircStaysOnTheCircleThroughItsThreePoints) {
  // A circle of radius 50 mm about (0.2, 0, 0.1) tilted out of every base plane.
  const Eigen::Vector3d centre(0.2, 0, 0.1);
  const Eigen::Vector3d e1 = Eigen::Vector3d(1, 1, 0).normalized(), e2 = Eigen::Vector3d(-1, 1, 2).normalized();
  auto on = [&](double t) { return Eigen::Vector3d(centre + 0.05 * (std::cos(t) * e1 + std::sin(t) * e2)); };
  Pose start = pose(0, 0, 0, {kPi, 0, 0});
  start.position = on(0);
  Pose target = pose(0, 0, 0, {kPi, 0, 1.0});
  target.position = on(4.0);  // more than half a turn
  const CartesianPath path = built(start, {circ(on(3.0), target, 0.02)});
  EXPECT_NEAR(path.duration(), 0.05 * 4.0 / 0.02, 1e-9);
  const auto& g = path.segments()[0];
  EXPECT_LT((g.centre - centre).norm(), 1e-12);
  EXPECT_NEAR(g.radius, 0.05, 1e-12);
  EXPECT_NEAR(g.arc, 4.0, 1e-12);
  const Eigen::Vector3d normal = e1.cross(e2);
  double nearest_via = 1;
  for (int i = 0; i <= 2000; ++i) {
    const double s = path.duration() * i / 2000;
    const Eigen::Vector3d p = path.at(s).position;
    EXPECT_NEAR((p - centre).norm(), 0.05, 1e-12) << s;
    EXPECT_NEAR((p - centre).dot(normal), 0, 1e-12) << s;
    EXPECT_LT((p - on(4.0 * s / path.duration())).norm(), 1e-12) << s;  // constant rate along the arc
    EXPECT_NEAR(path.rates(s).velocity.norm(), 0.02, 1e-12);
    EXPECT_NEAR(path.rates(s).acceleration.norm(), 0.02 * 0.02 / 0.05, 1e-12);  // v^2 / r
    nearest_via = std::min(nearest_via, (p - on(3.0)).norm());
  }
  EXPECT_LT(nearest_via, 0.05 * 4.0 / 2000);  // passes the via
  EXPECT_LT((path.at(path.duration()).position - target.position).norm(), 1e-15);
  EXPECT_NEAR(angle_between(path.at(path.duration() / 4).orientation, start.orientation), 0.25, 1e-9);
}

// Finite-difference checks of at() against rates() over a whole path.
void expect_rates_match_positions(const CartesianPath& path, double tolerance_v, double tolerance_a) {
  const double h = 1e-5;
  for (int i = 1; i < 4000; ++i) {
    const double s = path.duration() * i / 4000;
    const Eigen::Vector3d v = (path.at(s + h).position - path.at(s - h).position) / (2 * h);
    const PathRates r = path.rates(s);
    EXPECT_LT((v - r.velocity).norm(), tolerance_v) << "s " << s;
    const Eigen::Vector3d a = (path.rates(s + h).velocity - path.rates(s - h).velocity) / (2 * h);
    EXPECT_LT((a - r.acceleration).norm(), tolerance_a) << "s " << s;
    const Eigen::Quaterniond q0 = path.at(s - h).orientation, q1 = path.at(s + h).orientation;
    Eigen::Quaterniond d = q1 * q0.conjugate();
    if (d.w() < 0) d.coeffs() = -d.coeffs();
    const Eigen::Vector3d w = d.vec() * (2 / (2 * h));
    EXPECT_LT((w - r.angular_velocity).norm(), tolerance_v * 10) << "s " << s;
  }
}

// Largest jump of velocity and of acceleration between s - eps and s + eps at any s.
std::pair<double, double> largest_jumps(const CartesianPath& path, double from, double to, double eps) {
  double v = 0, a = 0;
  for (int i = 0; i <= 20000; ++i) {
    const double s = from + (to - from) * i / 20000;
    const PathRates r0 = path.rates(s - eps), r1 = path.rates(s + eps);
    v = std::max(v, (r1.velocity - r0.velocity).norm());
    a = std::max(a, (r1.acceleration - r0.acceleration).norm());
  }
  return {v, a};
}

TEST(CartesianPath, BlendedCornerStaysInTheZoneWithContinuousVelocityAndAcceleration) {
  const Pose start = pose(0.2, 0, 0.1, {kPi, 0, 0});
  const Pose corner = pose(0.3, 0, 0.1, {kPi, 0, 0.3});
  const Pose end = pose(0.3, 0.08, 0.15, {kPi, 0.2, 0.3});
  const double zone = 0.01;
  const CartesianPath path = built(start, {lin(corner, 0.05, zone), lin(end, 0.08)});
  const auto& a = path.segments()[0];
  const auto& b = path.segments()[1];
  const Eigen::Vector3d v1 = (corner.position - start.position) / (a.end_s - a.start_s);
  const Eigen::Vector3d v2 = (end.position - corner.position) / (b.end_s - b.start_s);
  const double tau = a.blend;
  ASSERT_GT(tau, 0);
  // tau: the largest with |v1| tau <= zone, |v2| tau <= zone and half of each segment's time.
  EXPECT_NEAR(tau, std::min({zone / v1.norm(), zone / v2.norm(), (a.end_s - a.start_s) / 2, (b.end_s - b.start_s) / 2}),
              1e-15);
  // The deviation: 3/16 tau |v2 - v1|, in the middle of the window.
  const double bound = 3.0 / 16.0 * tau * (v2 - v1).norm();
  EXPECT_NEAR(path.corner_deviation(0), bound, 1e-12);
  EXPECT_NEAR((path.at(a.end_s).position - corner.position).norm(), bound, 1e-12);
  // Inside the window: within the zone of the corner; outside it: on the segments.
  double farthest = 0;
  for (int i = 0; i <= 2000; ++i) {
    const double s = a.end_s - tau + 2 * tau * i / 2000;
    const double d = (path.at(s).position - corner.position).norm();
    farthest = std::max(farthest, d);
    EXPECT_LE(d, zone + 1e-12) << s;
  }
  EXPECT_NEAR(farthest, zone, 1e-9);  // it leaves and joins exactly at the zone's edge
  EXPECT_LT(distance_to_segment(path.at(a.end_s - tau - 1e-9).position, start.position, corner.position), 1e-12);
  EXPECT_LT(distance_to_segment(path.at(a.end_s + tau + 1e-9).position, corner.position, end.position), 1e-12);
  // No stop at the corner: the path's rests are only its end.
  EXPECT_EQ(path.rests(), std::vector<double>{path.duration()});
  expect_rates_match_positions(path, 1e-8, 1e-4);
  // Continuous: jumps over 2 eps shrink with eps (no step anywhere, also at the window's edges).
  const auto [dv, da] = largest_jumps(path, a.end_s - 2 * tau, a.end_s + 2 * tau, 1e-8);
  EXPECT_LT(dv, 1e-7);
  EXPECT_LT(da, 1e-6);
  // Without the zone the velocity jumps at the corner, where the path rests.
  const CartesianPath stop = built(start, {lin(corner, 0.05), lin(end, 0.08)});
  EXPECT_EQ(stop.rests(), (std::vector<double>{a.end_s, stop.duration()}));
  EXPECT_EQ(stop.corner_deviation(0), 0);
  EXPECT_GT(largest_jumps(stop, a.end_s - 0.01, a.end_s + 0.01, 1e-7).first, 0.05);
}

TEST(CartesianPath, BlendIsCappedAtHalfOfEachNeighboursTime) {
  const Pose start = pose(0.2, 0, 0.1);
  const CartesianPath path = built(start, {lin(pose(0.21, 0, 0.1), 0.05, 0.5), lin(pose(0.21, 0.04, 0.1), 0.05)});
  const auto& a = path.segments()[0];
  EXPECT_NEAR(a.blend, (a.end_s - a.start_s) / 2, 1e-15);  // 10 mm: 0.1 s each way, not 0.5 m worth
  EXPECT_LE(path.corner_deviation(0), 0.5);
  // A zone on the last segment is ignored: the path ends at rest.
  const CartesianPath last = built(start, {lin(pose(0.21, 0, 0.1), 0.05, 0.01)});
  EXPECT_EQ(last.segments()[0].blend, 0);
  EXPECT_EQ(last.rests(), std::vector<double>{last.duration()});
}

TEST(CartesianPath, BlendsWithACircNeighbourStayInTheZoneAndAreContinuous) {
  const Pose start = pose(0.2, 0, 0.1, {kPi, 0, 0});
  const Pose p1 = pose(0.3, 0, 0.1, {kPi, 0, 0});
  const Pose p2 = pose(0.3, 0.1, 0.1, {kPi, 0, 0.5});
  const Pose p3 = pose(0.2, 0.1, 0.12, {kPi, 0, 0.5});
  const double zone = 0.008;
  const CartesianPath path = built(start, {lin(p1, 0.05, zone), circ({0.35, 0.05, 0.1}, p2, 0.04, zone), lin(p3, 0.06)});
  for (int k = 0; k < 2; ++k) {
    const auto& g = path.segments()[std::size_t(k)];
    ASSERT_GT(g.blend, 0);
    for (int i = 0; i <= 2000; ++i) {
      const double s = g.end_s - g.blend + 2 * g.blend * i / 2000;
      EXPECT_LE((path.at(s).position - g.target.position).norm(), zone + 1e-12) << "corner " << k << " s " << s;
    }
    EXPECT_GT(path.corner_deviation(k), 0);
    EXPECT_LT(path.corner_deviation(k), zone);
    const auto [dv, da] = largest_jumps(path, g.end_s - 2 * g.blend, g.end_s + 2 * g.blend, 1e-8);
    EXPECT_LT(dv, 1e-7) << k;
    EXPECT_LT(da, 1e-6) << k;
  }
  // On the circle outside the windows.
  const auto& c = path.segments()[1];
  for (int i = 0; i <= 100; ++i) {
    const double s = c.start_s + path.segments()[0].blend + (c.end_s - c.blend - c.start_s - path.segments()[0].blend) * i / 100;
    EXPECT_NEAR((path.at(s).position - c.centre).norm(), c.radius, 1e-12);
  }
  expect_rates_match_positions(path, 1e-8, 1e-4);
}

TEST(CartesianPath, SegmentAtAndFractionNameWhereOnThePathSIs) {
  const Pose start = pose(0.2, 0, 0.1);
  const CartesianPath path = built(start, {lin(pose(0.25, 0, 0.1)), lin(pose(0.25, 0.1, 0.1))});
  EXPECT_EQ(path.segment_at(0), 0);
  EXPECT_EQ(path.segment_at(path.segments()[0].end_s), 0);  // the corner belongs to the segment it ends
  EXPECT_EQ(path.segment_at(1.5), 1);
  EXPECT_NEAR(path.segment_fraction(0.5), 0.5, 1e-12);
  EXPECT_NEAR(path.segment_fraction(2.0), 0.5, 1e-12);
  EXPECT_EQ(path.segment_at(99), 1);
}

Error refused(const Pose& start, const std::vector<PathSegment>& segments) {
  auto path = build_cartesian_path(start, segments);
  EXPECT_FALSE(path.ok());
  if (path) return Error{ErrorKind::io, "built"};
  EXPECT_EQ(path.error().kind, ErrorKind::invalid_argument);
  return path.error();
}

TEST(CartesianPath, ValidationNamesTheSegmentAndWhatIsAllowed) {
  const Pose start = pose(0.2, 0, 0.1);
  const PathSegment ok = lin(pose(0.25, 0, 0.1));
  const double nan = std::nan("");
  EXPECT_THAT(refused(start, {}).message, HasSubstr("at least one segment"));
  {
    PathSegment s = ok;
    s.target.position.y() = nan;
    EXPECT_THAT(refused(start, {ok, s}).message, HasSubstr("segment 2 (LIN): target: the position is not a finite"));
    const Error e = refused(start, {ok, s});
    ASSERT_NE(path_refusal_of(e), nullptr);
    EXPECT_EQ(path_refusal_of(e)->segment, 1);
    EXPECT_FALSE(path_refusal_of(e)->fraction);  // the segment as a whole
    EXPECT_EQ(path_refusal_of(e)->joint, -1);
  }
  {
    PathSegment s = ok;
    s.speed = 0;
    EXPECT_THAT(refused(start, {s}).message, HasSubstr("segment 1 (LIN): speed 0 is not allowed; it must be a finite number > 0"));
    s.speed = 0.05;
    s.angular_speed = -1;
    EXPECT_THAT(refused(start, {s}).message, HasSubstr("angular speed -1 is not allowed"));
    s.angular_speed = std::numeric_limits<double>::infinity();
    EXPECT_THAT(refused(start, {s}).message, HasSubstr("angular speed inf is not allowed"));
  }
  {
    PathSegment s = ok;
    s.zone = -0.001;
    EXPECT_THAT(refused(start, {s, ok}).message, HasSubstr("segment 1 (LIN): zone -0.001 is not allowed; it must be a finite number >= 0"));
  }
  {
    PathSegment s = ok;
    s.target.orientation.coeffs() *= 1.1;
    EXPECT_THAT(refused(start, {s}).message, HasSubstr("not a unit quaternion (norm 1.1); allowed: norm 1 within 1e-06"));
    s.target.orientation = Eigen::Quaterniond::Identity();
    s.target.orientation.coeffs() *= 1 + 5e-7;  // near-unit: normalized
    auto path = build_cartesian_path(start, std::vector<PathSegment>{s});
    ASSERT_TRUE(path.ok()) << path.error().message;
    EXPECT_NEAR(path->at(path->duration()).orientation.norm(), 1, 1e-15);
  }
  {
    Pose bad = start;
    bad.orientation.coeffs() *= 0;
    EXPECT_THAT(refused(bad, {ok}).message, HasSubstr("the path's start pose: the orientation is not a unit quaternion"));
  }
  EXPECT_THAT(refused(start, {ok, lin(pose(0.25, 0, 0.1))}).message,
              HasSubstr("segment 2 (LIN): the target is where the segment starts (it neither moves nor turns the tool)"));
}

// A coordinate of 1e200 or 1e308 m is finite but its distance is not; such a path had an
// infinite nominal time, and the check read past its samples (heap-buffer-overflow in
// differentiate). A speed of 1e300 m/s made a segment take no time. Both are refused here.
TEST(CartesianPath, LengthsAndTimesThatAreNotFiniteAreRefused) {
  const Pose start = pose(0.2, 0, 0.1);
  for (double x : {1e200, 1e308, -1e308}) {
    EXPECT_THAT(refused(start, {lin(pose(x, 0, 0.1))}).message,
                HasSubstr("segment 1 (LIN): the target is inf m from the segment's start, taking inf s at 0.05 m/s; a "
                          "segment's length and time must be finite numbers"))
        << x;
  }
  PathSegment fast = lin(pose(0.3, 0, 0.1), 1e300);
  fast.angular_speed = 0.5;
  EXPECT_THAT(refused(start, {lin(pose(0.25, 0, 0.1)), fast}).message,
              HasSubstr("segment 2 (LIN): at 1e+300 m/s and 0.5 rad/s its 0.05 m and 0 rad take no time after "
                        "the 1 s of path before it; lower its speed"));
}

TEST(CartesianPath, CircRefusesPointsThatMakeNoCircle) {
  const Pose start = pose(0.2, 0, 0.1);
  const Pose target = pose(0.3, 0, 0.1);
  EXPECT_THAT(refused(start, {circ({0.2, 0, 0.1}, target)}).message,
              HasSubstr("segment 1 (CIRC): the via point is at the segment's start"));
  EXPECT_THAT(refused(start, {circ({0.3, 0, 0.1}, target)}).message, HasSubstr("the via point is at the target"));
  EXPECT_THAT(refused(start, {circ({0.25, 0.05, 0.1}, start)}).message,
              HasSubstr("the target is at the segment's start; a full circle needs two CIRC segments"));
  EXPECT_THAT(refused(start, {circ({0.25, 0, 0.1}, target)}).message,
              HasSubstr("start, via and target lie on one line"));
  EXPECT_THAT(refused(start, {circ({0.4, 0, 0.1}, target)}).message, HasSubstr("lie on one line"));  // beyond the target
  PathSegment s = circ({0.25, 0.05, 0.1}, target);
  s.via.z() = std::nan("");
  EXPECT_THAT(refused(start, {s}).message, HasSubstr("segment 1 (CIRC): the via point is not a finite number"));
  // A via anywhere off the line gives the arc through it: here the long way round.
  const CartesianPath back = built(start, {circ({0.25, -0.05, 0.1}, target)});
  EXPECT_NEAR(back.segments()[0].arc, kPi, 1e-12);
}

}  // namespace
}  // namespace armctl::motion
