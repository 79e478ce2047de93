// The arm controller on Linux: the portable core, the same code the Mega controller runs
// (portable_controller/controller_core.hpp, docs/mega-controller.md), with Robot Commands
// frames in, joint bus transactions out through a transport::JointBusLink, and its group
// memory (action groups, the joints' saved settings) as a file in the state dir. What
// `armctl controller` and `armctl sim scara --robot-commands` serve (docs/arm-controller.md).
// This layer adds what Linux has and the Mega has not: a log of what happened, a bus link
// that can be lost and comes back, and the import of a state dir the earlier (non-core)
// implementation kept.
//
// Single-threaded and clock-driven: on a simulated bus (SimClock) tests call run_until() and
// every transaction happens at an exact simulated instant.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "devices/arm_controller/controller_config.hpp"
#include "devices/arm_controller/core_ports.hpp"
#include "devices/arm_controller/daemon_state_import.hpp"
#include "portable_controller/controller_core.hpp"
#include "portable_controller/rc_frame_reader.hpp"
#include "protocol/robot_commands/frame.hpp"

namespace armctl::arm_controller {

struct CoreDeviceOptions {
  // The group memory is kept here as core-memory.bin; nothing = in memory only.
  std::optional<std::filesystem::path> state_dir;
  // Measured supply voltage; empty = the config's supply_millivolts.
  std::function<std::uint16_t()> supply_millivolts;
  std::function<void(const std::string&)> log;
  // How many times the bus link has been lost so far (ReconnectingLink::losses); empty for
  // a link that cannot be lost. On each new loss playback and every queued command end and
  // every joint counts as not answering until it answers again (ControllerCore::link_lost).
  std::function<std::uint64_t()> link_losses;
};

class CoreDevice {
 public:
  using Output = std::function<void(const rc::Frame&)>;
  static constexpr const char* memory_file = "core-memory.bin";
  // Every group number the spec has (0..254), each as large as it allows (1,020 actions of
  // seven joints): what the daemon's group files held. 5.98 MB (the Mega: 16 groups in 4 KiB).
  static constexpr std::uint8_t group_entries = 255;
  static constexpr std::uint32_t memory_size =
      controller::GroupStore::directory_at + 8u * group_entries +
      255u * 1020u * controller::GroupStore::action_bytes(7) + controller::ControllerCore::settings_bytes;

  // Throws ArmctlError: a config the core cannot hold (invalid_config), a configured joint
  // without a select line on the link (invalid_config), an unusable state dir (io). Then
  // halts every joint and polls each once (or until 2 s pass), as the Mega does at reset.
  CoreDevice(transport::JointBusLink& link, ControllerConfig config, CoreDeviceOptions options, Output output);

  // Bytes from the host (Robot Commands, serial form), as they arrived.
  void receive(std::span<const std::uint8_t> bytes);
  // A whole frame (tests): as if its bytes had arrived.
  void handle(const rc::Frame& frame);
  // One pass of the core's loop: a poll, then the bus's next byte or a short wait (at most
  // until `limit`).
  void step(TimePoint limit);
  void run_until(TimePoint t);
  void run_for(Duration d) { run_until(clock().now() + d); }
  const Clock& clock() const { return link_.clock(); }
  // Where replies and notifications go from now on; returns where they went (the import of
  // an old state dir talks to the core itself for a moment: daemon_state_import.hpp).
  Output swap_output(Output output) { return upstream_.swap(std::move(output)); }

  // ---- inspection (tests, the serve log)
  const controller::ControllerCore& core() const { return core_; }
  const ControllerConfig& config() const { return config_; }
  const controller::JointState& joint_state(int joint) const {
    return core_.joint_state(static_cast<std::uint8_t>(joint));
  }
  std::uint16_t torn_frames() const { return reader_.torn_frames(); }

 private:
  // Every frame the core sends is seen by `watch` (the log), then goes to `out`.
  class Upstream final : public controller::UpstreamPort {
   public:
    Upstream(Output out, Output watch) : out_(std::move(out)), watch_(std::move(watch)) {}
    void send_frame(std::uint8_t command, const std::uint8_t* data, std::uint8_t length) override;
    Output swap(Output out) { return std::exchange(out_, std::move(out)); }

   private:
    Output out_;
    Output watch_;
  };
  // What the log has said of each joint, so it says each change once.
  struct Seen {
    bool answering = false;
    std::uint16_t following_lost = 0;
    bool diagnostics_read = false;
    std::uint16_t faults = 0;  // diagnostics[0] when last read
    static Seen of(const controller::JointState& s) {
      return Seen{s.answering, s.following_lost, s.diagnostics_read, s.diagnostics[0]};
    }
  };
  std::uint32_t now_us() const;
  // A whole frame to the core, and what became of it in the log.
  void take(const rc::Frame& frame);
  void explain(const rc::Frame& frame, const controller::CoreStats& before) const;
  // A reply worth a log line (JointFaultClear's).
  void watch(const rc::Frame& frame) const;
  void note_changes();
  void log(const std::string& line) const;

  transport::JointBusLink& link_;
  ControllerConfig config_;
  CoreDeviceOptions options_;
  std::vector<controller::JointSetup> joints_;
  LinkBusPort port_;
  Upstream upstream_;
  std::optional<DaemonState> to_import_;  // read before memory_ creates its file
  FileGroupMemory memory_;
  std::vector<controller::GroupStore::Entry> directory_;
  controller::ControllerCore core_;
  controller::RcFrameReader reader_;
  std::vector<Seen> seen_;
  std::uint64_t losses_seen_ = 0;
  std::uint16_t actions_skipped_seen_ = 0;
  bool started_ = false;
};

}  // namespace armctl::arm_controller
