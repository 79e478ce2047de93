// armctl: drive, simulate and program robot arms. See README.md.
#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include "apps/armctl/commands.hpp"
#include "core/error.hpp"

int main(int argc, char** argv) {
  CLI::App app{"armctl: drive, simulate and program robot arms (xArm, SCARA joint bus)"};
  app.require_subcommand(1);
  armctl::cli::add_bus_command(app);
  armctl::cli::add_sim_command(app);
  armctl::cli::add_xarm_command(app);
  armctl::cli::add_emulate_command(app);
  armctl::cli::add_list_command(app);
  armctl::cli::add_controller_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);  // usage errors: message on stderr, exit status 2 (106 for CLI11 internals)
  } catch (const armctl::ArmctlError& e) {
    fmt::print(stderr, "armctl: {}: {}\n", armctl::to_string(e.error().kind), e.what());
    return 1;
  } catch (const std::exception& e) {
    fmt::print(stderr, "armctl: error: {}\n", e.what());
    return 1;
  }
  return 0;
}
