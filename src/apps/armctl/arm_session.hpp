// The CLI's name for the arm session, which lives in armctl_session (src/session) so that
// the CLI and the Python module open arms the same way.
#pragma once

#include "apps/armctl/xarm_session.hpp"
#include "session/arm_session.hpp"

namespace armctl::cli {

using session::ArmSession;
using session::device_is_joint_bus;
using session::load_arm;
using session::open_arm_session;

}  // namespace armctl::cli
