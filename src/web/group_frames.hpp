// Action groups as the API carries them (docs/http-api.md "Action groups"): frames of
// {"time_ms", "positions": {"<joint name>": deg or mm}} <-> the group files' servo actions
// (files/action_group_file.hpp) through the arm's Robot Commands map. A joint a frame leaves
// out is kept where it is ("keep"). Every frame is validated before anything is returned,
// so nothing is sent for a group with one bad frame. Pure code; errors are ApiError 400
// naming the frame and the field.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "arm/arm_model.hpp"
#include "files/action_group_file.hpp"

namespace armctl::web {

struct GroupFrames {
  files::ActionGroupFile group;
  // Per frame, the joint targets it names (SI), for Arm::check_targets.
  std::vector<std::vector<std::optional<double>>> targets;
};

GroupFrames frames_to_group(const arm::ArmModel& model, const nlohmann::json& frames);
nlohmann::json group_to_frames(const arm::ArmModel& model, const files::ActionGroupFile& group);

// A group number from the URL: 0..254.
std::uint8_t parse_group_number(std::string_view text);
// POST /api/v1/groups/<n>/run: times to play it, 0 = continuous.
std::uint16_t parse_group_run(const nlohmann::json& body);
// POST /api/v1/groups/speed: percent 1..1000.
std::uint16_t parse_group_speed(const nlohmann::json& body);

// POST /api/v1/groups/import: a group file's text or a .rob file's base64 -> the group.
files::ActionGroupFile parse_group_import(const nlohmann::json& body);
// POST /api/v1/groups/export: frames -> the group file's text or the .rob file's base64.
nlohmann::json export_group(const arm::ArmModel& model, const nlohmann::json& body);

}  // namespace armctl::web
