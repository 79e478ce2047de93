#include "motion/urdf_chain.hpp"
#include "motion/urdf_model.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <mutex>
#include <sstream>

#include <console_bridge/console.h>
#include <fmt/format.h>
#include <urdf_parser/urdf_parser.h>

#include "core/printable.hpp"
#include "core/regular_file.hpp"

namespace armctl::motion {

const char* to_string(ChainJointType type) {
  return type == ChainJointType::revolute ? "revolute" : "prismatic";
}

namespace {

Error config_error(std::string message) { return Error{ErrorKind::invalid_config, std::move(message)}; }

// urdfdom reports why it refused a document only through console_bridge's log. Collect
// those lines during one parse so that our error can say what urdfdom said, instead of
// letting them go to stderr. console_bridge's handler is process-wide: one parse at a time.
class CollectingHandler : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR && lines_.size() < 4) lines_.push_back(text);
  }
  std::string joined() const {
    std::string out;
    for (const auto& l : lines_) out += (out.empty() ? "" : "; ") + l;
    return out;
  }

 private:
  std::vector<std::string> lines_;
};

std::mutex& parse_mutex() {
  static std::mutex m;
  return m;
}

// Where `text` stops being well-formed UTF-8 (or holds a NUL byte); npos when it does not.
// urdfdom's XML parser (TinyXML 2.6) trusts UTF-8 lead bytes and reads past the end of a
// text whose last character is cut short, so such text never reaches it.
std::size_t bad_utf8_at(std::string_view text) {
  std::size_t i = 0;
  while (i < text.size()) {
    const auto b = static_cast<unsigned char>(text[i]);
    if (b == 0) return i;
    if (b < 0x80) {
      ++i;
      continue;
    }
    std::size_t n = 0;
    std::uint32_t cp = 0;
    if ((b & 0xE0) == 0xC0) n = 1, cp = b & 0x1F;
    else if ((b & 0xF0) == 0xE0) n = 2, cp = b & 0x0F;
    else if ((b & 0xF8) == 0xF0) n = 3, cp = b & 0x07;
    else return i;
    if (i + n >= text.size()) return i;  // cut short
    for (std::size_t k = 1; k <= n; ++k) {
      const auto c = static_cast<unsigned char>(text[i + k]);
      if ((c & 0xC0) != 0x80) return i;
      cp = (cp << 6) | (c & 0x3F);
    }
    const std::uint32_t min[] = {0, 0x80, 0x800, 0x10000};
    if (cp < min[n] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return i;
    i += n + 1;
  }
  return std::string_view::npos;
}

// Where `text` holds a '%' outside an XML comment; npos when it does not. urdfdom passes some
// attribute text (a number it cannot read, such as rpy="0 1%n 0") to its logger as the printf
// format itself, so a '%' there makes it write through a pointer it never had: found by
// fuzz_urdf_chain. No URDF needs one (numbers, names and file names), so none reaches it;
// comments are the one place people write "50 %", and urdfdom never logs them.
// The comments are found by this simple scan, which a malformed file can make disagree with
// the XML parser's reading (fuzz_urdf_chain found `type=<ro<!-->` do so): so the '%' signs it
// takes to be in comments are also blanked in what urdfdom is given (without_percent_signs).
std::size_t percent_at(std::string_view text) {
  std::size_t i = 0;
  while (i < text.size()) {
    if (text.compare(i, 4, "<!--") == 0) {
      const std::size_t end = text.find("-->", i + 4);
      if (end == std::string_view::npos) return std::string_view::npos;  // XML's own error follows
      i = end + 3;
      continue;
    }
    if (text[i] == '%') return i;
    ++i;
  }
  return std::string_view::npos;
}

// `text` with every '%' made a space (the same length: line and column numbers stay true), so
// that urdfdom never sees one, whatever it takes for a comment.
std::string without_percent_signs(std::string text) {
  std::replace(text.begin(), text.end(), '%', ' ');
  return text;
}

// "line L, column C" of byte `at` (1-based), for messages.
std::string line_column(std::string_view text, std::size_t at) {
  const std::size_t line_start = text.rfind('\n', at == 0 ? 0 : at - 1);
  const std::size_t line = 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + at, '\n'));
  const std::size_t column = at - (line_start == std::string_view::npos || at == 0 ? 0 : line_start + 1) + 1;
  return fmt::format("line {}, column {}", line, column);
}

}  // namespace

