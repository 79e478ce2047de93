#include "calibration/joint_pictures.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <fmt/format.h>

#include "calibration/joint_steps.hpp"

namespace armctl::calibration {
namespace {

constexpr int kColumns = 3;
constexpr double kPanelWidth = 300, kDrawHeight = 250, kTextHeight = 46, kPad = 18;
constexpr int kCircleSamples = 16;

struct Point2 {
  double x = 0, y = 0;
};

// The view: u to the right, v up, looking along -d (from the side d points to).
struct View {
  Eigen::Vector3d u, v;
  Point2 project(const Eigen::Vector3d& p) const { return {p.dot(u), p.dot(v)}; }
};

View view_along(const Eigen::Vector3d& d) {
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ() - Eigen::Vector3d::UnitZ().dot(d) * d;
  if (up.norm() < 0.1) up = Eigen::Vector3d::UnitY() - Eigen::Vector3d::UnitY().dot(d) * d;
  View view;
  view.v = up.normalized();
  view.u = view.v.cross(d).normalized();  // u x v = d: counter-clockwise is a positive turn about d
  return view;
}

// A prismatic joint is seen from the side: across the arm's reach, so its links lie in the picture.
Eigen::Vector3d side_for(const Eigen::Vector3d& axis, const Eigen::Vector3d& tool) {
  Eigen::Vector3d d = axis.cross(Eigen::Vector3d::UnitZ());
  if (d.norm() > 0.1) return d.normalized();
  Eigen::Vector3d reach(tool.x(), tool.y(), 0);
  if (reach.norm() < 1e-6) reach = Eigen::Vector3d::UnitX();
  return Eigen::Vector3d::UnitZ().cross(reach).normalized();
}

// Points of a shape whose projection's convex hull is the shape's outline (a sphere: its
// outline circle in the view's plane).
void outline_points(const motion::Shape& shape, const Eigen::Isometry3d& body, const View& view,
                    std::vector<Point2>& out) {
  const Eigen::Isometry3d frame = body * shape.pose;
  auto put = [&](const Eigen::Vector3d& local) { out.push_back(view.project(frame * local)); };
  switch (shape.kind) {
    case motion::Shape::Kind::box:
      for (int i = 0; i < 8; ++i)
        put({(i & 1 ? 0.5 : -0.5) * shape.size.x(), (i & 2 ? 0.5 : -0.5) * shape.size.y(),
             (i & 4 ? 0.5 : -0.5) * shape.size.z()});
      break;
    case motion::Shape::Kind::cylinder:
      for (int i = 0; i < kCircleSamples; ++i) {
        const double a = 2 * std::numbers::pi * i / kCircleSamples;
        const double r = shape.size.x(), h = shape.size.y() / 2;
        put({r * std::cos(a), r * std::sin(a), -h});
        put({r * std::cos(a), r * std::sin(a), h});
      }
      break;
    case motion::Shape::Kind::sphere:
    case motion::Shape::Kind::capsule: {
      // A sphere's outline about its centre; a capsule's about each end's centre.
      const double h = shape.kind == motion::Shape::Kind::capsule ? shape.size.y() / 2 : 0.0;
      for (const double end : {-h, h})
        for (int i = 0; i < kCircleSamples; ++i) {
          const double a = 2 * std::numbers::pi * i / kCircleSamples;
          const Eigen::Vector3d c = frame * Eigen::Vector3d(0, 0, end);
          out.push_back(view.project(c + shape.size.x() * (std::cos(a) * view.u + std::sin(a) * view.v)));
        }
      break;
    }
  }
}

// Andrew's monotone chain: the convex hull, counter-clockwise.
std::vector<Point2> hull(std::vector<Point2> p) {
  std::sort(p.begin(), p.end(), [](const Point2& a, const Point2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  if (p.size() < 3) return p;
  auto cross = [](const Point2& o, const Point2& a, const Point2& b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
  };
  std::vector<Point2> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross(h[k - 2], h[k - 1], p[i - 1]) <= 0) --k;
    h[k++] = p[i - 1];
  }
  h.resize(k - 1);
  return h;
}

struct Outline {
  std::vector<Point2> points;
  bool moved = false;  // the joint moves it
};

// Every shape's outline at `joints`.
std::vector<Outline> outlines(const motion::LinkBodies& bodies, const std::vector<double>& joints, int joint,
                              const View& view) {
  std::vector<Eigen::Isometry3d> poses;
  bodies.poses(joints, poses);
  std::vector<Outline> out;
  for (std::size_t b = 0; b < bodies.bodies.size(); ++b)
    for (const auto& shape : bodies.bodies[b].shapes) {
      Outline o;
      std::vector<Point2> points;
      outline_points(shape, poses[b], view, points);
      o.points = hull(std::move(points));
      o.moved = bodies.moved_by(int(b), joint);
      out.push_back(std::move(o));
    }
  return out;
}

// Model coordinates to the panel's pixels: equal scales, y up.
struct Fit {
  double scale = 1, cx = 0, cy = 0, x0 = 0, y0 = 0;
  Point2 at(const Point2& p) const { return {x0 + (p.x - cx) * scale, y0 - (p.y - cy) * scale}; }
};

std::string polygon(const std::vector<Point2>& points, const Fit& fit, const char* style) {
  std::string d;
  for (const auto& p : points) {
    const Point2 s = fit.at(p);
    d += fmt::format("{}{:.1f},{:.1f}", d.empty() ? "" : " ", s.x, s.y);
  }
  return fmt::format("<polygon points=\"{}\" {}/>\n", d, style);
}

std::string arrow_head(const Point2& tip, const Point2& from) {
  const double dx = tip.x - from.x, dy = tip.y - from.y, n = std::hypot(dx, dy);
  if (n < 1e-9) return "";
  const double ux = dx / n, uy = dy / n, l = 9, w = 4.5;
  return fmt::format("<polygon points=\"{:.1f},{:.1f} {:.1f},{:.1f} {:.1f},{:.1f}\" fill=\"#d23a1e\"/>\n", tip.x, tip.y,
                     tip.x - l * ux - w * uy, tip.y - l * uy + w * ux, tip.x - l * ux + w * uy, tip.y - l * uy - w * ux);
}

std::string value_text(const arm::JointModel& j, double si) {
  return j.dimension == Dimension::angle ? fmt::format("{:.0f} deg", si * 180 / std::numbers::pi)
                                         : fmt::format("{:.0f} mm", si * 1000);
}

Result<std::string> panel(const arm::ArmModel& model, int joint, double left, double top) {
  const motion::LinkBodies& bodies = *model.bodies;
  const arm::JointModel& jm = model.joints[std::size_t(joint)];
  std::vector<double> mark(model.joints.size());
  for (std::size_t i = 0; i < mark.size(); ++i) mark[i] = mark_of(model.joints[i]);
  const bool turns = jm.dimension == Dimension::angle;
  std::vector<double> moved = mark;
  moved[std::size_t(joint)] = std::min(mark[std::size_t(joint)] + (turns ? kPictureTurn : kPictureTravel), jm.urdf_upper);

  int first = -1;  // the body the joint moves directly: its frame is the joint's
  for (std::size_t b = 0; b < bodies.bodies.size() && first < 0; ++b)
    if (bodies.bodies[b].joint == joint) first = int(b);
  if (first < 0)
    return Error{ErrorKind::invalid_config, fmt::format("joint '{}' moves no link of the URDF: no picture", jm.name)};
  std::vector<Eigen::Isometry3d> poses;
  bodies.poses(mark, poses);
  const Eigen::Vector3d origin = poses[std::size_t(first)].translation();
  const Eigen::Vector3d axis = (poses[std::size_t(first)].linear() * bodies.bodies[std::size_t(first)].axis).normalized();
  Eigen::Vector3d tool = origin;
  if (model.kinematics) {
    motion::JointVector chain(model.chain_joints());
    for (int i = 0; i < model.chain_joints(); ++i) chain[i] = mark[std::size_t(i)];
    tool = model.kinematics->forward(chain).position;
  }
  const View view = view_along(turns ? axis : side_for(axis, tool));

  const auto at_mark = outlines(bodies, mark, joint, view);
  const auto at_moved = outlines(bodies, moved, joint, view);
  // The arrow: a turn about the joint's centre through the tip of what it moves, or its travel.
  const Point2 centre = view.project(origin);
  Point2 tip = centre;
  double reach = 0;
  for (const auto& o : at_mark)
    if (o.moved)
      for (const auto& p : o.points)
        if (double r = std::hypot(p.x - centre.x, p.y - centre.y); r > reach) reach = r, tip = p;

  double lo_x = 1e9, lo_y = 1e9, hi_x = -1e9, hi_y = -1e9;
  for (const auto* set : {&at_mark, &at_moved})
    for (const auto& o : *set)
      for (const auto& p : o.points) lo_x = std::min(lo_x, p.x), hi_x = std::max(hi_x, p.x), lo_y = std::min(lo_y, p.y), hi_y = std::max(hi_y, p.y);
  Fit fit;
  fit.scale = std::min((kPanelWidth - 2 * kPad) / std::max(hi_x - lo_x, 1e-6), (kDrawHeight - 2 * kPad) / std::max(hi_y - lo_y, 1e-6));
  fit.cx = (lo_x + hi_x) / 2, fit.cy = (lo_y + hi_y) / 2;
  fit.x0 = left + kPanelWidth / 2, fit.y0 = top + kDrawHeight / 2;

  std::string svg = fmt::format("<rect x=\"{:.0f}\" y=\"{:.0f}\" width=\"{:.0f}\" height=\"{:.0f}\" fill=\"#fff\" stroke=\"#999\"/>\n",
                                left, top, kPanelWidth, kDrawHeight + kTextHeight);
  for (const auto& o : at_mark) svg += polygon(o.points, fit, "fill=\"#c8c8c8\" stroke=\"#555\" stroke-width=\"0.8\"");
  for (const auto& o : at_moved)
    if (o.moved) svg += polygon(o.points, fit, "fill=\"#4a90d9\" fill-opacity=\"0.45\" stroke=\"#1f5fbf\" stroke-width=\"0.8\"");

  const Point2 c = fit.at(centre);
  std::string path;
  Point2 last, before;
  if (turns) {
    // In the view's own coordinates a positive turn is counter-clockwise; the pixels flip y.
    const double radius = std::clamp(reach * fit.scale * 0.8, 22.0, kDrawHeight * 0.42);
    const double a0 = reach > 1e-9 ? std::atan2(tip.y - centre.y, tip.x - centre.x) : 0.0;
    for (int i = 0; i <= 12; ++i) {
      const double a = a0 + (kPictureTurn + 0.15) * i / 12;
      before = last;
      last = {c.x + radius * std::cos(a), c.y - radius * std::sin(a)};
      path += fmt::format("{}{:.1f},{:.1f}", path.empty() ? "" : " ", last.x, last.y);
    }
  } else {
    const Point2 end = view.project(origin + axis * kPictureTravel);
    double dx = end.x - centre.x, dy = end.y - centre.y;
    const double n = std::hypot(dx, dy) * fit.scale;
    const double stretch = n > 1e-9 ? std::max(1.0, 40.0 / n) : 1.0;
    before = {c.x + 8, c.y};
    last = {c.x + 8 + dx * fit.scale * stretch, c.y - dy * fit.scale * stretch};
    path = fmt::format("{:.1f},{:.1f} {:.1f},{:.1f}", before.x, before.y, last.x, last.y);
  }
  svg += fmt::format("<polyline points=\"{}\" fill=\"none\" stroke=\"#d23a1e\" stroke-width=\"2\"/>\n", path);
  svg += arrow_head(last, before);
  svg += fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"3\" fill=\"#d23a1e\"/>\n", c.x, c.y);
  svg += fmt::format("<text x=\"{:.0f}\" y=\"{:.0f}\" font-size=\"14\" font-weight=\"bold\">{}. {}</text>\n", left + 8,
                     top + 18, joint + 1, jm.name);
  svg += fmt::format("<text x=\"{:.0f}\" y=\"{:.0f}\" font-size=\"12\">grey: at its mark ({}); blue: +{}</text>\n",
                     left + 8, top + kDrawHeight + 18, value_text(jm, mark[std::size_t(joint)]),
                     value_text(jm, moved[std::size_t(joint)] - mark[std::size_t(joint)]));
  svg += fmt::format("<text x=\"{:.0f}\" y=\"{:.0f}\" font-size=\"12\">{}</text>\n", left + 8, top + kDrawHeight + 36,
                     turns ? "seen along its axis: positive turns this way" : "seen from the side: positive moves this way");
  return svg;
}

}  // namespace

