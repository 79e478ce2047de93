// What the server's handlers share (private to src/web): the worker, the lease, the
// program run, the points, and the one way jobs are started.
#pragma once

#include <atomic>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "files/points_file.hpp"
#include "session/arm_worker.hpp"
#include "session/servo_lane.hpp"
#include "web/connection_guard.hpp"
#include "web/control_lease.hpp"
#include "web/motion_jobs.hpp"
#include "web/program_run.hpp"
#include "web/router.hpp"
#include "web/security.hpp"
#include "web/web_server.hpp"

namespace armctl::web {

struct WebServer::State {
  State(session::ArmWorker& w, ServerOptions o) : worker(w), options(std::move(o)), lease(options.control_idle, options.control_grace) {}

  session::ArmWorker& worker;
  ServerOptions options;
  SecurityPolicy policy;
  ControlLease lease;
  ProgramRun program;
  std::atomic<bool> stopping{false};
  Router router;
  ConnectionTable* connections = nullptr;  // the server's (event streams take their budget there)

  std::mutex points_mutex;
  files::PointsFile points;
  // Called on the server's control watcher thread when control passed to another client or
  // to nobody (taken over, released, the holder's page gone): what a holder had started
  // for itself ends there (a calibration puts the torque back on). Added before start().
  std::vector<std::function<void(const std::optional<std::string>& holder)>> control_changed;

  // Hold-to-jog (POST /api/v1/servo): one servo session on the worker for every client.
  session::ServoLane servo{worker};

  // The arm's kinematics (check_targets, forward, tool_rpy, planning): an immutable value,
  // safe on the HTTP threads while the worker thread drives the arm.
  const arm::ArmKinematics& kinematics() { return *worker.session().arm->kinematics(); }

  // Queues a motion job and waits until it has accepted (planned, checked, started) or
  // refused: its answer, or an ApiError (400 a bad value, 409 busy, 500 the device).
  json start_motion(const std::string& what, MotionJob job);
  // Runs a short job to its end and gives its status (ApiError on failure).
  void run_to_end(const std::string& what, session::ArmWorker::Job job);

  json state_for(const std::string& client, const session::ArmSnapshot& snapshot);
};

void add_arm_routes(WebServer::State& s);
void add_point_routes(WebServer::State& s);
void add_group_routes(WebServer::State& s);
void add_program_routes(WebServer::State& s);
void add_scene_routes(WebServer::State& s);
void add_calibration_routes(WebServer::State& s);

}  // namespace armctl::web