Result<urdf::ModelInterfaceSharedPtr> parse_urdf_model(const std::string& xml, std::vector<UrdfCapsule>* capsules) {
  if (const auto at = bad_utf8_at(xml); at != std::string_view::npos) {
    return config_error(fmt::format("URDF not accepted: byte {} is not UTF-8 text (a URDF is XML, UTF-8 encoded)", at));
  }
  if (const auto at = percent_at(xml); at != std::string_view::npos) {
    return config_error(fmt::format("URDF not accepted: a '%' at {}; allowed only inside <!-- comments --> "
                                    "(URDF values are numbers, names and file names)",
                                    line_column(xml, at)));
  }
  // Checked UTF-8 above: TinyXML may read it.
  auto plain = without_capsules(xml);
  if (!plain) return plain.error();
  if (capsules) *capsules = std::move(plain->capsules);
  std::lock_guard lock(parse_mutex());
  CollectingHandler handler;
  console_bridge::useOutputHandler(&handler);
  urdf::ModelInterfaceSharedPtr model;
  std::string exception_text;
  try {
    model = urdf::parseURDF(without_percent_signs(plain->xml));
  } catch (const std::exception& e) {
    exception_text = e.what();
  }
  console_bridge::restorePreviousOutputHandler();
  if (!model) {
    std::string why = exception_text.empty() ? handler.joined() : exception_text;
    if (why.empty()) why = "not a URDF <robot> document";
    return config_error(fmt::format("URDF not accepted: {}", why));
  }
  return model;
}

