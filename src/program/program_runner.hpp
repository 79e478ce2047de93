// Runs a checked program plan on an arm: the one runner (arm/run_motion.hpp) with the
// program's conventions: every motion piece through the motion executor, WAITs on the
// device's clock, PRINTs handed to the caller as message events, and an error names the
// piece ("line 12 (LIN pick): ..."). The caller's `command` can stop at any point: a motion
// then slows down on its path within the joints' limits (the executor's stop) and the run
// ends there.
#pragma once

#include "arm/arm.hpp"
#include "arm/run_motion.hpp"
#include "core/error.hpp"
#include "program/program_plan.hpp"

namespace armctl::program {

using RunEventKind = arm::RunEventKind;
using RunEvent = arm::RunEvent;
using RunOptions = arm::RunHooks;
using RunReport = arm::RunReport;

// The plan must start where the arm stands (plan it from a fresh read).
Result<RunReport> run_plan(arm::Arm& arm, const ProgramPlan& plan, const RunOptions& options = {});

}  // namespace armctl::program
