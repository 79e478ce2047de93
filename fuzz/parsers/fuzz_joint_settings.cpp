// The arm controller's persisted settings (devices/arm_controller/joint_settings.hpp) on
// hostile input: the file sits in --state-dir and may be hand-edited or corrupt. Byte 0
// chooses the mode: even = the rest is the file's text; odd = the rest chooses edits
// (json_edits.hpp) to a file save_settings wrote. The parser must return invalid_config
// naming the source, or settings whose every value is one the controller accepts, for
// exactly the arm's joints, that save_settings writes and parse_settings reads back equal.
#include <stdlib.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>
#include <system_error>

#include "core/error.hpp"
#include "devices/arm_controller/joint_settings.hpp"
#include "json_edits.hpp"

namespace {

using armctl::arm_controller::ControllerSettings;

void check(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "fuzz_joint_settings: accepted settings break: %s\n", what);
  std::abort();
}

// The SCARA arm's joints 1..7, as the import of an old state dir starts them before loading.
const ControllerSettings& defaults() {
  static const ControllerSettings d = [] {
    ControllerSettings s;
    for (int n = 1; n <= 7; ++n) {
      armctl::arm_controller::JointSettings js;
      js.limits.servo = static_cast<std::uint8_t>(n);
      s.joints[n] = js;
    }
    return s;
  }();
  return d;
}

// Where the round trip writes; removed when the fuzzer exits.
struct StateDir {
  StateDir() {
    char tmpl[] = "/tmp/armctl-fuzz-joint-settings-XXXXXX";
    const char* made = ::mkdtemp(tmpl);
    check(made != nullptr, "mkdtemp for the round trip");
    path = made;
  }
  ~StateDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  std::filesystem::path path;
};

const std::filesystem::path& state_dir() {
  static const StateDir dir;
  return dir.path;
}

std::string saved_text(const ControllerSettings& s) {
  check(armctl::arm_controller::save_settings(state_dir(), s).ok(), "save_settings writes");
  return armctl::fuzz::read_text_file(armctl::arm_controller::settings_path(state_dir()).string());
}

// Not the defaults: offsets and limits away from their defaults, so edits hit real values.
const std::string& base_text() {
  static const std::string text = [] {
    ControllerSettings s = defaults();
    s.info_joint = 3;
    s.joints[2].saved_offset = -40;
    s.joints[3].limits.position_min = 100;
    s.joints[3].limits.position_max = 900;
    s.joints[3].limits.millivolts_min = 6000;
    s.joints[3].limits.temp_max = 60;
    s.joints[3].limits.led_warning = 5;
    return saved_text(s);
  }();
  return text;
}

void check_settings(const ControllerSettings& s) {
  check(s.joints.size() == defaults().joints.size(), "exactly the arm's joints");
  check(s.joints.count(s.info_joint) == 1, "info_joint is a joint of the arm");
  for (const auto& [number, js] : s.joints) {
    check(defaults().joints.count(number) == 1, "joint numbers of the arm only");
    const auto& l = js.limits;
    check(l.servo == number, "limits.servo is the joint's number");
    check(js.saved_offset >= -125 && js.saved_offset <= 125, "saved_offset -125..125");
    check(l.position_min <= l.position_max && l.position_max <= 1000, "positions 0 <= min <= max <= 1000");
    check(l.millivolts_min >= 4500 && l.millivolts_min <= l.millivolts_max && l.millivolts_max <= 12000,
          "millivolts 4500 <= min <= max <= 12000");
    check(l.temp_max >= 50 && l.temp_max <= 100, "temp_max 50..100");
    check(l.led_status <= 1, "led_status 0..1");
    check(l.led_warning <= 7, "led_warning 0..7");
  }
  auto again = armctl::arm_controller::parse_settings(saved_text(s), "again.json", defaults());
  check(again.ok(), "what save_settings writes parses");
  check(*again == s, "save -> parse round trip");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string text = armctl::fuzz::config_text_from(data, size, base_text());
  auto r = armctl::arm_controller::parse_settings(text, "fuzz.json", defaults());
  if (r.ok()) {
    check_settings(*r);
  } else {
    check(r.error().kind == armctl::ErrorKind::invalid_config, "error kind is invalid_config");
    check(std::string_view(r.error().message).substr(0, 10) == "fuzz.json:", "error message names the source");
  }
  // Any exception escapes and libFuzzer reports it as a crash.
  return 0;
}