Result<std::string> joint_pictures_svg(const arm::ArmModel& model) {
  if (!model.bodies || model.bodies->bodies.empty())
    return Error{ErrorKind::invalid_config, fmt::format("arm '{}' has no link shapes in its URDF: no pictures", model.name)};
  const int n = model.joint_count();
  const int rows = (n + kColumns - 1) / kColumns;
  const double width = kColumns * kPanelWidth + (kColumns + 1) * 10;
  const double height = 40 + rows * (kDrawHeight + kTextHeight + 10);
  std::string svg = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0:.0f}\" height=\"{1:.0f}\" viewBox=\"0 0 {0:.0f} {1:.0f}\" "
      "font-family=\"sans-serif\">\n<rect width=\"100%\" height=\"100%\" fill=\"#f4f4f4\"/>\n"
      "<text x=\"10\" y=\"26\" font-size=\"16\" font-weight=\"bold\">{2}: each joint at its mark (grey) and moved "
      "in its positive direction (blue)</text>\n",
      width, height, model.name);
  for (int j = 0; j < n; ++j) {
    auto p = panel(model, j, 10 + (j % kColumns) * (kPanelWidth + 10), 40 + (j / kColumns) * (kDrawHeight + kTextHeight + 10));
    if (!p) return p.error();
    svg += *p;
  }
  return svg + "</svg>\n";
}

}  // namespace armctl::calibration
