#include "apps/armctl/commands.hpp"

namespace armctl::cli {

// Not built yet: registers nothing, so 'armctl sim' is reported as an unknown subcommand.
void add_sim_command(CLI::App& /*app*/) {}

}  // namespace armctl::cli
