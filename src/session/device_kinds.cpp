#include "session/device_kinds.hpp"

#include "core/named_registry.hpp"

namespace armctl::session {

void add_builtin_device_kinds(NamedRegistry<DeviceFactory>& table);  // builtin_device_kinds.cpp

namespace {

NamedRegistry<DeviceFactory>& table() {
  static auto* t = new NamedRegistry<DeviceFactory>("device kind", add_builtin_device_kinds);  // used until exit
  return *t;
}

}  // namespace

Status register_device_kind(std::string kind, DeviceFactory open) {
  if (!open) return Error{ErrorKind::invalid_argument, "a device kind needs a factory"};
  auto added = table().add(std::move(kind), std::move(open));
  if (!added) return added.error();
  return Ok{};
}

Result<const DeviceFactory*> find_device_kind(std::string_view kind) { return table().get(kind); }

}  // namespace armctl::session
