#include "apps/armctl/commands.hpp"

namespace armctl::cli {

// Not built yet: registers nothing, so 'armctl emulate' is reported as an unknown subcommand.
void add_emulate_command(CLI::App& /*app*/) {}

}  // namespace armctl::cli
