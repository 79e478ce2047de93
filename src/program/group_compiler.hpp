// Compiling a checked program plan into a Robot Commands action group, so that the board
// replays the program without a host (docs/programs.md "Compile"). Each action is a
// MultiServoMove: the board moves every servo linearly (in servo units) to the action's
// positions over its time. The plan's motions are sampled finely enough that this stays
// within `path_error` of where the plan has the tool at every instant (checked at a
// quarter, half and three quarters of every action; see group_compiler.cpp), waits hold
// the position, prints are left out (the board has no output). Pure code.
#pragma once

#include <string>
#include <vector>

#include "arm/arm.hpp"
#include "core/error.hpp"
#include "devices/robot_commands/client.hpp"
#include "program/program_plan.hpp"

namespace armctl::program {

struct CompileOptions {
  double path_error = 0.001;        // m: the largest tool distance from the plan, from sampling
  double first_move_seconds = 1.0;  // the first action: every servo to where the plan starts
};

struct CompiledGroup {
  std::vector<robot_commands::GroupAction> actions;
  double duration = 0;         // s, the first move included
  double sampling_error = 0;   // m: the largest tool distance from the plan at the probes
  std::vector<std::string> notes;  // what the group leaves out ("line 9: PRINT is not replayed")
};

// Errors: unsupported (a joint without a Robot Commands servo), invalid_argument (more
// actions than a group holds, kActionsMax = 1020, naming how many were needed).
Result<CompiledGroup> compile_to_group(const arm::Arm& arm, const ProgramPlan& plan, const CompileOptions& options = {});

}  // namespace armctl::program
