#include "apps/armctl/commands.hpp"

namespace armctl::cli {

// Not built yet: registers nothing, so 'armctl list' is reported as an unknown subcommand.
void add_list_command(CLI::App& /*app*/) {}

}  // namespace armctl::cli
