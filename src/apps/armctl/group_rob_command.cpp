// armctl xarm group import FILE.rob [--out FILE] [--group N] and
// armctl xarm group export GROUPFILE --out FILE.rob: the xArm maker's PC-software action
// files to and from our group files (files/rob_file.hpp, docs/teach.md ".rob files").
#include <cstdio>
#include <memory>
#include <string>

#include <fmt/core.h>

#include "core/atomic_file.hpp"

#include "apps/armctl/commands.hpp"
#include "apps/armctl/xarm_args.hpp"
#include "session/xarm_session.hpp"
#include "core/error.hpp"
#include "core/must.hpp"
#include "files/action_group_file.hpp"
#include "files/rob_file.hpp"

namespace armctl::cli {

namespace {

struct RobArgs {
  std::string file;
  std::string out;
  std::string group;
};


void write_file(const std::string& path, const void* data, std::size_t size) {
  // Crash-safe: the old file or the new one, never a mix.
  must(write_file_atomically(path, std::span(static_cast<const std::uint8_t*>(data), size)));
}

void run_import(const RobArgs& a, const XarmDeviceOptions& d) {
  const auto group = must(files::read_rob_file(a.file));
  const std::string text = files::format_action_group(group);
  if (a.out.empty() && a.group.empty()) {
    fmt::print("{}", text);
    return;
  }
  if (!a.out.empty()) {
    write_file(a.out, text.data(), text.size());
    fmt::print("{}: {} actions written to {}\n", a.file, group.actions.size(), a.out);
  }
  if (!a.group.empty()) {
    const auto number = xarm_args::parse_group(a.group, false);
    auto s = session::open_xarm_session(*d.device, *d.servo_count, *d.timeout_ms).value();
    if (auto st = s->client->download_group(number, group.actions); !st) throw ArmctlError(st.error());
    fmt::print("group {}: {} actions downloaded\n", number, group.actions.size());
  }
}

void run_export(const RobArgs& a) {
  const auto group = must(files::read_action_group_file(a.file));
  const auto bytes = must(files::format_rob_file(group));
  write_file(a.out, bytes.data(), bytes.size());
  fmt::print("{}: {} actions written to {} ({} bytes)\n", a.file, group.actions.size(), a.out, bytes.size());
}

}  // namespace

void add_group_rob_commands(CLI::App& group, const XarmDeviceOptions& device) {
  auto a = std::make_shared<RobArgs>();
  auto* im = group.add_subcommand("import", "Convert a .rob action file of the maker's PC software (docs/teach.md)");
  im->add_option("file", a->file, ".rob file")->required();
  im->add_option("--out", a->out, "Group file to write (default: print it)");
  im->add_option("--group", a->group, "Also download it as this group number 0..254");
  im->callback([a, device] { run_import(*a, device); });
  auto* ex = group.add_subcommand("export", "Convert a group file (servos 1..6, no keep) to a .rob action file");
  ex->add_option("file", a->file, "Group file")->required();
  ex->add_option("--out", a->out, ".rob file to write")->required();
  ex->callback([a] { run_export(*a); });
}

}  // namespace armctl::cli
