// A table from a name to what that name stands for (a protocol, an arm family, a device
// kind): the one shape of armctl's open seams (docs/architecture.md "How to add an arm, a
// device, an app"). Entries are added, never removed or replaced, so a reference or pointer
// to an entry stays valid for the life of the program. A duplicate name is refused; an
// unknown one is named with every known one ("unknown device kind 'x' (known: hid, serial,
// sim, unix)"). Each table is made, with its built-in entries, the first time it is used:
//
//   NamedRegistry<ArmFamily>& table() {
//     static auto* t = new NamedRegistry<ArmFamily>("arm family", add_builtin);  // used until exit
//     return *t;
//   }
//
// so that no static initialization order, and no linker dropping an unreferenced object file
// of a static library, can lose a built-in entry.
//
// Thread-safe: registration and lookup may run on any thread (a test registers from its own
// files while a server's threads look names up).
#pragma once

#include <deque>
#include <mutex>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <fmt/core.h>

#include "core/error.hpp"

namespace armctl {

template <typename Entry>
class NamedRegistry {
 public:
  // `what` names an entry in errors: "device kind", "protocol", "arm family". `add_builtin`
  // adds the built-in entries (a clash among them is a bug: thrown as an ArmctlError).
  explicit NamedRegistry(std::string what, void (*add_builtin)(NamedRegistry&) = nullptr) : what_(std::move(what)) {
    if (add_builtin) add_builtin(*this);
  }
  NamedRegistry(const NamedRegistry&) = delete;
  NamedRegistry& operator=(const NamedRegistry&) = delete;

  // Adds `entry` under `name`; a name already taken, or empty, is refused (invalid_argument).
  Result<const Entry*> add(std::string name, Entry entry) {
    std::lock_guard lock(mutex_);
    if (name.empty()) return Error{ErrorKind::invalid_argument, fmt::format("a {} needs a name", what_)};
    for (const auto& e : entries_)
      if (e.first == name)
        return Error{ErrorKind::invalid_argument, fmt::format("{} '{}' is already registered", what_, name)};
    entries_.emplace_back(std::move(name), std::move(entry));
    return &entries_.back().second;
  }
  // An entry that carries its own name (`entry.name`).
  Result<const Entry*> add(Entry entry)
    requires requires(const Entry& e) { std::string(e.name); }
  {
    std::string name = entry.name;  // before the entry is moved
    return add(std::move(name), std::move(entry));
  }

  // The entry named `name`, or nullptr.
  const Entry* find(std::string_view name) const {
    std::lock_guard lock(mutex_);
    for (const auto& e : entries_)
      if (e.first == name) return &e.second;
    return nullptr;
  }

  // The entry named `name`, or invalid_argument "unknown <what> 'name' (known: a, b)".
  Result<const Entry*> get(std::string_view name) const {
    if (const Entry* e = find(name)) return e;
    return Error{ErrorKind::invalid_argument, fmt::format("unknown {} '{}' (known: {})", what_, name, known())};
  }

  // Every name, in registration order (the built-in ones first).
  std::vector<std::string> names() const {
    std::lock_guard lock(mutex_);
    std::vector<std::string> out;
    for (const auto& e : entries_) out.push_back(e.first);
    return out;
  }
  // The names as one list for messages: "hid, serial, sim".
  std::string known() const {
    std::string out;
    for (const auto& n : names()) out += (out.empty() ? "" : ", ") + n;
    return out;
  }

 private:
  std::string what_;
  mutable std::mutex mutex_;
  std::deque<std::pair<std::string, Entry>> entries_;  // a deque: entries never move
};

}  // namespace armctl
