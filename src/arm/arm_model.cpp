#include "arm/arm_model.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include <fmt/core.h>
#include <urdf_model/model.h>
#include <urdf_parser/urdf_parser.h>

#include "arm/collision_shapes.hpp"
#include "arm/reduced_mode.hpp"
#include "core/arm_file_sections.hpp"
#include "core/config_files.hpp"
#include "core/json_reader.hpp"
#include "motion/urdf_chain.hpp"
#include "motion/urdf_model.hpp"
#include "motion/urdf_for_viewers.hpp"

namespace armctl::arm {

namespace {

using json_reader::json;
using json_reader::ObjectReader;

// A quantity written as a string with its unit ("30deg", "120mm/s").
double quantity(const ObjectReader& r, const json& v, const std::string& path, Dimension d, int power) {
  if (!v.is_string())
    r.fail(path, fmt::format("must be a string with a unit, e.g. \"{}\"",
                             d == Dimension::angle ? "30deg" : "120mm") + (power ? "/s" : ""));
  Result<double> q = parse_quantity(v.get<std::string>(), d, path, power);
  if (!q) r.fail(path, q.error().message.substr(path.size() + 2));
  return *q;
}

std::string name_of(const ObjectReader& r, const json& v, const std::string& path) {
  if (!v.is_string() || v.get<std::string>().empty()) r.fail(path, "must be a non-empty string");
  return v.get<std::string>();
}

JointLimits parse_limits(const std::string& source, const json& v, const std::string& path, Dimension d) {
  ObjectReader r(source, v, path);
  JointLimits l;
  const json& pos = r.require("position");
  if (!pos.is_array() || pos.size() != 2) r.fail(r.at("position"), "must be [lower, upper], e.g. [\"-90deg\", \"90deg\"]");
  l.lower = quantity(r, pos[0], r.at("position") + "[0]", d, 0);
  l.upper = quantity(r, pos[1], r.at("position") + "[1]", d, 0);
  if (l.lower >= l.upper)
    r.fail(r.at("position"), fmt::format("lower {} must be below upper {}", format_quantity(d, l.lower),
                                         format_quantity(d, l.upper)));
  const char* names[] = {"velocity", "acceleration", "jerk"};
  double* fields[] = {&l.velocity, &l.acceleration, &l.jerk};
  for (int k = 0; k < 3; ++k) {
    *fields[k] = quantity(r, r.require(names[k]), r.at(names[k]), d, k + 1);
    if (*fields[k] <= 0) r.fail(r.at(names[k]), "must be above zero");
  }
  r.finish();
  return l;
}

DeviceMap parse_map(const std::string& source, const json& v, const std::string& path, Dimension d,
                    const ProtocolInfo& p) {
  ObjectReader r(source, v, path);
  DeviceMap m;
  const DeviceRange range = p.range;
  m.id = static_cast<int>(r.integer(p.id_key, 1, p.max_id));
  const json& dev = r.require("device");
  if (!dev.is_array() || dev.size() != 2)
    r.fail(r.at("device"), fmt::format("must be two device positions [a, b] in {}..{}", range.min, range.max));
  m.device_a = r.number(dev[0], r.at("device") + "[0]", range.min, range.max);
  m.device_b = r.number(dev[1], r.at("device") + "[1]", range.min, range.max);
  const json& joint = r.require("joint");
  if (!joint.is_array() || joint.size() != 2)
    r.fail(r.at("joint"), "must be the two joint positions [a, b] that the device positions stand for");
  m.actuator_a = quantity(r, joint[0], r.at("joint") + "[0]", d, 0);
  m.actuator_b = quantity(r, joint[1], r.at("joint") + "[1]", d, 0);
  if (m.device_a == m.device_b) r.fail(r.at("device"), "the two device positions must differ");
  if (m.actuator_a == m.actuator_b) r.fail(r.at("joint"), "the two joint positions must differ");
  if (p.read_extras) p.read_extras(r, m);
  r.finish();
  return m;
}

const char* type_name(int urdf_type) {
  switch (urdf_type) {
    case urdf::Joint::REVOLUTE: return "revolute";
    case urdf::Joint::PRISMATIC: return "prismatic";
    case urdf::Joint::CONTINUOUS: return "continuous";
    case urdf::Joint::FIXED: return "fixed";
    case urdf::Joint::FLOATING: return "floating";
    case urdf::Joint::PLANAR: return "planar";
    default: return "unknown";
  }
}

bool same_name(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

// Throws ArmctlError(invalid_config) on the first problem.
ArmModel parse(std::string_view arm_json, const std::string& source, std::string_view urdf_text,
               const std::string& urdf_source) {
  const json doc = json_reader::parse_document(arm_json, source);
  ObjectReader r(source, doc, "");
  ArmModel m;
  m.name = name_of(r, r.require("name"), "name");
  const std::string family = name_of(r, r.require("family"), "family");
  auto found_family = find_arm_family(family);
  if (!found_family) r.fail("family", found_family.error().message);
  const ArmFamily& arm_family = **found_family;
  m.family = arm_family.name;
  m.rules = arm_family.rules;
  (void)name_of(r, r.require("urdf"), "urdf");  // read by the caller
  const std::string base = name_of(r, r.require("base_link"), "base_link");
  const std::string tip = name_of(r, r.require("tool_link"), "tool_link");

  // Calibrated lengths of URDF joint origins (docs/calibration.md), applied to the URDF
  // before anything is read from it: {"servo4": "98.2mm", ...}.
  if (const json* lengths = r.find("link_lengths")) {
    ObjectReader lr(source, *lengths, "link_lengths");
    for (auto it = lengths->begin(); it != lengths->end(); ++it) {
      if (it.key() == "comment") continue;
      const double length = quantity(lr, lr.require(it.key()), lr.at(it.key()), Dimension::length, 0);
      m.link_lengths.push_back(motion::OriginLength{it.key(), length});
    }
    lr.finish();
  }
  // The URDF: the chain from base to tool, and every joint the arm file names.
  Result<motion::UrdfChain> chain = motion::read_urdf_chain(urdf_text, base, tip);
  if (!chain) throw ArmctlError(ErrorKind::invalid_config, fmt::format("{}: {}", urdf_source, chain.error().message));
  // Through the guards every URDF reader shares (no '%' reaches urdfdom's logger).
  Result<urdf::ModelInterfaceSharedPtr> parsed_urdf = motion::parse_urdf_model(std::string(urdf_text));
  if (!parsed_urdf) throw ArmctlError(ErrorKind::invalid_config, fmt::format("{}: {}", urdf_source, parsed_urdf.error().message));
  // The lengths checked against this URDF (the error names the arm file's key), then the
  // chain read again with them.
  if (!m.link_lengths.empty()) {
    if (Status s = motion::apply_origin_lengths(**parsed_urdf, m.link_lengths); !s)
      r.fail("link_lengths", fmt::format("{} ({})", s.error().message, urdf_source));
    chain = motion::read_urdf_chain(urdf_text, base, tip, m.link_lengths);
    if (!chain) throw ArmctlError(ErrorKind::invalid_config, fmt::format("{}: {}", urdf_source, chain.error().message));
  }
  const urdf::ModelInterfaceSharedPtr& urdf_model = *parsed_urdf;
  m.tool_link = tip;

  std::string gripper_name;
  const json* gripper = r.find("gripper");
  if (gripper) {
    ObjectReader g(source, *gripper, "gripper");
    gripper_name = name_of(g, g.require("joint"), "gripper.joint");
  }

  const json& joints = r.require("joints");
  if (!joints.is_array() || joints.empty() || joints.size() > motion::kMaxChainJoints + 1u)
    r.fail("joints", fmt::format("must be an array of 1..{} joint objects", motion::kMaxChainJoints + 1));
  std::set<std::string> names;
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const std::string path = fmt::format("joints[{}]", i);
    ObjectReader jr(source, joints[i], path);
    JointModel jm;
    jm.name = name_of(jr, jr.require("name"), jr.at("name"));
    if (!names.insert(jm.name).second) jr.fail(jr.at("name"), fmt::format("joint '{}' appears twice", jm.name));
    urdf::JointConstSharedPtr uj = urdf_model->getJoint(jm.name);
    if (!uj)
      jr.fail(jr.at("name"), fmt::format("{} has no joint named '{}'", urdf_source, jm.name));
    if (uj->type == urdf::Joint::REVOLUTE) jm.dimension = Dimension::angle;
    else if (uj->type == urdf::Joint::PRISMATIC) jm.dimension = Dimension::length;
    else
      jr.fail(jr.at("name"), fmt::format("{}: joint '{}' is {}; armctl drives revolute and prismatic joints only",
                                         urdf_source, jm.name, type_name(uj->type)));
    jm.role = jm.name == gripper_name ? JointRole::gripper : JointRole::chain;
    jm.limits = parse_limits(source, jr.require("limits"), jr.at("limits"), jm.dimension);
    jm.urdf_lower = uj->limits ? uj->limits->lower : jm.limits.lower;
    jm.urdf_upper = uj->limits ? uj->limits->upper : jm.limits.upper;
    if (uj->limits && (jm.limits.lower < uj->limits->lower - 1e-9 || jm.limits.upper > uj->limits->upper + 1e-9))
      jr.fail(jr.at("limits.position"),
              fmt::format("{}..{} reaches beyond the URDF's limits {}..{} for joint '{}'",
                          format_quantity(jm.dimension, jm.limits.lower), format_quantity(jm.dimension, jm.limits.upper),
                          format_quantity(jm.dimension, uj->limits->lower),
                          format_quantity(jm.dimension, uj->limits->upper), jm.name));
    std::string known;
    for (Protocol p : protocols()) {
      const ProtocolInfo& info = protocol_info(p);
      known += (known.empty() ? "" : ", ") + info.name;
      if (const json* v = jr.find(info.name))
        jm.devices.emplace(info.name, parse_map(source, *v, jr.at(info.name), jm.dimension, info));
    }
    if (jm.devices.empty()) jr.fail(path, fmt::format("needs a device mapping: one or more of {}", known));
    jr.finish();
    m.joints.push_back(std::move(jm));
  }

  // The chain joints, in the order the URDF chain has them, then the gripper.
  std::vector<JointModel> ordered;
  for (const auto& cj : chain->joints) {
    auto it = std::find_if(m.joints.begin(), m.joints.end(), [&](const JointModel& j) { return j.name == cj.name; });
    if (it == m.joints.end())
      r.fail("joints", fmt::format("the URDF chain {} -> {} has joint '{}', which the arm file does not describe",
                                   base, tip, cj.name));
    if (it->role == JointRole::gripper)
      r.fail("gripper.joint", fmt::format("'{}' is a joint of the chain {} -> {}, not a gripper", cj.name, base, tip));
    ordered.push_back(*it);
  }
  for (const auto& j : m.joints) {
    if (j.role == JointRole::chain &&
        std::none_of(ordered.begin(), ordered.end(), [&](const JointModel& o) { return o.name == j.name; }))
      r.fail("joints", fmt::format("joint '{}' is not on the URDF chain {} -> {} (and is not the gripper)", j.name, base, tip));
  }
  if (gripper) {
    auto it = std::find_if(m.joints.begin(), m.joints.end(), [&](const JointModel& j) { return j.name == gripper_name; });
    if (it == m.joints.end()) r.fail("gripper.joint", fmt::format("no joint named '{}' in joints", gripper_name));
    ObjectReader g(source, *gripper, "gripper");
    (void)g.require("joint");
    GripperModel gm;
    gm.joint = static_cast<int>(ordered.size());
    gm.open = quantity(g, g.require("open"), "gripper.open", it->dimension, 0);
    gm.closed = quantity(g, g.require("closed"), "gripper.closed", it->dimension, 0);
    if (!it->limits.contains(gm.open) || !it->limits.contains(gm.closed))
      g.fail("gripper", "open and closed must lie inside the gripper joint's position limits");
    g.finish();
    ordered.push_back(*it);
    m.gripper = gm;
  }
  // Each protocol mapped for every joint, or for none: a protocol the arm supports must
  // reach all of its joints.
  for (Protocol p : protocols()) {
    const bool any = std::any_of(ordered.begin(), ordered.end(), [&](const JointModel& j) { return j.map(p) != nullptr; });
    std::set<int> ids;
    for (std::size_t i = 0; any && i < ordered.size(); ++i) {
      if (!ordered[i].map(p))
        r.fail("joints", fmt::format("joint '{}' has no {} mapping, but other joints do (map every joint or none)",
                                     ordered[i].name, to_string(p)));
      if (!ids.insert(ordered[i].map(p)->id).second)
        r.fail("joints", fmt::format("joint '{}': {} ID {} is used twice", ordered[i].name, to_string(p), ordered[i].map(p)->id));
    }
  }
  m.joints = std::move(ordered);

  if (const json* cs = r.find("couplings")) {
    if (!cs->is_array()) r.fail("couplings", "must be an array of {\"joints\": [A, B], \"matrix\": [[a, b], [c, d]]}");
    for (std::size_t i = 0; i < cs->size(); ++i) {
      const std::string path = fmt::format("couplings[{}]", i);
      ObjectReader c(source, (*cs)[i], path);
      const json& js = c.require("joints");
      if (!js.is_array() || js.size() != 2) c.fail(c.at("joints"), "must name two joints");
      Coupling k;
      int* idx[] = {&k.first, &k.second};
      for (int n = 0; n < 2; ++n) {
        const std::string jn = name_of(c, js[n], fmt::format("{}[{}]", c.at("joints"), n));
        auto found = m.find_joint(jn);
        if (!found) c.fail(c.at("joints"), fmt::format("no joint named '{}'", jn));
        *idx[n] = *found;
      }
      if (k.first == k.second) c.fail(c.at("joints"), "must name two different joints");
      for (const Coupling& other : m.couplings)
        for (int a : {other.first, other.second})
          if (a == k.first || a == k.second) c.fail(c.at("joints"), "a joint can be in one coupling only");
      const json& mx = c.require("matrix");
      if (!mx.is_array() || mx.size() != 2 || !mx[0].is_array() || mx[0].size() != 2 || !mx[1].is_array() ||
          mx[1].size() != 2)
        c.fail(c.at("matrix"), "must be a 2x2 matrix [[a, b], [c, d]]");
      for (int row = 0; row < 2; ++row)
        for (int col = 0; col < 2; ++col)
          k.matrix[row][col] = c.number(mx[row][col], fmt::format("{}[{}][{}]", c.at("matrix"), row, col), -100, 100);
      const double det = k.matrix[0][0] * k.matrix[1][1] - k.matrix[0][1] * k.matrix[1][0];
      if (std::abs(det) < 1e-9) c.fail(c.at("matrix"), "is singular: the two joints could not be told apart");
      c.finish();
      m.couplings.push_back(k);
    }
  }

  if (const json* tf = r.find("tool_frame")) {
    ObjectReader t(source, *tf, "tool_frame");
    Eigen::Vector3d xyz = Eigen::Vector3d::Zero();
    double rpy[3] = {0, 0, 0};
    if (const json* v = t.find("xyz")) {
      if (!v->is_array() || v->size() != 3) t.fail(t.at("xyz"), "must be [x, y, z] with units, e.g. [\"0mm\", \"0mm\", \"20mm\"]");
      for (int n = 0; n < 3; ++n) xyz[n] = quantity(t, (*v)[n], fmt::format("{}[{}]", t.at("xyz"), n), Dimension::length, 0);
    }
    if (const json* v = t.find("rpy")) {
      if (!v->is_array() || v->size() != 3) t.fail(t.at("rpy"), "must be [roll, pitch, yaw] with units, e.g. [\"0deg\", \"0deg\", \"0deg\"]");
      for (int n = 0; n < 3; ++n) rpy[n] = quantity(t, (*v)[n], fmt::format("{}[{}]", t.at("rpy"), n), Dimension::angle, 0);
    }
    t.finish();
    m.tool.position = xyz;
    m.tool.orientation = motion::from_rpy({rpy[0], rpy[1], rpy[2]});
  }
  // Link pairs allowed to touch (docs/scene.md): [{"links": [a, b], "why": "..."}].
  if (const json* collision = r.find("collision")) {
    ObjectReader c(source, *collision, "collision");
    const json& allowed = c.require("allowed");
    if (!allowed.is_array()) c.fail(c.at("allowed"), "must be an array of {\"links\": [link, link], \"why\": text}");
    for (std::size_t i = 0; i < allowed.size(); ++i) {
      ObjectReader a(source, allowed[i], fmt::format("collision.allowed[{}]", i));
      const json& links = a.require("links");
      if (!links.is_array() || links.size() != 2) a.fail(a.at("links"), "must be two link names of the URDF");
      std::string pair[2];
      for (std::size_t n = 0; n < 2; ++n) {
        pair[n] = name_of(a, links[n], fmt::format("{}[{}]", a.at("links"), n));
        if (!urdf_model->getLink(pair[n])) {
          a.fail(fmt::format("{}[{}]", a.at("links"), n), fmt::format("'{}' is not a link of {}", pair[n], urdf_source));
        }
      }
      const json& why = a.require("why");
      if (!why.is_string()) a.fail(a.at("why"), "must be text: why the pair may touch (adjacent, always touching)");
      a.finish();
      m.allowed_collisions.emplace_back(pair[0], pair[1]);
    }
    c.finish();
  }
  // The fence and reduced mode, as a scene file writes them (docs/scene.md "Fence and reduced
  // mode"): where the arm stands for good, its own file may carry them.
  if (const json* fence = r.find("fence")) m.fence = scene::read_fence(source, *fence, "fence");
  if (const json* reduced = r.find("reduced")) m.reduced = scene::read_reduced(source, *reduced, "reduced");
  // The sections of the boxes that run the arm, each read by its box (core/arm_file_sections.hpp).
  (void)r.find(std::string(arm_file::kSimulatorSection));
  (void)r.find(std::string(arm_file::kControllerSection));
  r.finish();

  std::vector<motion::PositionLimits> limits;
  for (const auto& j : m.joints)
    if (j.role == JointRole::chain) limits.push_back({j.limits.lower, j.limits.upper});
  m.reach = chain->tip_from_last.translation().norm() + m.tool.position.norm();
  for (std::size_t i = 0; i < chain->joints.size(); ++i) {
    const motion::ChainJoint& cj = chain->joints[i];
    m.reach += cj.from_previous.translation().norm();
    if (cj.type == motion::ChainJointType::prismatic)
      m.reach += std::max(std::abs(m.joints[i].limits.lower), std::abs(m.joints[i].limits.upper));
  }
  std::vector<std::string> joint_names;
  for (const auto& j : m.joints) joint_names.push_back(j.name);
  auto bodies = motion::read_link_bodies(urdf_text, base, joint_names, m.link_lengths);
  if (!bodies) throw ArmctlError(ErrorKind::invalid_config, fmt::format("{}: {}", urdf_source, bodies.error().message));
  m.bodies = std::make_shared<const motion::LinkBodies>(std::move(bodies).value());
  auto kin = arm_family.make(*chain, limits);
  if (!kin) throw ArmctlError(ErrorKind::invalid_config, fmt::format("{}: {}", urdf_source, kin.error().message));
  m.kinematics = std::shared_ptr<const motion::Kinematics>(std::move(kin.value()));
  m.chain = std::make_shared<const motion::UrdfChain>(std::move(chain).value());
  auto drawn = motion::urdf_for_viewers(urdf_text, m.link_lengths);
  if (!drawn) throw ArmctlError(ErrorKind::invalid_config, fmt::format("{}: {}", urdf_source, drawn.error().message));
  m.urdf_text = std::move(drawn).value();
  if ((m.fence || m.reduced) && !has_collision_shapes(m))
    throw ArmctlError(ErrorKind::invalid_config,
                      fmt::format("{}: {}: {} gives no link a <collision> shape, so it cannot be checked", source,
                                  m.fence ? "fence" : "reduced", urdf_source));
  if (m.reduced) {
    auto ranges = reduced_limits(m, *m.reduced);
    if (!ranges) throw ArmctlError(ranges.error().prefixed(source + ": "));
  }
  return m;
}

}  // namespace

Status within_reach(const ArmModel& model, const Eigen::Vector3d& position, std::string_view what) {
  if (!position.allFinite())
    return Error{ErrorKind::invalid_argument, fmt::format("{}: the position is not a finite number", what)};
  // The norm of a finite vector can overflow (1e200 squared): the largest coordinate
  // decides first, and it is the one named.
  Eigen::Index axis = 0;
  position.cwiseAbs().maxCoeff(&axis);
  const auto error = [&](std::string beyond) {
    return Error{ErrorKind::invalid_argument,
                 fmt::format("{}: {} is beyond reach: arm '{}' reaches at most {:.0f} mm from its base",
                             what, beyond, model.name, model.reach * 1e3)};
  };
  if (std::abs(position[axis]) > model.reach)
    return error(fmt::format("{} {:.6g} mm", "xyz"[axis], position[axis] * 1e3));
  if (position.norm() > model.reach)
    return error(fmt::format("the point (x {:.1f} y {:.1f} z {:.1f} mm), {:.0f} mm from the base,", position.x() * 1e3,
                             position.y() * 1e3, position.z() * 1e3, position.norm() * 1e3));
  return Ok{};
}

std::optional<int> ArmModel::find_joint(std::string_view joint_name) const {
  for (int i = 0; i < joint_count(); ++i)
    if (same_name(joints[static_cast<std::size_t>(i)].name, joint_name)) return i;
  return std::nullopt;
}

bool ArmModel::supports(Protocol p) const {
  return !joints.empty() && joints.front().map(p) != nullptr;
}

std::vector<double> ArmModel::to_device(Protocol p, const std::vector<double>& q) const {
  std::vector<double> actuator = q;
  for (const Coupling& c : couplings) {
    const double a = q[std::size_t(c.first)], b = q[std::size_t(c.second)];
    actuator[std::size_t(c.first)] = c.matrix[0][0] * a + c.matrix[0][1] * b;
    actuator[std::size_t(c.second)] = c.matrix[1][0] * a + c.matrix[1][1] * b;
  }
  std::vector<double> out(q.size());
  for (std::size_t i = 0; i < q.size(); ++i) out[i] = joints[i].map(p)->to_device(actuator[i]);
  return out;
}

std::vector<double> ArmModel::from_device(Protocol p, const std::vector<double>& device) const {
  std::vector<double> q(device.size());
  for (std::size_t i = 0; i < device.size(); ++i) q[i] = joints[i].map(p)->to_actuator(device[i]);
  for (const Coupling& c : couplings) {
    const double a = q[std::size_t(c.first)], b = q[std::size_t(c.second)];
    const double det = c.matrix[0][0] * c.matrix[1][1] - c.matrix[0][1] * c.matrix[1][0];
    q[std::size_t(c.first)] = (c.matrix[1][1] * a - c.matrix[0][1] * b) / det;
    q[std::size_t(c.second)] = (-c.matrix[1][0] * a + c.matrix[0][0] * b) / det;
  }
  return q;
}

Result<ArmModel> parse_arm_model(std::string_view arm_json, std::string_view source, std::string_view urdf_text,
                                 std::string_view urdf_source) {
  try {
    return parse(arm_json, std::string(source), urdf_text, std::string(urdf_source));
  } catch (const ArmctlError& e) {
    return e.error();
  }
}

Result<ArmModel> load_arm_model(const std::filesystem::path& arm_file) {
  try {
    const std::string text = json_reader::read_config_file(arm_file, "arm file");
    // The URDF's name, read before the full parse so the URDF can be found beside the file.
    std::string urdf_name;
    try {
      json doc = json::parse(text);
      if (doc.is_object() && doc.contains("urdf") && doc["urdf"].is_string()) urdf_name = doc["urdf"].get<std::string>();
    } catch (const json::exception&) {
    }
    if (urdf_name.empty()) return parse_arm_model(text, arm_file.string(), "", "(no urdf)");
    std::filesystem::path urdf_path = urdf_name;
    if (urdf_path.is_relative()) urdf_path = arm_file.parent_path() / urdf_path;
    const std::string urdf = json_reader::read_config_file(urdf_path, "URDF");
    Result<ArmModel> m = parse_arm_model(text, arm_file.string(), urdf, urdf_path.string());
    if (!m) return m;
    ArmModel model = std::move(m.value());
    model.file = arm_file;
    model.urdf = urdf_path;
    return model;
  } catch (const ArmctlError& e) {
    return e.error();
  }
}

std::filesystem::path arm_file_path(std::string_view arm) {
  if (arm == "xarm" || arm == "scara") return find_config_file(std::string(arm) + ".arm.json");
  return std::filesystem::path(arm);
}

bool has_collision_shapes(const ArmModel& model) {
  if (!model.bodies) return false;
  const auto& b = model.bodies->bodies;
  return std::any_of(b.begin(), b.end(), [](const motion::LinkBody& body) { return !body.shapes.empty(); });
}

}  // namespace armctl::arm
