#include "scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/json_reader.hpp"
#include "core/printable.hpp"

namespace armctl::scene {

using json_reader::json;
using json_reader::ObjectReader;

const char* to_string(ObjectRole role) {
  switch (role) {
    case ObjectRole::obstacle: return "obstacle";
    case ObjectRole::table: return "table";
    case ObjectRole::keep_out: return "keep-out zone";
  }
  return "?";
}

std::string describe(const SceneObject& o) {
  switch (o.role) {
    case ObjectRole::table: return fmt::format("the table '{}'", o.name);
    case ObjectRole::keep_out: return fmt::format("keep-out zone '{}'", o.name);
    case ObjectRole::obstacle: break;
  }
  return fmt::format("{}{} '{}'", o.attached ? "held " : "", motion::to_string(o.shape.kind), o.name);
}

namespace {

// Far enough for any bench an arm of ours stands on; sizes from a tenth of a millimetre.
constexpr double kMaxCoordinateMm = 10000, kMinSizeMm = 0.1, kMaxSizeMm = 10000;
constexpr std::size_t kMaxObjects = 200, kMaxNameLength = 40;
// A table is a slab this thick under its top, as wide as asked (by default 2 m square).
constexpr double kTableThicknessMm = 50, kDefaultTableSizeMm = 2000;
constexpr double kMmPerM = 1000;
constexpr double kRadPerDeg = std::numbers::pi / 180;

bool name_allowed(const std::string& name) {
  if (name.empty() || name.size() > kMaxNameLength) return false;
  for (char c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' || c == '.';
    if (!ok) return false;
  }
  return true;
}

// [x, y, z] (or [x, y]) in `min`..`max` millimetres, as metres.
Eigen::Vector3d mm_vector(ObjectReader& r, const json& v, const std::string& path, std::size_t n, double min, double max) {
  if (!v.is_array() || v.size() != n) {
    r.fail(path, fmt::format("must be an array of {} numbers in {}..{} (mm)", n, min, max));
  }
  Eigen::Vector3d out = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i) out[Eigen::Index(i)] = r.number(v[i], fmt::format("{}[{}]", path, i), min, max) / kMmPerM;
  return out;
}

motion::Shape read_shape(const std::string& src, ObjectReader& r, ObjectRole& role) {
  const char* kinds =
      "exactly one of box: [x, y, z], cylinder: {radius, length}, capsule: {radius, length}, sphere: {radius}, table: "
      "{top, size, center} (mm)";
  const json* box = r.find("box");
  const json* cylinder = r.find("cylinder");
  const json* capsule = r.find("capsule");
  const json* sphere = r.find("sphere");
  const json* table = r.find("table");
  const int given = (box != nullptr) + (cylinder != nullptr) + (capsule != nullptr) + (sphere != nullptr) + (table != nullptr);
  if (given != 1) r.fail(r.at("box"), fmt::format("{} shapes given; wants {}", given, kinds));
  motion::Shape s;
  if (box != nullptr) {
    s.kind = motion::Shape::Kind::box;
    s.size = mm_vector(r, *box, r.at("box"), 3, kMinSizeMm, kMaxSizeMm);
  } else if (cylinder != nullptr || capsule != nullptr) {
    // A capsule's length is its straight part's, between the centres of its half spheres.
    const char* key = cylinder != nullptr ? "cylinder" : "capsule";
    ObjectReader c(src, cylinder != nullptr ? *cylinder : *capsule, r.at(key));
    s.kind = cylinder != nullptr ? motion::Shape::Kind::cylinder : motion::Shape::Kind::capsule;
    s.size = {c.number("radius", kMinSizeMm, kMaxSizeMm) / kMmPerM, c.number("length", kMinSizeMm, kMaxSizeMm) / kMmPerM, 0};
    c.finish();
  } else if (sphere != nullptr) {
    ObjectReader c(src, *sphere, r.at("sphere"));
    s.kind = motion::Shape::Kind::sphere;
    s.size = {c.number("radius", kMinSizeMm, kMaxSizeMm) / kMmPerM, 0, 0};
    c.finish();
  } else {
    role = ObjectRole::table;
    ObjectReader t(src, *table, r.at("table"));
    const json* top = t.find("top");
    const double z = top ? t.number(*top, t.at("top"), -kMaxCoordinateMm, kMaxCoordinateMm) / kMmPerM : 0.0;
    const json* size = t.find("size");
    const Eigen::Vector3d xy = size ? mm_vector(r, *size, t.at("size"), 2, kMinSizeMm, kMaxSizeMm)
                                    : Eigen::Vector3d(kDefaultTableSizeMm, kDefaultTableSizeMm, 0) / kMmPerM;
    const json* center = t.find("center");
    const Eigen::Vector3d c = center ? mm_vector(r, *center, t.at("center"), 2, -kMaxCoordinateMm, kMaxCoordinateMm)
                                     : Eigen::Vector3d::Zero();
    t.finish();
    s.kind = motion::Shape::Kind::box;
    s.size = {xy.x(), xy.y(), kTableThicknessMm / kMmPerM};
    s.pose.translation() = Eigen::Vector3d(c.x(), c.y(), z - 0.5 * kTableThicknessMm / kMmPerM);
  }
  return s;
}

}  // namespace

