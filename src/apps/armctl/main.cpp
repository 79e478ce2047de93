// armctl: drive, simulate and program robot arms. See README.md.
#include <csignal>
#include <cstdio>
#include <exception>
#include <iostream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include "apps/armctl/cli_reference.hpp"
#include "apps/armctl/commands.hpp"
#include "apps/armctl/json_output.hpp"
#include "apps/armctl/serve_support.hpp"
#include "core/error.hpp"
#include "core/printable.hpp"

namespace {

// CLI11 answers an unknown subcommand ("armctl bus frobnicate") with "A subcommand is
// required", which hides the typo. Let such commands parse with no subcommand, so the typo
// is reported as an unexpected argument, and report a truly missing one with the choices.
std::string display_name(const CLI::App& app) {
  return app.get_parent() == nullptr ? "armctl" : app.get_name();
}

std::string subcommand_names(CLI::App& app) {
  std::string names;
  for (const CLI::App* sub : app.get_subcommands({})) {
    names += (names.empty() ? "" : ", ") + sub->get_name();
  }
  return names;
}

// Follows argv down the subcommand tree; the first word that should name a subcommand and
// does not is reported with the allowed names ("armctl bus frobnicate").
void check_command_words(CLI::App& app, int argc, char** argv) {
  CLI::App* current = &app;
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    if (current->get_subcommands({}).empty() || word == "--") return;
    if (word.size() > 1 && word[0] == '-') {
      const CLI::Option* option = current->get_option_no_throw(word.substr(0, word.find('=')));
      if (option != nullptr && word.find('=') == std::string::npos &&
          option->get_items_expected_min() > 0) {
        ++i;  // the option's value
      }
      continue;
    }
    CLI::App* sub = nullptr;
    for (CLI::App* candidate : current->get_subcommands({})) {
      if (candidate->check_name(word)) sub = candidate;
    }
    if (sub == nullptr) {
      throw CLI::ValidationError(fmt::format("{}: unknown command '{}'; allowed: {}",
                                             display_name(*current), word, subcommand_names(*current)));
    }
    current = sub;
  }
}

void name_missing_subcommands(CLI::App& app) {
  for (CLI::App* sub : app.get_subcommands({})) name_missing_subcommands(*sub);
  if (app.get_require_subcommand_min() == 0) return;
  app.require_subcommand(0, app.get_require_subcommand_max());
  app.parse_complete_callback([&app] {
    if (!app.get_subcommands().empty()) return;
    throw CLI::ValidationError(fmt::format("{}: a command is required; allowed: {}",
                                           display_name(app), subcommand_names(app)));
  });
}

// Exit statuses (README "Exit status"): 0 done, 1 failed, 2 a usage error, 128 + N a
// command that ended because signal N stopped it (130: Ctrl-C), as shells report it.
constexpr int kUsageError = 2;

int failure_status() {
  const int signal = armctl::cli::last_stop_signal();
  return signal != 0 ? 128 + signal : 1;
}

// Asked for --json (anywhere before a "--"): a failure is also one JSON line on standard
// output, {"event": "error", "kind": ..., "message": ..., "exit_status": N}, so that a script
// reading the command's JSON reads its failure there too. The message stays on stderr.
bool json_asked(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view word = argv[i];
    if (word == "--") return false;
    if (word == "--json") return true;
  }
  return false;
}

int report_json_error(bool asked, std::string_view kind, const std::string& message, int status) {
  if (asked) {
    try {
      armctl::cli::print_json_line({{"event", "error"}, {"kind", kind}, {"message", message}, {"exit_status", status}});
      std::fflush(stdout);
    } catch (const std::exception&) {
    }
  }
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  // A file-size limit (ulimit -f) must not kill armctl with SIGXFSZ in the middle of a save
  // (the emulated board's state dir, an arm file): ignored, a write past the limit fails with
  // EFBIG, and the board or command reports that like any other storage error.
  std::signal(SIGXFSZ, SIG_IGN);
  CLI::App app{"armctl: drive, simulate and program robot arms (xArm, SCARA joint bus)"};
  app.set_version_flag("--version", std::string("armctl ") + ARMCTL_VERSION);
  app.require_subcommand(1);
  armctl::cli::add_arm_command(app);
  armctl::cli::add_stop_command(app);
  armctl::cli::add_program_command(app);
  armctl::cli::add_teach_command(app);
  armctl::cli::add_jog_command(app);
  armctl::cli::add_calibrate_command(app);
  armctl::cli::add_follow_command(app);
  armctl::cli::add_replay_command(app);
  armctl::cli::add_serve_command(app);
  armctl::cli::add_bus_command(app);
  armctl::cli::add_sim_command(app);
  armctl::cli::add_xarm_command(app);
  armctl::cli::add_emulate_command(app);
  armctl::cli::add_list_command(app);
  armctl::cli::add_controller_command(app);
  armctl::cli::add_reference_commands(app);
  name_missing_subcommands(app);
  // Messages go to stderr even when it is closed or full: a failed write of a message must
  // not turn an exit status 1 into an abort.
  // printable(): a message may quote a file's text, a key, a device string or an argument;
  // control characters in it are shown as \xNN, never sent to the terminal.
  auto report = [](const std::string& line) {
    try {
      std::size_t start = 0;  // line by line: a message of several lines keeps its shape
      for (std::size_t end; (end = line.find('\n', start)) != std::string::npos; start = end + 1)
        fmt::print(stderr, "{}\n", armctl::printable(std::string_view(line).substr(start, end - start)));
      fmt::print(stderr, "{}\n", armctl::printable(std::string_view(line).substr(start)));
    } catch (const std::exception&) {
    }
  };
  const bool json = json_asked(argc, argv);
  try {
    check_command_words(app, argc, argv);
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    try {
      // Usage errors: message on stderr, exit status 2 whatever CLI11's own code (105, 106,
      // 109...); --help and --version exit 0. CLI11 echoes the arguments it did not expect:
      // they pass through report() like every message.
      std::ostringstream message;
      const int status = app.exit(e, std::cout, message);
      std::string text = message.str();
      if (!text.empty() && text.back() == '\n') text.pop_back();
      if (!text.empty()) report(text);
      if (status == 0) return 0;
      return report_json_error(json, "usage", text, kUsageError);
    } catch (const std::exception&) {
      return 2;
    }
  } catch (const armctl::ArmctlError& e) {
    report(fmt::format("armctl: {}: {}", armctl::to_string(e.error().kind), e.what()));
    return report_json_error(json, armctl::to_string(e.error().kind), e.what(), failure_status());
  } catch (const std::exception& e) {
    report(fmt::format("armctl: error: {}", e.what()));
    return report_json_error(json, "error", e.what(), failure_status());
  }
  // Output that did not reach stdout (a full disk, /dev/full, a closed pipe) is a failure:
  // a script must not read "0" as "printed".
  if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
    report("armctl: I/O error: could not write the output to stdout");
    return 1;
  }
  return 0;
}
