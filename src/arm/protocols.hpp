// The protocols an arm can be driven through, by name: the keys of a joint's device maps in
// an arm file ("robot_commands", "joint_bus", or one added with register_protocol), with
// what each map holds (the ID's key and range, the device values' range, any extra keys).
// An open table (core/named_registry.hpp): a new transport adds its protocol here, from its
// own files, without editing this one (docs/architecture.md "How to add a device").
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.hpp"
#include "core/json_reader.hpp"

namespace armctl::arm {

struct DeviceMap;

// A protocol, by its name. The names of the built-in ones are spelled Protocol::robot_commands
// and Protocol::joint_bus; any other comes from find_protocol, so its name lives in the table.
class Protocol {
 public:
  static const Protocol robot_commands;
  static const Protocol joint_bus;
  // Only for names with static storage (a literal, or the table's own copy).
  constexpr explicit Protocol(std::string_view name) : name_(name) {}
  constexpr std::string_view name() const { return name_; }
  friend constexpr bool operator==(Protocol a, Protocol b) { return a.name_ == b.name_; }

 private:
  std::string_view name_;
};
inline constexpr Protocol Protocol::robot_commands{"robot_commands"};
inline constexpr Protocol Protocol::joint_bus{"joint_bus"};
std::string to_string(Protocol p);

// The smallest and largest value a protocol can carry for one joint.
struct DeviceRange {
  double min, max;
};

struct ProtocolInfo {
  std::string name;       // the arm file's key for a joint's map: "robot_commands"
  std::string id_key;     // the map's key for the joint's ID on the device: "servo", "number"
  int max_id = 1;         // IDs are 1..max_id
  DeviceRange range{0, 0};
  std::string raw_unit;   // device values as people read them: "servo units", "counts"
  // Reads the map's keys beyond id, device and joint (the joint bus's tuning); fails
  // through the reader (invalid_config naming the key). Empty: no other keys.
  std::function<void(json_reader::ObjectReader&, DeviceMap&)> read_extras;
};

// Adds a protocol (invalid_argument if its name is taken, or its range or IDs are empty).
// The built-in ones (robot_commands, joint_bus) are there from the start.
Status register_protocol(ProtocolInfo info);
// The protocol named `name`, or invalid_argument "unknown protocol 'x' (known: ...)".
Result<Protocol> find_protocol(std::string_view name);
// What `p` is; `p` must be registered (a built-in, or from find_protocol).
const ProtocolInfo& protocol_info(Protocol p);
DeviceRange device_range(Protocol p);
// Every protocol, built-in ones first.
std::vector<Protocol> protocols();

}  // namespace armctl::arm
