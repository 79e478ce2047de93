#include "apps/armctl/commands.hpp"

namespace armctl::cli {

// Not built yet: registers nothing, so 'armctl controller' is reported as an unknown subcommand.
void add_controller_command(CLI::App& /*app*/) {}

}  // namespace armctl::cli
