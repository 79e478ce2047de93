#include "apps/armctl/commands.hpp"

namespace armctl::cli {

// Not built yet: registers nothing, so 'armctl bus' is reported as an unknown subcommand.
void add_bus_command(CLI::App& /*app*/) {}

}  // namespace armctl::cli
