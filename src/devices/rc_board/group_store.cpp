#include "devices/rc_board/group_store.hpp"

#include <charconv>

#include <fmt/core.h>

#include "core/printable.hpp"
#include "core/atomic_file.hpp"
#include "devices/rc_board/group_file_format.hpp"

namespace armctl::rc_board {
namespace fs = std::filesystem;

namespace {

// "group-NNN.grp" -> NNN, for NNN in 0..254.
std::optional<GroupNumber> group_of(const std::string& name) {
  if (name.size() != 13 || name.rfind("group-", 0) != 0 || name.substr(9) != ".grp")
    return std::nullopt;
  unsigned value = 0;
  auto [p, ec] = std::from_chars(name.data() + 6, name.data() + 9, value);
  if (ec != std::errc{} || p != name.data() + 9 || value >= kGroupCount) return std::nullopt;
  return static_cast<GroupNumber>(value);
}

}  // namespace

GroupStore::GroupStore(fs::path state_dir) : dir_(std::move(state_dir)) {
  std::error_code ec;
  fs::create_directories(*dir_, ec);
  if (ec)
    throw ArmctlError(ErrorKind::io, fmt::format("cannot create state directory {}: {}",
                                                 dir_->string(), ec.message()));
  load_all();
}

GroupStore GroupStore::in_memory() {
  return GroupStore();
}

fs::path GroupStore::file_name(GroupNumber group) {
  return fmt::format("group-{:03}.grp", group);
}

void GroupStore::load_all() {
  std::error_code list_error;  // the listing's own error, apart from each entry's
  for (const auto& entry : fs::directory_iterator(*dir_, list_error)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("group-", 0) != 0) continue;  // other files share the state dir
    if (is_temporary_name(name)) {
      // A save that never reached its rename: the group file itself is intact. In a
      // read-only dir it cannot be removed; that is no reason not to start.
      std::error_code ec;
      fs::remove(entry.path(), ec);
      problems_.push_back(ec ? fmt::format("could not remove unfinished save {}: {}; ignored", printable(name),
                                           ec.message())
                             : fmt::format("removed unfinished save {}", printable(name)));
      continue;
    }
    auto group = group_of(name);
    if (!group) {
      problems_.push_back(fmt::format("{}: not a group file name (group-000.grp .. group-254.grp); skipped",
                                      printable(name)));
      continue;
    }
    // Checked before a byte is read: a directory, a FIFO or a file larger than any group
    // (a sparse 2 GB one) is reported and skipped, never read.
    auto bytes = read_whole_file(entry.path(), kMaxGroupFileBytes);
    if (!bytes) {
      problems_.push_back(fmt::format("{}: {}; skipped", printable(name), bytes.error().message));
      continue;
    }
    if (!bytes.value()) continue;  // vanished meanwhile
    auto decoded = decode_group_file(**bytes, *group);
    if (decoded) {
      groups_[*group] = std::move(decoded).value();
      continue;
    }
    std::error_code ec;
    fs::path quarantine = *dir_ / "quarantine";
    fs::create_directories(quarantine, ec);
    fs::path moved = quarantine / fmt::format("{}.{}", name, problems_.size());
    if (!ec) fs::rename(entry.path(), moved, ec);
    problems_.push_back(fmt::format("{}: {}; {}", name, decoded.error().message,
                                    ec ? "not loaded (could not move it to quarantine: " + ec.message() + ")"
                                       : "moved to " + moved.string()));
  }
  if (list_error)
    throw ArmctlError(ErrorKind::io, fmt::format("cannot read state directory {}: {}",
                                                 printable(dir_->string()), list_error.message()));
}

const ActionGroup* GroupStore::find(GroupNumber group) const {
  auto it = groups_.find(group);
  return it == groups_.end() ? nullptr : &it->second;
}

Status GroupStore::save(GroupNumber group, ActionGroup actions) {
  if (group >= kGroupCount)
    return Error{ErrorKind::invalid_argument, fmt::format("group {} out of range 0..254", group)};
  if (dir_) {
    auto status =
        write_file_atomically(*dir_ / file_name(group), encode_group_file(group, actions));
    if (!status) return status;
  }
  groups_[group] = std::move(actions);
  return Ok{};
}

Status GroupStore::erase(GroupNumber group) {
  if (dir_) {
    auto status = remove_file_durably(*dir_ / file_name(group));
    if (!status) return status;
  }
  groups_.erase(group);
  return Ok{};
}

Status GroupStore::erase_all() {
  while (!groups_.empty()) {
    auto status = erase(groups_.begin()->first);
    if (!status) return status;
  }
  return Ok{};
}

}  // namespace armctl::rc_board
