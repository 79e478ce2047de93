#include "program/program_runner.hpp"

namespace armctl::program {

Result<RunReport> run_plan(arm::Arm& arm, const ProgramPlan& plan, const RunOptions& options) {
  RunOptions named = options;
  named.label_errors = true;
  return arm::run_motion(arm, plan, named);
}

}  // namespace armctl::program
