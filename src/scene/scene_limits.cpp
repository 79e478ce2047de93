#include "scene/scene_limits.hpp"

#include <set>

#include <fmt/format.h>

#include "core/json_reader.hpp"

namespace armctl::scene {

using json_reader::json;
using json_reader::ObjectReader;

namespace {

constexpr double kMmPerM = 1000;
// As far as a scene's objects may be placed (scene.cpp): any bench an arm of ours stands on.
constexpr double kMaxCoordinateMm = 10000;
// A tool speed cap from 1 mm/s (a careful approach) to 2 m/s (beyond both arms' reach per second).
constexpr double kMinToolSpeedMm = 1, kMaxToolSpeedMm = 2000;
// Joint values as files give them: degrees within a few turns, millimetres within reach.
constexpr double kMaxJointValue = 10000;
constexpr std::size_t kMaxRanges = 32;

bool boolean(ObjectReader& r, const std::string& key, bool otherwise) {
  const json* v = r.find(key);
  if (!v) return otherwise;
  if (!v->is_boolean()) r.fail(r.at(key), fmt::format("{}: must be true or false", v->dump()));
  return v->get<bool>();
}

Eigen::Vector3d corner(ObjectReader& r, const std::string& key) {
  const json& v = r.require(key);
  const std::string path = r.at(key);
  if (!v.is_array() || v.size() != 3)
    r.fail(path, fmt::format("must be an array of 3 numbers in {0}..{1} (mm)", -kMaxCoordinateMm, kMaxCoordinateMm));
  Eigen::Vector3d out;
  for (std::size_t i = 0; i < 3; ++i)
    out[Eigen::Index(i)] = r.number(v[i], fmt::format("{}[{}]", path, i), -kMaxCoordinateMm, kMaxCoordinateMm) / kMmPerM;
  return out;
}

}  // namespace

Fence read_fence(const std::string& source, const json& v, const std::string& at) {
  ObjectReader r(source, v, at);
  Fence f;
  f.low = corner(r, "min");
  f.high = corner(r, "max");
  for (int i = 0; i < 3; ++i)
    if (!(f.low[i] < f.high[i]))
      r.fail(r.at("max"), fmt::format("{} {:g} mm is not above min's {:g} mm: the box must have a size", "xyz"[i],
                                      f.high[i] * kMmPerM, f.low[i] * kMmPerM));
  f.links = boolean(r, "links", false);
  f.on = boolean(r, "on", true);
  r.finish();
  return f;
}

ReducedMode read_reduced(const std::string& source, const json& v, const std::string& at) {
  ObjectReader r(source, v, at);
  ReducedMode m;
  if (const json* speed = r.find("tool_speed"))
    m.tool_speed = r.number(*speed, r.at("tool_speed"), kMinToolSpeedMm, kMaxToolSpeedMm) / kMmPerM;
  if (const json* joints = r.find("joints")) {
    const std::string path = r.at("joints");
    if (!joints->is_object() || joints->size() > kMaxRanges)
      r.fail(path, fmt::format("must be an object of at most {} joints, each \"name\": [lower, upper] (deg, or mm for a "
                               "prismatic joint)",
                               kMaxRanges));
    for (const auto& [name, range] : joints->items()) {
      const std::string key = path + "." + name;
      if (!range.is_array() || range.size() != 2)
        r.fail(key, "must be [lower, upper] (deg, or mm for a prismatic joint)");
      ReducedJointRange j{name, r.number(range[0], key + "[0]", -kMaxJointValue, kMaxJointValue),
                          r.number(range[1], key + "[1]", -kMaxJointValue, kMaxJointValue)};
      if (!(j.lower < j.upper)) r.fail(key, fmt::format("[{:g}, {:g}]: lower must be below upper", j.lower, j.upper));
      m.joints.push_back(std::move(j));
    }
  }
  if (!m.tool_speed && m.joints.empty())
    r.fail(at, "sets nothing: give tool_speed (mm/s) or joints ({\"name\": [lower, upper]}), or both");
  m.on = boolean(r, "on", true);
  r.finish();
  return m;
}

json fence_json(const Fence& f) {
  auto mm = [](const Eigen::Vector3d& p) { return json::array({p.x() * kMmPerM, p.y() * kMmPerM, p.z() * kMmPerM}); };
  return json{{"min", mm(f.low)}, {"max", mm(f.high)}, {"links", f.links}, {"on", f.on}};
}

json reduced_json(const ReducedMode& m) {
  json out{{"on", m.on}};
  if (m.tool_speed) out["tool_speed"] = *m.tool_speed * kMmPerM;
  if (!m.joints.empty()) {
    json joints = json::object();
    for (const auto& j : m.joints) joints[j.joint] = json::array({j.lower, j.upper});
    out["joints"] = std::move(joints);
  }
  return out;
}

}  // namespace armctl::scene
