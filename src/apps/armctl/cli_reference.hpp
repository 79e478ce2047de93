// What armctl's own command tree says about itself, for the shell and for `man`: a bash
// completion script and a manual page, both generated from the CLI11 tree that parses the
// arguments, so they never miss a command or an option (armctl completion bash, armctl
// manual; installed by `make install`).
#pragma once

#include <string>
#include <string_view>

#include <CLI/CLI.hpp>

namespace armctl::cli {

// A bash script that completes every command word and every option of `root` (and files
// after an option that takes a value). `source <(armctl completion bash)`.
std::string bash_completion(const CLI::App& root);

// The manual page of `root` in man(7) format: every command with its description, options
// and their descriptions, the exit statuses and where the documentation is.
std::string manual_page(const CLI::App& root, std::string_view version);

// `armctl completion bash` and `armctl manual`.
void add_reference_commands(CLI::App& app);

}  // namespace armctl::cli
