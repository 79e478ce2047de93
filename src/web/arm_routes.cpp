// The arm's own endpoints: model, URDF, state and its event stream, control, STOP and the
// moves (joints, tool, jog, gripper, torque), clearing joint faults.
#include <fmt/core.h>

#include "web/api_error.hpp"
#include "web/request_body.hpp"
#include "web/server_state.hpp"
#include "web/state_json.hpp"

namespace armctl::web {

namespace {

using namespace std::chrono_literals;

void add_event_stream(WebServer::State& s) {
  s.router.add("GET", "/api/v1/events", [&s](Call& c) {
    // Each stream holds a connection for as long as the page is open: they have a budget of
    // their own, so that tabs never use up what STOP and the page need.
    if (s.connections)
      if (auto refused = s.connections->begin_stream(GuardedServer::current_socket(), c.client))
        throw ApiError(503, *refused);
    auto last = std::make_shared<std::uint64_t>(0);
    const std::string client = c.client;
    s.lease.stream_opened(client);
    c.response.set_header("Cache-Control", "no-cache");
    c.response.set_header("X-Accel-Buffering", "no");
    // One "state" event per published snapshot; without news, one every idle interval.
    c.response.set_chunked_content_provider(
        "text/event-stream", [&s, last, client](std::size_t, httplib::DataSink& sink) {
          if (s.stopping) return false;
          const auto snapshot = s.worker.wait_for_update(*last, s.options.idle_event_interval);
          if (s.stopping) return false;
          *last = snapshot.sequence;
          const std::string event =
              "event: state\ndata: " + s.state_for(client, snapshot).dump(-1, ' ', false, json::error_handler_t::replace) +
              "\n\n";
          return sink.write(event.data(), event.size());
        },
        [&s, client](bool) { s.lease.stream_closed(client); });
  });
}

}  // namespace

void add_arm_routes(WebServer::State& s) {
  // Made at each request: a confirmed calibration changes the model the server drives with.
  s.router.add("GET", "/api/v1/model", [&s](Call& c) { c.reply(model_json(s.worker.model(), s.options.device)); });
  s.router.add("GET", "/api/v1/urdf", [&s](Call& c) {
    c.response.set_header("Cache-Control", "no-cache");
    c.response.set_content(s.worker.model().urdf_text, "application/xml");
  });
  s.router.add("GET", "/api/v1/state", [&s](Call& c) { c.reply(s.state_for(c.client, s.worker.snapshot())); });
  add_event_stream(s);

  s.router.add("POST", "/api/v1/control", [&s](Call& c) {
    const ControlRequest r = parse_control_request(c.body());
    if (r.take) s.lease.take(c.client);
    else s.lease.release(c.client);
    const ControlView v = s.lease.view(c.client);
    c.reply({{"control", {{"you", v.you}, {"holder", v.holder}, {"since", v.since}}}});
  });

  // From anyone, always, whatever the body: a STOP must never be refused for its form. The
  // worker tells the running job, drops queued ones and halts the arm (Arm::stop: on a
  // Robot Commands board that also stops a running action group).
  // With the link lost the halt may not reach the arm: the answer says so (still 200: the
  // stop was taken; the arm's own safety is what is left, docs/http-api.md).
  s.router.add("POST", "/api/v1/stop", [&s](Call& c) {
    s.worker.command(arm::MotionCommand::stop);
    const session::ArmSnapshot now = s.worker.snapshot();
    json answer{{"stopped", true}, {"link_ok", now.link_ok}};
    if (!now.link_ok)
      answer["warning"] = fmt::format("the link to the arm is lost ({}): the stop may not have reached it",
                                      now.link_error.empty() ? "nothing read yet" : now.link_error);
    c.reply(answer);
  });

  s.router.add("POST", "/api/v1/joints", [&s](Call& c) {
    s.lease.require(c.client);
    const JointsRequest r = parse_joints_request(s.worker.model(), c.body());
    if (auto ok = s.kinematics().check_targets(r.targets); !ok) fail(ok.error());
    c.reply(s.start_motion("joints move", joint_move_job(r)));
  });
  s.router.add("POST", "/api/v1/tool", [&s](Call& c) {
    s.lease.require(c.client);
    const ToolRequest r = parse_tool_request(c.body());
    c.reply(s.start_motion(r.linear ? "linear tool move" : "tool move", tool_move_job(r)));
  });
  s.router.add("POST", "/api/v1/jog", [&s](Call& c) {
    s.lease.require(c.client);
    const JogRequest r = parse_jog_request(c.body());
    c.reply(s.start_motion("jog", jog_job(r)));
  });
  // Hold-to-jog, a tool axis or one joint: the page sends this every 50 ms while a button is
  // held; when it stops coming (released, the page closed, the connection lost) the arm slows
  // to rest in 0.2 s.
  s.router.add("POST", "/api/v1/servo", [&s](Call& c) {
    s.lease.require(c.client);
    if (auto ok = s.servo.send(parse_servo_request(s.worker.model(), c.body())); !ok) fail(ok.error());
    const arm::ServoStatus now = s.servo.status();
    c.reply(json{{"following", true}, {"slowdown", arm::to_string(now.slowdown)}, {"detail", now.detail}});
  });
  s.router.add("POST", "/api/v1/gripper", [&s](Call& c) {
    s.lease.require(c.client);
    const double closed = parse_gripper_request(c.body());
    if (!s.worker.model().gripper)
      throw ApiError(409, fmt::format("arm {} has no gripper", s.worker.model().name));
    c.reply(s.start_motion("gripper", gripper_job(closed)));
  });
  s.router.add("POST", "/api/v1/torque", [&s](Call& c) {
    s.lease.require(c.client);
    const bool on = parse_torque_request(c.body());
    // Done at once: answered when the worker is free again.
    s.run_to_end(on ? "torque on" : "torque off", [on](arm::Arm& arm, session::JobContext&) { return arm.set_torque(on); });
    c.reply({{"torque", on}});
  });
  // The faults the joints hold (shown in the state's `faults`): each joint holds where it is
  // and drives again. 500 naming the joints that could not be cleared.
  s.router.add("POST", "/api/v1/clear-faults", [&s](Call& c) {
    s.lease.require(c.client);
    parse_empty_request(c.body());
    s.run_to_end("clear faults", session::clear_faults);
    c.reply({{"faults_cleared", true}});
  });
}

}  // namespace armctl::web