namespace {
bool finite(const urdf::Vector3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
}  // namespace

Result<Eigen::Isometry3d> urdf_pose(const urdf::Pose& pose, const std::string& what) {
  const auto& p = pose.position;
  const auto& r = pose.rotation;
  if (!finite(p) || !std::isfinite(r.x) || !std::isfinite(r.y) || !std::isfinite(r.z) || !std::isfinite(r.w)) {
    return config_error(fmt::format("URDF {}: <origin> xyz and rpy must be finite numbers", what));
  }
  Eigen::Quaterniond q(r.w, r.x, r.y, r.z);
  if (q.norm() < 0.5) {
    return config_error(fmt::format("URDF {}: <origin> rotation is not a rotation", what));
  }
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = q.normalized().toRotationMatrix();
  t.translation() = Eigen::Vector3d(p.x, p.y, p.z);
  return t;
}

namespace {

const char* urdf_type_name(int type) {
  switch (type) {
    case urdf::Joint::REVOLUTE: return "revolute";
    case urdf::Joint::CONTINUOUS: return "continuous";
    case urdf::Joint::PRISMATIC: return "prismatic";
    case urdf::Joint::FLOATING: return "floating";
    case urdf::Joint::PLANAR: return "planar";
    case urdf::Joint::FIXED: return "fixed";
    default: return "unknown";
  }
}

Result<ChainJoint> moving_joint(const urdf::Joint& j) {
  ChainJoint out;
  out.name = j.name;
  out.type = j.type == urdf::Joint::REVOLUTE ? ChainJointType::revolute : ChainJointType::prismatic;
  const auto& p = j.parent_to_joint_origin_transform;
  out.origin_xyz = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  double roll = 0, pitch = 0, yaw = 0;
  p.rotation.getRPY(roll, pitch, yaw);
  out.origin_rpy = Eigen::Vector3d(roll, pitch, yaw);
  if (!finite(j.axis)) {
    return config_error(fmt::format("URDF joint '{}': <axis> xyz must be finite numbers", j.name));
  }
  const Eigen::Vector3d axis(j.axis.x, j.axis.y, j.axis.z);
  if (axis.norm() < 1e-9) {
    return config_error(fmt::format("URDF joint '{}': <axis> xyz is zero; it must be a direction", j.name));
  }
  out.axis = axis.normalized();
  if (!j.limits) {
    return config_error(fmt::format("URDF joint '{}': a {} joint needs a <limit> element", j.name,
                                    urdf_type_name(j.type)));
  }
  const auto& l = *j.limits;
  if (!std::isfinite(l.lower) || !std::isfinite(l.upper) || !(l.lower < l.upper)) {
    return config_error(fmt::format(
        "URDF joint '{}': <limit> lower {} and upper {} must be finite numbers with lower < upper", j.name,
        l.lower, l.upper));
  }
  if (out.type == ChainJointType::revolute && (l.lower < -100 || l.upper > 100)) {
    return config_error(fmt::format("URDF joint '{}': <limit> lower and upper must lie within -100..100 rad",
                                    j.name));
  }
  if (out.type == ChainJointType::prismatic && (l.lower < -100 || l.upper > 100)) {
    return config_error(fmt::format("URDF joint '{}': <limit> lower and upper must lie within -100..100 m",
                                    j.name));
  }
  if (!std::isfinite(l.velocity) || l.velocity < 0 || !std::isfinite(l.effort) || l.effort < 0) {
    return config_error(fmt::format("URDF joint '{}': <limit> velocity and effort must be finite and >= 0",
                                    j.name));
  }
  out.limits = UrdfJointLimits{l.lower, l.upper, l.velocity, l.effort};
  return out;
}

}  // namespace

Status apply_origin_lengths(urdf::ModelInterface& model, std::span<const OriginLength> lengths) {
  for (std::size_t i = 0; i < lengths.size(); ++i) {
    const OriginLength& l = lengths[i];
    for (std::size_t k = 0; k < i; ++k)
      if (lengths[k].joint == l.joint) return config_error(fmt::format("link length of joint '{}' given twice", l.joint));
    auto it = model.joints_.find(l.joint);
    if (it == model.joints_.end() || !it->second)
      return config_error(fmt::format("link length for joint '{}': the URDF robot '{}' has no such joint", l.joint,
                                      model.getName()));
    if (!std::isfinite(l.length) || !(l.length > 0) || l.length > 100)
      return config_error(fmt::format("link length for joint '{}': {} m; allowed is a length above 0 and at most 100 m",
                                      l.joint, l.length));
    urdf::Vector3& p = it->second->parent_to_joint_origin_transform.position;
    const double now = std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
    // Below a micrometre the URDF gives no direction to keep.
    if (!(now > 1e-6))
      return config_error(fmt::format("link length for joint '{}': its <origin> has no offset, so no direction to "
                                      "lengthen along; only joints with an offset xyz have a link length",
                                      l.joint));
    const double scale = l.length / now;
    p.x *= scale;
    p.y *= scale;
    p.z *= scale;
  }
  return Ok{};
}

Result<UrdfChain> read_urdf_chain(std::string_view urdf_xml, std::string_view base_link,
                                  std::string_view tip_link, std::span<const OriginLength> lengths) {
  auto parsed = parse_urdf_model(std::string(urdf_xml));
  if (!parsed) return parsed.error();
  if (Status s = apply_origin_lengths(**parsed, lengths); !s) return s.error();
  const urdf::ModelInterface& model = **parsed;
  const std::string base(base_link), tip(tip_link);
  if (!model.getLink(base)) {
    return config_error(fmt::format("URDF robot '{}' has no <link name=\"{}\"> (the chain's base link)",
                                    model.getName(), base));
  }
  if (!model.getLink(tip)) {
    return config_error(fmt::format("URDF robot '{}' has no <link name=\"{}\"> (the chain's tip link)",
                                    model.getName(), tip));
  }
  // Walk up from the tip to the base; the tree guarantees one parent per link.
  std::vector<urdf::JointConstSharedPtr> path;
  for (auto link = model.getLink(tip); link->name != base;) {
    const auto joint = link->parent_joint;
    if (!joint) {
      return config_error(
          fmt::format("URDF link '{}' is not below link '{}': the chain must lead from base to tip", tip, base));
    }
    path.push_back(joint);
    link = model.getLink(joint->parent_link_name);
    if (!link) return config_error(fmt::format("URDF joint '{}' has no parent link", joint->name));
    if (path.size() > 1000) return config_error("URDF tree deeper than 1000 joints");
  }
  UrdfChain chain;
  chain.robot_name = model.getName();
  chain.base_link = base;
  chain.tip_link = tip;
  Eigen::Isometry3d pending = Eigen::Isometry3d::Identity();
  for (auto it = path.rbegin(); it != path.rend(); ++it) {
    const urdf::Joint& j = **it;
    // urdfdom accepts name="" (found by fuzz_urdf_chain): a joint nobody can name cannot be
    // mapped to a device or reported in an error.
    if (j.name.empty())
      return config_error(fmt::format("URDF joint between links '{}' and '{}' has an empty name; every <joint> "
                                      "on the chain needs a name",
                                      j.parent_link_name, j.child_link_name));
    auto origin = urdf_pose(j.parent_to_joint_origin_transform, "joint '" + j.name + "'");
    if (!origin) return origin.error();
    if (j.type == urdf::Joint::FIXED) {
      pending = pending * *origin;
      chain.fixed_joints.push_back(j.name);
      chain.fixed.push_back(FixedChainJoint{j.name, *origin, chain.joints.size()});
      continue;
    }
    if (j.type != urdf::Joint::REVOLUTE && j.type != urdf::Joint::PRISMATIC) {
      return config_error(fmt::format(
          "URDF joint '{}' is {}; a chain joint must be revolute (with limits), prismatic or fixed", j.name,
          urdf_type_name(j.type)));
    }
    if (j.mimic) {
      return config_error(fmt::format("URDF joint '{}' has <mimic>; a chain joint must move on its own", j.name));
    }
    auto parsed_joint = moving_joint(j);
    if (!parsed_joint) return parsed_joint.error();
    ChainJoint joint = std::move(parsed_joint).value();
    joint.from_previous = pending * *origin;
    pending = Eigen::Isometry3d::Identity();
    chain.joints.push_back(std::move(joint));
  }
  chain.tip_from_last = pending;
  return chain;
}

Result<UrdfChain> read_urdf_chain_file(const std::string& path, std::string_view base_link,
                                       std::string_view tip_link) {
  // A directory or FIFO is refused at once; URDF files of these arms are a few kB (meshes are
  // separate files), so 4 MiB is far above any real one.
  constexpr std::uintmax_t kMaxUrdfBytes = 4 << 20;
  auto text = read_regular_file(path, "URDF file", kMaxUrdfBytes);
  if (!text) return text.error();
  auto chain = read_urdf_chain(*text, base_link, tip_link);
  if (!chain) return Error{chain.error().kind, fmt::format("{}: {}", printable(path), chain.error().message)};
  return chain;
}

}  // namespace armctl::motion
