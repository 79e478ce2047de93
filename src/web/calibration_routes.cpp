// The guided calibration over HTTP (docs/http-api.md "Calibration"): one server-side
// calibration::CalibrationSession, started by the client that holds control and used only
// by it; every step is the engine's, run on the arm's worker thread like any job. Nothing is
// written until confirm; cancel, a new start, another client starting its own session, or
// the client losing control (the torque goes back on) drop the pending answers (nothing
// written). A confirmed file is what the server drives with from then on (the engine's
// confirm hands it to the Arm), and what a next calibration starts from. Values in the API's
// units (deg or mm, the tool in mm: docs/http-api.md "Conventions").
#include <memory>
#include <mutex>

#include <fmt/core.h>

#include "calibration/arm_file_writer.hpp"
#include "calibration/calibration_json.hpp"
#include "calibration/joint_pictures.hpp"
#include "calibration/rc_servo_bus.hpp"
#include "calibration/touch_sheet.hpp"
#include "web/api_error.hpp"
#include "web/calibration_request.hpp"
#include "web/display_value.hpp"
#include "web/server_state.hpp"

namespace armctl::web {

namespace {

namespace cal = calibration;

// A session with the servo bus it reaches the xArm's IDs and offsets through: one object, so
// that a step still running on the worker keeps both alive.
struct Calibrating {
  Calibrating(arm::Arm& arm, robot_commands::Client* board, cal::SessionOptions options)
      : servos(board ? std::make_unique<cal::RcServoBus>(*board) : nullptr), session(arm, servos.get(), options) {}
  std::unique_ptr<cal::RcServoBus> servos;
  cal::CalibrationSession session;
};

// The one session and whose it is. Handlers hold `mutex` for their whole run, so that the
// session's answers never change under a step that runs on the worker.
struct CalibrationLane {
  std::mutex mutex;
  std::string owner;  // the client that started it
  std::shared_ptr<Calibrating> calibrating;
};

cal::JsonValues shown(const arm::ArmModel& model) { return {model, cal::Units::display}; }

// A step that gives nothing back, as the value on_worker carries.
Result<bool> status(Status st) {
  if (!st) return st.error();
  return true;
}

json state_json(const CalibrationLane& lane) {
  json out{{"active", lane.calibrating != nullptr}};
  if (!lane.calibrating) return out;
  const cal::CalibrationSession& session = lane.calibrating->session;
  const auto v = shown(session.model());
  auto changes = session.changes();
  out["changes"] = changes ? cal::to_json(v, *changes) : json(nullptr);
  // A refused whole (check_changes) is said, not failed: the user redoes or forgets a step.
  out["refused"] = changes ? json(nullptr) : json(changes.error().message);
  out["describe"] = session.describe();
  json touched = json::array();
  for (const auto& p : session.touched()) touched.push_back(cal::to_json(v, p));
  out["touched"] = touched;
  out["file"] = session.model().file.string();
  return out;
}

}  // namespace

void add_calibration_routes(WebServer::State& s) {
  auto lane = std::make_shared<CalibrationLane>();

  // Runs `f(session)` on the worker (it moves or reads the arm) and gives what it returns.
  auto on_worker = [&s](const std::string& what, std::shared_ptr<Calibrating> calibrating, auto f) {
    using T = decltype(f(calibrating->session));
    auto out = std::make_shared<std::optional<T>>();
    s.run_to_end("calibration " + what, [calibrating, out, f](arm::Arm&, session::JobContext&) -> Status {
      auto r = f(calibrating->session);
      if (!r) return r.error();
      out->emplace(std::move(r));
      return Ok{};
    });
    return std::move(**out).value();
  };

  // The client that calibrates lost control (another took it, it released it, its page went
  // away and its control ended): its session ends as a cancel ends it, the torque back on
  // where the arm stands, so that a page closed with the joints released leaves no limp arm
  // and no session behind.
  s.control_changed.push_back([lane, on_worker](const std::optional<std::string>& holder) {
    std::lock_guard lock(lane->mutex);
    if (!lane->calibrating || (holder && *holder == lane->owner)) return;
    try {
      on_worker("hold", lane->calibrating, [](cal::CalibrationSession& x) { return status(x.hold()); });
    } catch (const std::exception&) {
      // The worker is busy with the new holder's motion (which has the torque on), or the
      // device failed (the session has nothing left to hold): it ends all the same.
    }
    lane->calibrating.reset();
    lane->owner.clear();
  });

  // The pictures the direction and zero steps refer to (docs/calibration.md "Pictures"), of the
  // arm file the server runs: read-only, for anyone.
  s.router.add("GET", "/api/v1/calibration/pictures", [&s](Call& c) {
    c.response.set_header("Cache-Control", "no-cache");
    c.response.set_content(must(cal::joint_pictures_svg(s.worker.model())), "image/svg+xml");
  });

  s.router.add("GET", "/api/v1/calibration", [&s, lane](Call& c) {
    s.lease.require(c.client);
    std::lock_guard lock(lane->mutex);
    if (lane->owner != c.client) return c.reply(json{{"active", false}});
    c.reply(state_json(*lane));
  });

  s.router.add("POST", R"(/api/v1/calibration/([a-z]+))", [&s, lane, on_worker](Call& c) {
    s.lease.require(c.client);
    const arm::ArmModel& model = s.worker.model();
    const CalibrationRequest q = parse_calibration_request(model, c.params.at(0), c.body());
    const auto v = shown(model);
    std::lock_guard lock(lane->mutex);
    if (q.step == "start") {
      // A new session replaces any other (nothing of it written): the holder of control is
      // the one who calibrates.
      cal::SessionOptions options;
      options.servo_offsets = q.servo_offsets;
      session::ArmSession& opened = s.worker.session();
      lane->calibrating = std::make_shared<Calibrating>(*opened.arm, opened.board, options);
      lane->owner = c.client;
      json marks = json::object();
      for (std::size_t i = 0; i < model.joints.size(); ++i)
        marks[model.joints[i].name] = display_value(model.joints[i].dimension, cal::mark_of(model.joints[i]));
      json sheet = json::array();
      if (auto points = cal::sheet_points(model, cal::default_placement(model)))
        for (const auto& p : *points) sheet.push_back(cal::to_json(v, p));
      json out = state_json(*lane);
      out["marks"] = marks;
      out["sheet"] = sheet;
      out["previous"] = cal::previous_file(model.file).string();
      return c.reply(out);
    }
    if (!lane->calibrating || lane->owner != c.client)
      throw ApiError(409, "no calibration started by this client: POST /api/v1/calibration/start first");
    auto calibrating = lane->calibrating;
    cal::CalibrationSession* session = &calibrating->session;
    json out;
    if (q.step == "find") {
      out["find"] = cal::to_json(v, on_worker("find", calibrating, [](cal::CalibrationSession& x) { return x.find(); }));
    } else if (q.step == "wiggle") {
      on_worker("wiggle", calibrating, [=](cal::CalibrationSession& x) { return status(x.wiggle(q.joint)); });
    } else if (q.step == "which") {
      // A mix-up is an answer, not a failure: said with what to do (the engine's words).
      Status same = session->answer_which(q.joint, q.moved);
      out["same"] = bool(same);
      out["advice"] = same ? json(nullptr) : json(same.error().message);
    } else if (q.step == "nudge") {
      on_worker("nudge", calibrating, [=](cal::CalibrationSession& x) { return status(x.nudge(q.joint)); });
    } else if (q.step == "direction") {
      must(status(session->answer_direction(q.joint, q.went_as_shown)));
    } else if (q.step == "release" || q.step == "hold") {
      const bool on = q.step == "hold";
      on_worker(q.step, calibrating, [=](cal::CalibrationSession& x) { return status(on ? x.hold() : x.release()); });
      out["torque"] = on;
    } else if (q.step == "read") {
      out["value"] = display_value(model.joints[std::size_t(q.joint)].dimension,
                                   on_worker("read", calibrating, [=](cal::CalibrationSession& x) { return x.read_joint(q.joint); }));
    } else if (q.step == "zero") {
      const double mark = q.mark.value_or(cal::mark_of(model.joints[std::size_t(q.joint)]));
      out["zero"] = cal::to_json(v, q.joint, on_worker("zero", calibrating, [=](cal::CalibrationSession& x) { return x.zero_here(q.joint, mark); }));
    } else if (q.step == "limits") {
      out["limits"] = cal::to_json(v, q.joint, must(session->limits(q.joint, q.end_a, q.end_b)));
    } else if (q.step == "gripper") {
      out["gripper"] = cal::to_json(v, must(session->gripper(q.open, q.closed)));
    } else if (q.step == "touch") {
      const cal::NamedPoint point = must(cal::user_point(model, q.name, q.position));
      out["touched"] = cal::to_json(v, on_worker("touch", calibrating, [=](cal::CalibrationSession& x) { return x.touch(point); }));
    } else if (q.step == "verify") {
      out["verify"] = cal::to_json(v, must(session->verify()));
    } else if (q.step == "fit") {
      out["fit"] = cal::to_json(v, must(session->fit()));
    } else if (q.step == "forget") {
      if (q.joint < 0) session->forget_all();
      else session->forget(q.joint);
    } else if (q.step == "confirm") {
      // The torque goes back on before anything is written: the arm holds where it stands.
      on_worker("hold", calibrating, [](cal::CalibrationSession& x) { return status(x.hold()); });
      const arm::ArmModel written = on_worker("confirm", calibrating, [](cal::CalibrationSession& x) { return x.confirm(); });
      out["written"] = cal::written_json(written);
      lane->calibrating.reset();
      lane->owner.clear();
      return c.reply(out);
    } else if (q.step == "cancel") {
      on_worker("hold", calibrating, [=](cal::CalibrationSession& x) { return status(x.hold()); });
      lane->calibrating.reset();
      lane->owner.clear();
      return c.reply(json{{"active", false}, {"written", nullptr}});
    }
    json state = state_json(*lane);
    for (auto& [key, value] : out.items()) state[key] = value;
    c.reply(state);
  });
}

}  // namespace armctl::web
