// Action groups on a Robot Commands board (docs/action-groups.md): download, erase, run,
// speed, stop; import and export of group files and .rob files; the current positions as
// a frame. The board keeps the groups and cannot send one back: the page holds the frames.
#include <fmt/core.h>

#include "core/quantity.hpp"
#include "web/display_value.hpp"
#include "web/api_error.hpp"
#include "web/group_frames.hpp"
#include "web/request_body.hpp"
#include "web/server_state.hpp"

namespace armctl::web {

namespace {

void require_board(WebServer::State& s) {
  if (!s.options.device.groups_supported)
    throw ApiError(409, fmt::format("action groups need a Robot Commands board; arm {} is driven over the joint bus",
                                    s.worker.model().name));
}

}  // namespace

void add_group_routes(WebServer::State& s) {
  auto board = [&s](const std::string& what, std::function<Status(arm::ActionGroups&)> f) {
    s.run_to_end(what, [f](arm::Arm& arm, session::JobContext&) -> Status {
      arm::ActionGroups* groups = arm.device().action_groups();  // require_board: there
      Status st = f(*groups);
      while (groups->next_event()) {
      }
      return st;
    });
  };
  s.router.add("PUT", "/api/v1/groups/([^/]+)", [&s, board](Call& c) {
    require_board(s);
    s.lease.require(c.client);
    const auto n = parse_group_number(c.params[0]);
    const json body = c.body();
    BodyReader r(body);
    const json& frames = r.require("frames", "an array of frames");
    r.finish();
    const GroupFrames g = frames_to_group(s.worker.model(), frames);
    for (std::size_t k = 0; k < g.targets.size(); ++k)
      if (auto ok = s.kinematics().check_targets(g.targets[k]); !ok)
        throw ApiError(400, fmt::format("frames[{}]: {}", k, ok.error().message));
    board(fmt::format("download group {}", n),
          [n, actions = g.group.actions](arm::ActionGroups& groups) { return groups.download(n, actions); });
    c.reply({{"group", n}, {"frames", g.group.actions.size()}});
  });
  s.router.add("DELETE", "/api/v1/groups/([^/]+)", [&s, board](Call& c) {
    require_board(s);
    s.lease.require(c.client);
    const auto n = parse_group_number(c.params[0]);
    parse_empty_request(c.body());
    board(fmt::format("erase group {}", n), [n](arm::ActionGroups& groups) { return groups.erase(n); });
    c.reply({{"erased", n}});
  });
  s.router.add("POST", "/api/v1/groups/([^/]+)/run", [&s, board](Call& c) {
    require_board(s);
    s.lease.require(c.client);
    const auto n = parse_group_number(c.params[0]);
    const auto times = parse_group_run(c.body());
    board(fmt::format("run group {}", n), [n, times](arm::ActionGroups& groups) { return groups.run_started(n, times); });
    c.reply({{"running", n}, {"times", times}, {"continuous", times == 0}});
  });
  s.router.add("POST", "/api/v1/groups/speed", [&s, board](Call& c) {
    require_board(s);
    s.lease.require(c.client);
    const auto percent = parse_group_speed(c.body());
    board("group speed", [percent](arm::ActionGroups& groups) { return groups.set_speed(255, percent); });
    c.reply({{"percent", percent}});
  });
  s.router.add("POST", "/api/v1/groups/stop", [&s, board](Call& c) {
    require_board(s);
    s.lease.require(c.client);
    parse_empty_request(c.body());
    board("stop group", [](arm::ActionGroups& groups) { return groups.stop(); });
    c.reply({{"stopped", true}});
  });
  s.router.add("POST", "/api/v1/groups/import", [&s](Call& c) {
    const auto group = parse_group_import(c.body());
    c.reply({{"frames", group_to_frames(s.worker.model(), group)}});
  });
  s.router.add("POST", "/api/v1/groups/export", [&s](Call& c) { c.reply(export_group(s.worker.model(), c.body())); });
  s.router.add("GET", "/api/v1/frame", [&s](Call& c) {
    const auto snapshot = s.worker.snapshot();
    const arm::ArmModel& model = s.worker.model();
    if (snapshot.positions.size() != model.joints.size())
      throw ApiError(500, fmt::format("no positions read from the arm yet{}",
                                      snapshot.link_error.empty() ? "" : ": " + snapshot.link_error));
    json positions = json::object();
    for (std::size_t i = 0; i < model.joints.size(); ++i)
      if (model.joints[i].map(arm::Protocol::robot_commands))
        positions[model.joints[i].name] = display_value(model.joints[i].dimension, snapshot.positions[i]);
    c.reply({{"time_ms", 1000}, {"positions", std::move(positions)}});
  });
}

}  // namespace armctl::web
