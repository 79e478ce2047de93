#include "motion/link_bodies.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <urdf_model/model.h>

#include "motion/urdf_capsules.hpp"
#include "motion/urdf_model.hpp"

namespace armctl::motion {

const char* to_string(Shape::Kind kind) {
  switch (kind) {
    case Shape::Kind::box: return "box";
    case Shape::Kind::cylinder: return "cylinder";
    case Shape::Kind::sphere: return "sphere";
    case Shape::Kind::capsule: return "capsule";
  }
  return "?";
}

double bounding_radius(const Shape& s) {
  switch (s.kind) {
    case Shape::Kind::box: return 0.5 * s.size.norm();
    case Shape::Kind::cylinder: return std::hypot(s.size.x(), 0.5 * s.size.y());
    case Shape::Kind::sphere: return s.size.x();
    case Shape::Kind::capsule: return 0.5 * s.size.y() + s.size.x();
  }
  return 0;
}

void world_bounds(const Shape& s, const Eigen::Isometry3d& pose, Eigen::Vector3d& low, Eigen::Vector3d& high) {
  const Eigen::Matrix3d& r = pose.linear();
  Eigen::Vector3d half = Eigen::Vector3d::Zero();  // every kind sets it: g++ 12 -O2 cannot see that (-Wmaybe-uninitialized)
  switch (s.kind) {
    case Shape::Kind::box:
      half = r.cwiseAbs() * (0.5 * s.size);
      break;
    case Shape::Kind::cylinder: {
      // The disc of radius r about the axis a spans r * sqrt(1 - a_i^2) along axis i.
      const Eigen::Vector3d a = r.col(2);
      const double radius = s.size.x(), h = 0.5 * s.size.y();
      for (int i = 0; i < 3; ++i) half[i] = h * std::abs(a[i]) + radius * std::sqrt(std::max(0.0, 1 - a[i] * a[i]));
      break;
    }
    case Shape::Kind::sphere:
      half = Eigen::Vector3d::Constant(s.size.x());
      break;
    case Shape::Kind::capsule:
      // The segment between the half spheres' centres, grown by the radius every way.
      half = 0.5 * s.size.y() * r.col(2).cwiseAbs() + Eigen::Vector3d::Constant(s.size.x());
      break;
  }
  low = pose.translation() - half;
  high = pose.translation() + half;
}

std::optional<int> LinkBodies::find(std::string_view name) const {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (bodies[i].name == name) return static_cast<int>(i);
  }
  return std::nullopt;
}

void LinkBodies::poses(std::span<const double> joints, std::vector<Eigen::Isometry3d>& out) const {
  out.resize(bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const LinkBody& b = bodies[i];
    Eigen::Isometry3d t = b.parent < 0 ? Eigen::Isometry3d::Identity() : out[std::size_t(b.parent)] * b.origin;
    if (b.joint >= 0 && std::size_t(b.joint) < joints.size()) {
      const double q = joints[std::size_t(b.joint)];
      if (b.prismatic) {
        t.translate(q * b.axis);
      } else {
        t.rotate(Eigen::AngleAxisd(q, b.axis));
      }
    }
    out[i] = t;
  }
}

bool LinkBodies::moves(int body) const {
  for (int i = body; i >= 0; i = bodies[std::size_t(i)].parent) {
    if (bodies[std::size_t(i)].joint >= 0) return true;
  }
  return false;
}

bool LinkBodies::moved_by(int body, int joint) const {
  for (int i = body; i >= 0; i = bodies[std::size_t(i)].parent) {
    if (bodies[std::size_t(i)].joint == joint) return true;
  }
  return false;
}