// One object of a scene file at `path` ("objects[3]"); throws ArmctlError naming the key.
SceneObject read_object(const std::string& src, const json& v, const std::string& path) {
  ObjectReader r(src, v, path);
  SceneObject o;
  const json& name = r.require("name");
  if (!name.is_string() || !name_allowed(name.get<std::string>())) {
    r.fail(r.at("name"), fmt::format("{}: wants 1..{} of the letters a-z A-Z, digits, '_', '-', '.'",
                                     printable(name.dump()), kMaxNameLength));
  }
  o.name = name.get<std::string>();
  o.shape = read_shape(src, r, o.role);
  if (const json* at = r.find("at")) {
    if (o.role == ObjectRole::table) r.fail(r.at("at"), "a table is placed by its top, size and center, not at");
    o.shape.pose.translation() = mm_vector(r, *at, r.at("at"), 3, -kMaxCoordinateMm, kMaxCoordinateMm);
  } else if (o.role != ObjectRole::table) {
    r.fail(r.at("at"), "missing: where the object's centre is, [x, y, z] mm in the base frame (the tool frame when attached)");
  }
  if (const json* rpy = r.find("rpy")) {
    if (!rpy->is_array() || rpy->size() != 3) r.fail(r.at("rpy"), "must be an array of 3 numbers in -360..360 (deg)");
    double a[3];
    for (std::size_t k = 0; k < 3; ++k) a[k] = r.number((*rpy)[k], fmt::format("{}[{}]", r.at("rpy"), k), -360, 360) * kRadPerDeg;
    o.shape.pose.linear() = (Eigen::AngleAxisd(a[2], Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(a[1], Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(a[0], Eigen::Vector3d::UnitX())).toRotationMatrix();
  }
  if (const json* keep_out = r.find("keep_out")) {
    if (!keep_out->is_boolean()) r.fail(r.at("keep_out"), "must be true or false");
    if (keep_out->get<bool>()) {
      if (o.role == ObjectRole::table) r.fail(r.at("keep_out"), "a table is not a keep-out zone");
      o.role = ObjectRole::keep_out;
    }
  }
  if (const json* attached = r.find("attached")) {
    if (!attached->is_string() || attached->get<std::string>() != "tool") {
      r.fail(r.at("attached"), fmt::format("{}: the only place a part can be held is \"tool\"", printable(attached->dump())));
    }
    if (o.role != ObjectRole::obstacle) r.fail(r.at("attached"), "only a box, cylinder, capsule or sphere can be held by the tool");
    o.attached = true;
  }
  r.finish();
  return o;
}

Result<Scene> parse_scene(std::string_view json_text, std::string_view source) {
  return catch_error([&]() -> Result<Scene> {
    const std::string src(source);
    const json doc = json_reader::parse_document(json_text, src);
    ObjectReader top(src, doc, "");
    Scene scene;
    if (const json* fence = top.find("fence")) scene.fence = read_fence(src, *fence, "fence");
    if (const json* reduced = top.find("reduced")) scene.reduced = read_reduced(src, *reduced, "reduced");
    // A scene of limits alone needs no objects.
    static const json kNone = json::array();
    const json* given = top.find("objects");
    if (!given && !scene.fence && !scene.reduced) top.require("objects");  // refused: missing
    const json& objects = given ? *given : kNone;
    if (!objects.is_array()) top.fail("objects", "must be an array of objects (each: name, a shape, at, rpy, keep_out, attached)");
    if (objects.size() > kMaxObjects) top.fail("objects", fmt::format("{} objects; at most {}", objects.size(), kMaxObjects));
    std::set<std::string> names;
    for (std::size_t i = 0; i < objects.size(); ++i) {
      SceneObject o = read_object(src, objects[i], fmt::format("objects[{}]", i));
      if (!names.insert(o.name).second)
        top.fail(fmt::format("objects[{}].name", i), fmt::format("'{}' names two objects; names must differ", o.name));
      scene.objects.push_back(std::move(o));
    }
    top.finish();
    return scene;
  });
}

Result<Scene> load_scene(const std::filesystem::path& file) {
  return catch_error([&]() -> Result<Scene> {
    const std::string text = json_reader::read_config_file(file, "scene file");
    Scene scene = parse_scene(text, file.string()).value();
    scene.file = file;
    return scene;
  });
}

std::string scene_json(const Scene& scene) {
  json objects = json::array();
  auto mm = [](const Eigen::Vector3d& v, int n) {
    json a = json::array();
    for (int i = 0; i < n; ++i) a.push_back(v[i] * kMmPerM);
    return a;
  };
  for (const auto& o : scene.objects) {
    json j{{"name", o.name}};
    const Eigen::Isometry3d& p = o.shape.pose;
    if (o.role == ObjectRole::table) {
      j["table"] = {{"top", (p.translation().z() + 0.5 * o.shape.size.z()) * kMmPerM},
                    {"size", mm(o.shape.size, 2)},
                    {"center", mm(p.translation(), 2)}};
    } else {
      switch (o.shape.kind) {
        case motion::Shape::Kind::box: j["box"] = mm(o.shape.size, 3); break;
        case motion::Shape::Kind::cylinder:
        case motion::Shape::Kind::capsule:
          j[motion::to_string(o.shape.kind)] = {{"radius", o.shape.size.x() * kMmPerM}, {"length", o.shape.size.y() * kMmPerM}};
          break;
        case motion::Shape::Kind::sphere: j["sphere"] = {{"radius", o.shape.size.x() * kMmPerM}}; break;
      }
      j["at"] = mm(p.translation(), 3);
      // Z-Y-X angles, as read: yaw, pitch, roll.
      const Eigen::Vector3d ypr = p.linear().eulerAngles(2, 1, 0) / kRadPerDeg;
      j["rpy"] = {ypr[2], ypr[1], ypr[0]};
      if (o.role == ObjectRole::keep_out) j["keep_out"] = true;
      if (o.attached) j["attached"] = "tool";
    }
    objects.push_back(std::move(j));
  }
  json out{{"objects", std::move(objects)}};
  if (scene.fence) out["fence"] = fence_json(*scene.fence);
  if (scene.reduced) out["reduced"] = reduced_json(*scene.reduced);
  return out.dump(2) + "\n";
}

Result<Scene> with_object(const Scene& scene, std::string_view object_json, std::string_view source) {
  return catch_error([&]() -> Result<Scene> {
    const std::string src(source);
    const json doc = json_reader::parse_document(object_json, src);
    SceneObject o = read_object(src, doc, "");
    Scene out = scene;
    auto same = std::find_if(out.objects.begin(), out.objects.end(), [&](const SceneObject& s) { return s.name == o.name; });
    if (same != out.objects.end()) {
      *same = std::move(o);
    } else {
      if (out.objects.size() >= kMaxObjects)
        throw ArmctlError(ErrorKind::invalid_argument,
                          fmt::format("{}: the scene holds {} objects already, the most it may; remove one first", src, kMaxObjects));
      out.objects.push_back(std::move(o));
    }
    return out;
  });
}

Result<Scene> with_fence(const Scene& scene, bool on) {
  if (!scene.fence)
    return Error{ErrorKind::invalid_argument,
                 "the scene sets no fence, nor does the arm file: give one in a scene file's or the arm file's "
                 "\"fence\" (docs/scene.md)"};
  Scene out = scene;
  out.fence->on = on;
  return out;
}

Result<Scene> with_reduced_mode(const Scene& scene, bool on) {
  if (!scene.reduced)
    return Error{ErrorKind::invalid_argument,
                 "the scene sets no reduced mode, nor does the arm file: give one in a scene file's or the arm file's "
                 "\"reduced\" (docs/scene.md)"};
  Scene out = scene;
  out.reduced->on = on;
  return out;
}

std::string limits_json(const Scene& scene) {
  return json{{"fence", scene.fence ? fence_json(*scene.fence) : json(nullptr)},
              {"reduced", scene.reduced ? reduced_json(*scene.reduced) : json(nullptr)}}
      .dump();
}

Result<Scene> without_object(const Scene& scene, std::string_view name) {
  Scene out = scene;
  auto it = std::find_if(out.objects.begin(), out.objects.end(), [&](const SceneObject& o) { return o.name == name; });
  if (it == out.objects.end()) {
    std::string names;
    for (const auto& o : scene.objects) names += (names.empty() ? "" : ", ") + o.name;
    return Error{ErrorKind::invalid_argument, fmt::format("no scene object is named '{}' (the scene holds: {})", printable(name),
                                                          names.empty() ? "nothing" : names)};
  }
  out.objects.erase(it);
  return out;
}

}  // namespace armctl::scene
