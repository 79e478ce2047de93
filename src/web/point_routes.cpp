// Named points (docs/programs.md "Points"): listed, recorded where the arm stands, deleted;
// saved to the --points file after every change (program points-file format).
#include <fmt/core.h>

#include "core/printable.hpp"
#include "core/quantity.hpp"
#include "web/display_value.hpp"
#include "teach/teach.hpp"
#include "web/api_error.hpp"
#include "web/request_body.hpp"
#include "web/server_state.hpp"

namespace armctl::web {

namespace {

json point_json(const arm::ArmKinematics& arm, const files::Point& p) {
  const arm::ArmModel& model = arm.model();
  json out{{"name", p.name}};
  if (p.is_joints()) {
    json joints = json::object();
    std::vector<double> positions(model.joints.size(), 0.0);
    for (std::size_t i = 0; i < p.joints.size() && i < model.joints.size(); ++i) {
      joints[model.joints[i].name] = display_value(p.joints[i].dimension, p.joints[i].value);
      positions[i] = p.joints[i].value;
    }
    out["joints"] = std::move(joints);
    // Where the tool is at those joints (a point may leave the last joints out: zero then).
    out["tool"] = p.joints.size() >= std::size_t(model.chain_joints())
                      ? tool_json(arm, arm.forward(arm.chain_of(positions)), positions)
                      : json(nullptr);
  } else {
    json tool{{"x", tidy(p.position.x() * 1e3)}, {"y", tidy(p.position.y() * 1e3)}, {"z", tidy(p.position.z() * 1e3)}};
    for (auto [key, value] : {std::pair{"roll", p.roll}, std::pair{"pitch", p.pitch}, std::pair{"yaw", p.yaw}})
      tool[key] = value ? json(display_value(Dimension::angle, *value)) : json(nullptr);
    out["joints"] = nullptr;
    out["tool"] = std::move(tool);
  }
  return out;
}

// The points as the API shows them; the caller holds points_mutex.
json points_json(WebServer::State& s) {
  json list = json::array();
  for (const auto& p : s.points.points) list.push_back(point_json(s.kinematics(), p));
  return {{"file", s.options.points_file.empty() ? json(nullptr) : json(s.options.points_file.string())},
          {"points", std::move(list)}};
}

// Writes the file (if any) with `next`; only then does `next` replace the points.
void commit(WebServer::State& s, files::PointsFile next) {
  if (!s.options.points_file.empty())
    if (auto ok = files::write_points_file(s.options.points_file, next); !ok)
      throw ApiError(500, fmt::format("the points were not changed: {}", ok.error().message));
  s.points = std::move(next);
}

}  // namespace

void add_point_routes(WebServer::State& s) {
  s.router.add("GET", "/api/v1/points", [&s](Call& c) {
    std::lock_guard lock(s.points_mutex);
    c.reply(points_json(s));
  });
  s.router.add("POST", "/api/v1/points", [&s](Call& c) {
    s.lease.require(c.client);
    const std::string name = parse_point_request(c.body());
    // Where the arm stands now: a fresh read on the worker (the snapshot may be a poll old).
    std::vector<double> positions;
    s.run_to_end("record point", [&positions](arm::Arm& arm, session::JobContext&) -> Status {
      auto here = arm.read();
      if (!here) return here.error();
      positions = here->positions;
      return Ok{};
    });
    std::lock_guard lock(s.points_mutex);
    files::PointsFile next = s.points;
    files::Point point = teach::point_at(s.worker.model(), positions, name);
    bool replaced = false;
    for (auto& p : next.points)
      if (p.name == name) {
        p = point;
        replaced = true;
      }
    if (!replaced) {
      if (next.points.size() >= files::kPointsFileMaxPoints)
        throw ApiError(400, fmt::format("name: '{}' would be point {}; at most {} points are allowed", name,
                                        next.points.size() + 1, files::kPointsFileMaxPoints));
      next.points.push_back(point);
    }
    commit(s, std::move(next));
    c.reply({{"point", point_json(s.kinematics(), point)}, {"replaced", replaced}});
  });
  s.router.add("DELETE", "/api/v1/points/([^/]*)", [&s](Call& c) {
    s.lease.require(c.client);
    const std::string name = check_point_name(c.params[0]);
    std::lock_guard lock(s.points_mutex);
    files::PointsFile next = s.points;
    const auto before = next.points.size();
    std::erase_if(next.points, [&](const files::Point& p) { return p.name == name; });
    if (next.points.size() == before) throw ApiError(404, fmt::format("no point named '{}'", printable(name)));
    commit(s, std::move(next));
    c.reply({{"deleted", name}});
  });
}

}  // namespace armctl::web
