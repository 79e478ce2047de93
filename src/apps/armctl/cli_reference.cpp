#include "apps/armctl/cli_reference.hpp"

#include <functional>
#include <iostream>
#include <vector>

#include <fmt/core.h>

namespace armctl::cli {
namespace {

struct Command {
  std::string path;  // "arm move-to"; "" for armctl itself
  const CLI::App* app;
};

// Every command of the tree, depth first, armctl itself first.
std::vector<Command> commands_of(const CLI::App& root) {
  std::vector<Command> out;
  std::function<void(const std::string&, const CLI::App&)> visit = [&](const std::string& path, const CLI::App& app) {
    out.push_back({path, &app});
    for (const CLI::App* sub : const_cast<CLI::App&>(app).get_subcommands({}))
      if (!sub->get_disabled()) visit(path.empty() ? sub->get_name() : path + " " + sub->get_name(), *sub);
  };
  visit("", root);
  return out;
}

std::vector<const CLI::Option*> options_of(const CLI::App& app) {
  return app.get_options([](const CLI::Option* o) { return o != nullptr; });
}

// "--speed -s" for an option; empty for a positional argument.
std::vector<std::string> names_of(const CLI::Option& o) {
  std::vector<std::string> out;
  for (const auto& l : o.get_lnames()) out.push_back("--" + l);
  for (const auto& s : o.get_snames()) out.push_back("-" + s);
  return out;
}

std::string joined(const std::vector<std::string>& words) {
  std::string out;
  for (const auto& w : words) out += (out.empty() ? "" : " ") + w;
  return out;
}

// A bash `case` of one line per command: "path") echo "words";;
std::string case_function(const std::string& name, const std::string& comment, const std::vector<Command>& commands,
                          const std::function<std::vector<std::string>(const CLI::App&)>& words_of) {
  std::string out = fmt::format("{}() {{  # {}\n  case \"$1\" in\n", name, comment);
  for (const auto& c : commands) {
    const auto words = words_of(*c.app);
    if (!words.empty()) out += fmt::format("    \"{}\") echo \"{}\" ;;\n", c.path, joined(words));
  }
  return out + "  esac\n}\n";
}

// man(7) text: backslashes escaped, a line never starting with a control character.
std::string roff(std::string_view text) {
  std::string out;
  bool line_start = true;
  for (char c : text) {
    if (line_start && (c == '.' || c == '\'')) out += "\\&";
    if (c == '\\') out += "\\e";
    else if (c == '-') out += "\\-";
    else out += c;
    line_start = c == '\n';
  }
  return out;
}

}  // namespace

std::string bash_completion(const CLI::App& root) {
  const auto commands = commands_of(root);
  std::string out =
      "# bash completion for armctl: `source <(armctl completion bash)`, or installed by\n"
      "# `make install` (generated from armctl's own command tree by `armctl completion bash`).\n";
  out += case_function("_armctl_commands", "the commands under a command", commands, [](const CLI::App& app) {
    std::vector<std::string> words;
    for (const CLI::App* sub : const_cast<CLI::App&>(app).get_subcommands({}))
      if (!sub->get_disabled()) words.push_back(sub->get_name());
    return words;
  });
  out += case_function("_armctl_options", "the options of a command", commands, [](const CLI::App& app) {
    std::vector<std::string> words;
    for (const CLI::Option* o : options_of(app))
      for (const auto& n : names_of(*o)) words.push_back(n);
    return words;
  });
  out += case_function("_armctl_valued", "its options that take a value", commands, [](const CLI::App& app) {
    std::vector<std::string> words;
    for (const CLI::Option* o : options_of(app))
      if (o->get_items_expected_min() > 0)
        for (const auto& n : names_of(*o)) words.push_back(n);
    return words;
  });
  out += R"bash(_armctl() {
  local cur="${COMP_WORDS[COMP_CWORD]}" prev="" path="" w i
  # The command path typed so far: the words that name a command under the one before.
  for ((i = 1; i < COMP_CWORD; i++)); do
    w="${COMP_WORDS[i]}"
    [[ "$w" == -* ]] && continue
    [[ " $(_armctl_commands "$path") " == *" $w "* ]] && path="${path:+$path }$w"
  done
  ((COMP_CWORD > 1)) && prev="${COMP_WORDS[COMP_CWORD - 1]}"
  if [[ "$prev" == -* && " $(_armctl_valued "$path") " == *" $prev "* ]]; then
    COMPREPLY=($(compgen -f -- "$cur"))  # a value: often a file or a device
  elif [[ "$cur" == -* ]]; then
    COMPREPLY=($(compgen -W "$(_armctl_options "$path")" -- "$cur"))
  else
    COMPREPLY=($(compgen -W "$(_armctl_commands "$path")" -- "$cur"))
    ((${#COMPREPLY[@]} == 0)) && COMPREPLY=($(compgen -f -- "$cur"))
  fi
  return 0
}
complete -F _armctl armctl
)bash";
  return out;
}

std::string manual_page(const CLI::App& root, std::string_view version) {
  const auto commands = commands_of(root);
  std::string out = fmt::format(".TH ARMCTL 1 \"\" \"armctl {}\" \"User Commands\"\n", roff(version));
  out += ".SH NAME\narmctl \\- " + roff(root.get_description().substr(root.get_description().find(':') + 2)) + "\n";
  out += ".SH SYNOPSIS\n.B armctl\n.I command\n.RI [ subcommand ]\n.RI [ options ]\n";
  out += ".SH DESCRIPTION\narmctl drives the Hiwonder/LewanSoul xArm (USB HID or serial) and a retrofitted SCARA "
         "arm (joint bus), and simulates both, so that every command runs with no hardware attached: without "
         "\\fB\\-\\-device\\fR a command opens the embedded simulator. Values carry their units (30deg, 120mm, "
         "40mm/s, 2s). Below, every command with its options (each also answers \\fB\\-\\-help\\fR). The README "
         "takes a newcomer from install to a moving arm; the docs folder holds the rest (docs/arm-api.md, "
         "docs/programs.md, docs/http-api.md, docs/ros.md).\n";
  out += ".SH COMMANDS\n";
  for (const auto& c : commands) {
    if (c.path.empty()) continue;
    out += fmt::format(".SS \"armctl {}\"\n{}\n", roff(c.path), roff(c.app->get_description()));
    for (const CLI::Option* o : options_of(*c.app)) {
      const auto names = names_of(*o);
      if (o == c.app->get_help_ptr()) continue;  // said once above
      std::string head = names.empty() ? "\\fI" + roff(o->get_name(true)) + "\\fR" : "\\fB" + roff(joined(names)) + "\\fR";
      if (!names.empty() && o->get_items_expected_min() > 0) head += " \\fI" + roff(o->get_type_name()) + "\\fR";
      out += ".TP\n" + head + "\n" + roff(o->get_description().empty() ? "(no description)" : o->get_description());
      if (o->get_required()) out += " (required)";
      out += "\n";
    }
  }
  out +=
      ".SH EXIT STATUS\n.TP\n0\ndone\n.TP\n1\nfailed (the message on stderr says what was wrong and what is allowed)\n"
      ".TP\n2\na usage error: an unknown command or option, a missing or malformed argument\n"
      ".TP\n128 + N\nended by signal N (130: Ctrl\\-C); a motion under way was stopped first\n";
  out += ".SH FILES\n.TP\n/usr/local/share/armctl\nthe arm files, URDFs and simulator configs (docs/arm-files.md)\n";
  out += ".SH SEE ALSO\nREADME.md and docs/ in armctl's source; \\fBarmctl \\-\\-help\\fR and "
         "\\fBarmctl\\fR \\fIcommand\\fR \\fB\\-\\-help\\fR.\n";
  return out;
}

void add_reference_commands(CLI::App& app) {
  CLI::App* root = &app;
  auto* completion = app.add_subcommand("completion", "Print a shell completion script (bash)");
  completion->require_subcommand(1);
  auto* bash = completion->add_subcommand(
      "bash", "The bash completion script: source <(armctl completion bash), or see `make install`");
  bash->callback([root] { std::cout << bash_completion(*root); });
  auto* manual = app.add_subcommand("manual", "Print armctl's manual page (man format): armctl manual | man -l -");
  manual->callback([root] { std::cout << manual_page(*root, ARMCTL_VERSION); });
}

}  // namespace armctl::cli
