// The CLI's name for the Robot Commands session, which lives in armctl_session (src/session)
// so that the CLI and the Python module open boards the same way.
#pragma once

#include "session/xarm_session.hpp"

namespace armctl::cli {

using session::open_xarm_session;
using session::XarmSession;

}  // namespace armctl::cli
