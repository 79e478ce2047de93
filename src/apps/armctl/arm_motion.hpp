// Host-planned motions from the command line: `armctl arm move-to --linear` and
// `armctl arm path FILE`. Every move is planned and checked, from where the previous one
// ends, before the first byte goes out; then they run one after the other through the
// motion executor: a progress line on motions longer than a second (or --json events),
// Ctrl-C stops along the path. Docs: docs/motion.md.
#pragma once

#include <optional>
#include <vector>

#include "session/arm_session.hpp"
#include "files/path_file.hpp"

namespace armctl::cli {

class MotionTrace;  // apps/armctl/motion_trace.hpp

struct MotionCliOptions {
  bool json = false;
  double speed_override = 1.0;  // (0, 1]
  MotionTrace* trace = nullptr;  // --trace FILE: every piece's plan and read-backs
};

// A path file's moves, or one move from the command line (line 0), planned by arm::plan_moves
// and run by arm::run_motion; returns the read that found the arm arrived at the end.
// Throws ArmctlError naming the line and what was wrong (nothing has moved then).
arm::JointState run_path_moves(session::ArmSession& session, const std::vector<files::PathMove>& moves, const MotionCliOptions& options);

}  // namespace armctl::cli
