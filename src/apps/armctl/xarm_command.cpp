#include "apps/armctl/commands.hpp"

namespace armctl::cli {

// Not built yet: registers nothing, so 'armctl xarm' is reported as an unknown subcommand.
void add_xarm_command(CLI::App& /*app*/) {}

}  // namespace armctl::cli
