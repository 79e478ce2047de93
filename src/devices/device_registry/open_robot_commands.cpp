// Robot Commands devices: the embedded emulated xArm here, everything else from the SDK.
#include <cstdlib>
#include <mutex>
#include <optional>
#include <utility>

#include "core/debug_log.hpp"
#include "core/error.hpp"
#include "core/miscalibration.hpp"
#include "devices/device_registry/device_registry.hpp"
#include "devices/robot_commands/stream_link.hpp"
#include "devices/xarm_emulator/emulator_runner.hpp"
#include "transport/serial_port.hpp"

namespace armctl::devices {

namespace {

class SdkConnection final : public RcConnection {
 public:
  explicit SdkConnection(std::unique_ptr<robot_commands::RcLink> link) : link_(std::move(link)) {}
  robot_commands::RcLink& link() override { return *link_; }
  bool embedded() const override { return false; }

 private:
  std::unique_ptr<robot_commands::RcLink> link_;
};

// The emulated board serves a pty from a thread of this process and is reached through it
// like a serial board, so the host side runs exactly the code it runs on a real port.
class EmbeddedXarm final : public RcConnection {
 public:
  explicit EmbeddedXarm(std::optional<std::uint32_t> miscal) {
    // Keeps what a real board keeps (action groups, saved offsets, servo limits) in a per-user
    // state directory, so `group download` and a later `group run` meet the same stored group.
    // Servo positions are not stored: every connection starts with the servos at centre.
    // A mis-assembled arm keeps nothing: it must not leave its servo IDs in the user's board.
    xarm::EmulatorRunnerOptions options;
    if (miscal) {
      options.emulator.miscal = make_miscalibration(MiscalArm::xarm, *miscal);
      debug_log("embedded emulated xArm: " + describe(*options.emulator.miscal));
    } else {
      options.emulator.state_dir = embedded_xarm_state_dir().value();
    }
    emulator_ = std::make_unique<xarm::EmulatorRunner>(options, [this](const std::string& line) {
      const std::lock_guard lock(log_mutex_);  // the board runs on the runner's thread
      log_.push_back(line);
    });
    emulator_->start();
    link_ = std::make_unique<robot_commands::StreamLink>(
        transport::SerialPort::open(emulator_->device_path()),
        "embedded emulated xArm on " + emulator_->device_path());
  }
  ~EmbeddedXarm() override {
    link_.reset();
    emulator_->stop();
  }
  robot_commands::RcLink& link() override { return *link_; }
  bool embedded() const override { return true; }
  xarm::EmulatorRunner& runner() { return *emulator_; }
  std::vector<std::string> take_board_log() override {
    const std::lock_guard lock(log_mutex_);
    return std::exchange(log_, {});
  }

 private:
  std::mutex log_mutex_;
  std::vector<std::string> log_;
  std::unique_ptr<xarm::EmulatorRunner> emulator_;
  std::unique_ptr<robot_commands::RcLink> link_;
};

}  // namespace

xarm::EmulatorRunner* embedded_xarm(RcConnection& connection) {
  auto* sim = dynamic_cast<EmbeddedXarm*>(&connection);
  return sim ? &sim->runner() : nullptr;
}

Result<std::filesystem::path> embedded_xarm_state_dir() {
  namespace fs = std::filesystem;
  auto env = [](const char* name) -> std::string {
    const char* v = std::getenv(name);
    return v ? std::string(v) : std::string();
  };
  if (auto dir = env("ARMCTL_STATE_DIR"); !dir.empty()) return fs::path(dir) / "xarm-emulator";
  // XDG base directories: a relative XDG_STATE_HOME is invalid and must be ignored.
  if (auto xdg = env("XDG_STATE_HOME"); !xdg.empty() && fs::path(xdg).is_absolute())
    return fs::path(xdg) / "armctl" / "xarm-emulator";
  if (auto home = env("HOME"); !home.empty())
    return fs::path(home) / ".local" / "state" / "armctl" / "xarm-emulator";
  return Error{ErrorKind::invalid_config,
               "no state directory for the embedded emulated xArm: HOME is not set (set "
               "ARMCTL_STATE_DIR or XDG_STATE_HOME, or use --device)"};
}

Result<std::unique_ptr<RcConnection>> open_robot_commands(const robot_commands::DeviceUri& uri) {
  // Devices are opened by constructors, which throw: this is where that becomes a Result.
  try {
    if (uri.kind == robot_commands::DeviceUri::Kind::sim) {
      return std::unique_ptr<RcConnection>(std::make_unique<EmbeddedXarm>(uri.miscal));
    }
    auto link = robot_commands::open_link(uri);
    if (!link) return link.error();
    return std::unique_ptr<RcConnection>(std::make_unique<SdkConnection>(std::move(link).value()));
  } catch (const ArmctlError& e) {
    return e.error();
  }
}

Result<std::unique_ptr<RcConnection>> open_robot_commands(std::string_view uri) {
  auto parsed = robot_commands::parse_device_uri(std::string(uri));
  if (!parsed) return parsed.error();
  return open_robot_commands(*parsed);
}

}  // namespace armctl::devices
