// One file per arm: the arm file (docs/arm-files.md) holds what the Arm API needs (URDF,
// limits, device mappings) and a section for each box that runs the arm, read by that box:
// "simulator" (the simulated SCARA's hardware, devices/joint_sim) and "arm_controller" (the
// controller's maps and soft limits, devices/arm_controller). A value the boxes share (a
// joint's name, its number on the joint bus, its velocity and acceleration limits in clicks)
// is written once, in the joint's own entry, and read from there by every box; before, three
// files repeated them and had to agree (config/scara.json, config/scara-arm.json).
//
// In core because the devices below the arm layer read these parts, and the arm layer
// (arm/arm_model.cpp) checks the whole file; errors are ArmctlError(invalid_config) naming the
// file and the key path, as json_reader's.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.hpp"
#include "core/json_reader.hpp"
#include "core/printable.hpp"

namespace armctl::arm_file {

// The files that became sections of config/scara.arm.json, and the sections.
inline constexpr std::string_view kScaraArmFile = "scara.arm.json";
inline constexpr std::string_view kSimulatorSection = "simulator";
inline constexpr std::string_view kControllerSection = "arm_controller";

// An arm file, as opposed to a simulator or controller config of the old form: it names the
// arm's kinematic family and URDF.
bool is_arm_file(const json_reader::json& root);
// The same for the file at `path`; true when it cannot be read as JSON (its loader then says
// why, as for any arm file).
bool is_arm_file(const std::filesystem::path& path);

// One joint of the arm file with a joint-bus mapping, as every box sees it.
struct BusJoint {
  std::string name;             // joints[i].name
  int number = 0;               // joints[i].joint_bus.number
  double max_speed_cps = 0;     // joints[i].joint_bus.max_speed_cps
  double max_accel_cps2 = 0;    // joints[i].joint_bus.max_accel_cps2
  std::string bus_path;         // "joints[2].joint_bus", for errors about the values above
  const json_reader::json* entry = nullptr;  // this joint's entry in the section's "joints"; nullptr if none
  std::string path;             // that entry's key path: "simulator.joints.Z"
};

// The section `section` of the arm file `root` (an object: refused otherwise, or when
// missing) and its joints: every arm joint with a joint-bus mapping, in the file's order,
// each with its entry in the section's "joints" object (keyed by joint name; a name no joint
// has is refused). Only the keys read here are checked; arm/arm_model.cpp checks the rest.
struct Section {
  const json_reader::json* object = nullptr;
  std::string path;  // "simulator"
  std::vector<BusJoint> joints;
};
Section read_section(const json_reader::json& root, std::string_view section, const std::string& source);

// A box's config from a document: `read(object, source, path, joints)` on the box's section
// `section` of the arm file `doc` (path "simulator", joints the arm's), or on `doc` itself
// (path "", joints null) when it is a config of the old form. What each box's parser is made
// of: parse_box_config on text, load_box_config on a file.
template <typename Read>
auto read_box_config(const json_reader::json& doc, std::string_view section, const std::string& source, Read&& read) {
  if (!doc.is_object())
    throw ArmctlError(ErrorKind::invalid_config, printable(source) + ": expected a JSON object at the top");
  if (is_arm_file(doc)) {
    const Section s = read_section(doc, section, source);
    return read(*s.object, source, s.path, &s.joints);
  }
  return read(doc, source, std::string(), static_cast<const std::vector<BusJoint>*>(nullptr));
}

template <typename Read>
auto parse_box_config(std::string_view text, std::string_view section, const std::string& source, Read&& read) {
  return read_box_config(json_reader::parse_document(text, source), section, source, read);
}

// The document of the config file `asked` for the box whose section is `section`, `what`
// naming it in errors ("simulator config"): moved_config_file, then read_config_file; a file
// of the old form (not an arm file) is read with a warning. `*path` is the file read.
json_reader::json load_box_document(const std::filesystem::path& asked, std::string_view section, std::string_view what,
                                    std::filesystem::path* path);

template <typename Read>
auto load_box_config(const std::filesystem::path& asked, std::string_view section, std::string_view what, Read&& read) {
  std::filesystem::path path;
  const json_reader::json doc = load_box_document(asked, section, what, &path);
  return read_box_config(doc, section, path.string(), read);
}

// The file to read for `path`, asked for as `what` ("simulator config"): `path` itself, or,
// when `path` names one of the files that became sections of the SCARA's arm file
// (scara.json, scara-arm.json) and that file is not there but the arm file is beside it (as
// in config/ and the installed share/armctl), that arm file, with a warning on stderr naming
// it and the section.
std::filesystem::path moved_config_file(const std::filesystem::path& path);

// "armctl: warning: <message>" on stderr (through printable()), each message once per process: a file or an option
// of an old form still works, and says once what replaces it.
void warn_once(const std::string& message);

}  // namespace armctl::arm_file
