#include "web/error_detail.hpp"

#include "core/source_place.hpp"
#include "web/display_value.hpp"

namespace armctl::web {

namespace {

using nlohmann::json;

json body_json(const scene::BodyId& id, const std::string& text) {
  return {{"kind", id.kind == scene::BodyId::Kind::link ? "link" : "object"},
          {"name", id.name.empty() ? json(nullptr) : json(id.name)},
          {"text", text}};
}

json mm(const Eigen::Vector3d& p) { return json::array({tidy(p.x() * 1e3), tidy(p.y() * 1e3), tidy(p.z() * 1e3)}); }

}  // namespace

json collision_json(const arm::CollisionDetail& d, const arm::ArmModel& model) {
  json joints = json::object();
  for (std::size_t i = 0; i < model.joints.size() && i < d.joints.size(); ++i)
    joints[model.joints[i].name] = display_value(model.joints[i].dimension, d.joints[i]);
  return {{"bodies", json::array({body_json(d.contact.first_body, d.contact.first),
                                  body_json(d.contact.second_body, d.contact.second)})},
          {"point", mm(d.contact.point)},
          // What was met: "collision" (two bodies), "fence" or "joint range" (a limit of the
          // scene: the first body breaks it, the second is the limit's words).
          {"limit", scene::to_string(d.contact.limit)},
          // A joint range's depth is an angle or a length of that joint, not a distance in space.
          {"depth_mm", d.contact.limit == scene::Limit::joint_range ? json(nullptr) : json(tidy(d.contact.depth * 1e3))},
          {"tool_point", mm(d.tool_point)},
          {"fraction", tidy(d.fraction)},
          {"line", d.line ? json(d.line) : json(nullptr)},
          {"while_moving", d.while_moving},
          {"joints", joints}};
}

void add_error_detail(json& body, const Error& error, const arm::ArmModel& model) {
  if (const auto* c = detail_or_cause<arm::CollisionDetail>(error)) body["collision"] = collision_json(*c, model);
}

}  // namespace armctl::web
