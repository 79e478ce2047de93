// Stored action groups. With a state directory every change is written crash-safely
// (atomic_file.hpp): a kill -9 at any instant leaves each group either as it was or as
// newly saved. Without one (in_memory) groups live only as long as the object (fuzzing,
// tests, boards that must not touch the disk).
//
// Loading validates every file; a corrupt one is moved to "<dir>/quarantine/" (kept for a
// person to inspect, never loaded) and reported in problems(); stray temporary files from
// an interrupted save are deleted.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "devices/rc_board/action_group.hpp"

namespace armctl::rc_board {

class GroupStore {
 public:
  // Creates the directory if needed and loads every group in it. Throws ArmctlError(io)
  // if the directory cannot be created or read.
  explicit GroupStore(std::filesystem::path state_dir);
  static GroupStore in_memory();

  const ActionGroup* find(GroupNumber group) const;
  // Durable before it returns Ok; on error the stored group is unchanged.
  Status save(GroupNumber group, ActionGroup actions);
  Status erase(GroupNumber group);
  Status erase_all();

  std::size_t size() const { return groups_.size(); }
  // What loading found wrong (quarantined files, removed temporary files).
  const std::vector<std::string>& problems() const { return problems_; }
  static std::filesystem::path file_name(GroupNumber group);

 private:
  GroupStore() = default;
  void load_all();

  std::optional<std::filesystem::path> dir_;
  std::map<GroupNumber, ActionGroup> groups_;
  std::vector<std::string> problems_;
};

}  // namespace armctl::rc_board