namespace {

Error config_error(std::string message) { return Error{ErrorKind::invalid_config, std::move(message)}; }

bool positive(double v) { return std::isfinite(v) && v > 0; }

Result<Shape> collision_shape(const urdf::Collision& c, const std::string& link, std::size_t n,
                              std::span<const UrdfCapsule> capsules) {
  const std::string what = fmt::format("link '{}' <collision> {}", link, n + 1);
  if (!c.geometry) return config_error(fmt::format("URDF {}: no <geometry>", what));
  Shape s;
  auto pose = urdf_pose(c.origin, what);
  if (!pose) return pose.error();
  s.pose = *pose;
  // urdfdom read it as a cylinder of its size (motion/urdf_capsules.hpp), checked there.
  for (const UrdfCapsule& capsule : capsules) {
    if (capsule.link != link || capsule.collision != n) continue;
    s.kind = Shape::Kind::capsule;
    s.size = {capsule.radius, capsule.length, 0};
    return s;
  }
  const char* allowed =
      "a <box size>, <cylinder radius length>, <sphere radius> or <capsule radius length> with sizes above 0 (m)";
  switch (c.geometry->type) {
    case urdf::Geometry::BOX: {
      const auto& d = static_cast<const urdf::Box&>(*c.geometry).dim;
      s.kind = Shape::Kind::box;
      s.size = {d.x, d.y, d.z};
      if (!positive(d.x) || !positive(d.y) || !positive(d.z)) {
        return config_error(fmt::format("URDF {}: box size {} {} {}: wants {}", what, d.x, d.y, d.z, allowed));
      }
      break;
    }
    case urdf::Geometry::CYLINDER: {
      const auto& g = static_cast<const urdf::Cylinder&>(*c.geometry);
      s.kind = Shape::Kind::cylinder;
      s.size = {g.radius, g.length, 0};
      if (!positive(g.radius) || !positive(g.length)) {
        return config_error(fmt::format("URDF {}: cylinder radius {} length {}: wants {}", what, g.radius, g.length, allowed));
      }
      break;
    }
    case urdf::Geometry::SPHERE: {
      const auto& g = static_cast<const urdf::Sphere&>(*c.geometry);
      s.kind = Shape::Kind::sphere;
      s.size = {g.radius, 0, 0};
      if (!positive(g.radius)) return config_error(fmt::format("URDF {}: sphere radius {}: wants {}", what, g.radius, allowed));
      break;
    }
    default:
      return config_error(fmt::format("URDF {}: a <mesh>: collision shapes are primitives: {}", what, allowed));
  }
  return s;
}

}  // namespace

Result<LinkBodies> read_link_bodies(std::string_view urdf_xml, std::string_view base_link,
                                    std::span<const std::string> joint_names,
                                    std::span<const OriginLength> lengths) {
  std::vector<UrdfCapsule> capsules;
  auto parsed = parse_urdf_model(std::string(urdf_xml), &capsules);
  if (!parsed) return parsed.error();
  if (Status s = apply_origin_lengths(**parsed, lengths); !s) return s.error();
  const urdf::ModelInterface& model = **parsed;
  auto base = model.getLink(std::string(base_link));
  if (!base) return config_error(fmt::format("URDF robot '{}' has no <link name=\"{}\"> (the base link)", model.getName(), base_link));
  LinkBodies out;
  // Breadth first from the base: every parent before its children.
  std::vector<std::pair<urdf::LinkConstSharedPtr, int>> queue{{base, -1}};
  for (std::size_t at = 0; at < queue.size(); ++at) {
    const auto [link, parent] = queue[at];
    LinkBody body;
    body.name = link->name;
    body.parent = parent;
    if (parent >= 0) {
      const urdf::Joint& j = *link->parent_joint;
      auto origin = urdf_pose(j.parent_to_joint_origin_transform, "joint '" + j.name + "'");
      if (!origin) return origin.error();
      body.origin = *origin;
      if (j.type != urdf::Joint::FIXED) {
        if (j.type != urdf::Joint::REVOLUTE && j.type != urdf::Joint::CONTINUOUS && j.type != urdf::Joint::PRISMATIC) {
          return config_error(fmt::format("URDF joint '{}': type not allowed below the base link (revolute, continuous, "
                                          "prismatic or fixed)", j.name));
        }
        const auto it = std::find(joint_names.begin(), joint_names.end(), j.name);
        if (it == joint_names.end()) {
          return config_error(fmt::format("URDF joint '{}' moves link '{}' but the arm names no joint '{}' "
                                          "(every moving joint below the base link must be one of the arm's joints)",
                                          j.name, link->name, j.name));
        }
        body.joint = static_cast<int>(it - joint_names.begin());
        body.prismatic = j.type == urdf::Joint::PRISMATIC;
        const Eigen::Vector3d axis(j.axis.x, j.axis.y, j.axis.z);
        if (!(axis.norm() > 1e-9) || !axis.allFinite()) {
          return config_error(fmt::format("URDF joint '{}': <axis> must be a non-zero vector", j.name));
        }
        body.axis = axis.normalized();
      }
    }
    for (std::size_t n = 0; n < link->collision_array.size(); ++n) {
      auto shape = collision_shape(*link->collision_array[n], link->name, n, capsules);
      if (!shape) return shape.error();
      body.shapes.push_back(*shape);
    }
    const int index = static_cast<int>(out.bodies.size());
    out.bodies.push_back(std::move(body));
    for (const auto& child : link->child_links) queue.emplace_back(child, index);
  }
  return out;
}

}  // namespace armctl::motion
