// The arm-worker jobs behind the API's moves (joints, tool, jog, gripper). Each
// plans from where the arm stands when it runs (a fresh read), checks everything before
// anything moves (Arm::check_targets, IK, the motion layer's planners), says whether it
// was accepted through `accept` (the HTTP answer), then runs through the motion executor
// with the job's context so that STOP, pause and the published positions reach it.
#pragma once

#include <functional>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "session/arm_worker.hpp"
#include "web/request_body.hpp"

namespace armctl::web {

// Called once by a job: the error that refused it, or what to answer ({"moving": true, ...}).
using Accept = std::function<void(Result<nlohmann::json>)>;
using MotionJob = std::function<Status(arm::Arm&, session::JobContext&, const Accept&)>;

MotionJob joint_move_job(JointsRequest request);
MotionJob tool_move_job(ToolRequest request);
MotionJob jog_job(JogRequest request);
MotionJob gripper_job(double closed_fraction);

}  // namespace armctl::web
