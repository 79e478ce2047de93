// Seven scripted joints behind a BusPort, byte for byte: READY on select rise, RESPONSE
// after COMMAND (and DATA), STATUS after select falls. Bytes are queued and handed to the
// master by pump(), never from inside a master call. A joint can be made silent, or to
// answer with another number. Also: a recorder of what the core sends upstream.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "portable/joint_bus_codes.hpp"
#include "portable/setpoint_ramp.hpp"
#include "portable_controller/bus_master.hpp"
#include "portable_controller/controller_core.hpp"

namespace armctl::controller::testing {

struct SentCommand {
  int joint;
  int command;
  int data;
};

class FakeJoints final : public BusPort {
 public:
  void set_select(std::uint8_t joint, bool high) override {
    if (high) {
      selected_ = joint;
      received_.clear();
      if (!silent(joint)) queue_word(ready_word(joint));
      return;
    }
    if (selected_ == joint && !silent(joint) && pending_status_) queue_word(*pending_status_);
    pending_status_.reset();
    selected_ = 0;
  }
  void send_byte(std::uint8_t byte) override {
    if (selected_ == 0 || silent(selected_)) return;
    received_.push_back(byte);
    if (received_.size() < 2) return;
    const auto command = joint_bus::word_from(received_[0], received_[1]);
    const auto shape = joint_bus::command_shape(command);
    if (shape.takes_data && received_.size() < 4) return;
    const int data = shape.takes_data ? joint_bus::word_from(received_[2], received_[3]) : 0;
    const int j = selected_;
    log.push_back(SentCommand{j, command, data});
    std::int16_t response = 0;
    if (command == joint_bus::cmd_get_position) response = position[j];
    // Instant, for these tests (or never: a joint whose polls lag behind its motion), or
    // through the joint's own setpoint ramp (ramps_from()).
    if (command == joint_bus::cmd_drive_to && drives_move && !ramping_ && !refuses_drives[j] && !stuck[j])
      position[j] = static_cast<std::int16_t>(data);
    if (ramping_ && command == joint_bus::cmd_drive_to && !refuses_drives[j]) target_q8_[j] = std::int32_t{data} * 256;
    if (ramping_ && command == joint_bus::cmd_set_speed) ramp_[j].set_speed_percent(static_cast<std::uint8_t>(data));
    if (command == joint_bus::cmd_ping) response = static_cast<std::int16_t>(data);
    if (command == joint_bus::cmd_clear_faults) {  // faults := 0, holds where it is
      refuses_drives[j] = false;
      diagnostics[j][joint_bus::diagnostic_faults] = 0;
      target_q8_[j] = std::int32_t{position[j]} * 256;
    }
    if (command == joint_bus::cmd_read_diagnostic && data >= 0 && data < joint_bus::diagnostic_count)
      response = diagnostics[j][data];
    if (shape.returns_value) queue_word(response);
    pending_status_ = joint_bus::success_status(command);
    // A joint holding a fault refuses every drive (its target follows its position).
    if (refuses_drives[j] && command == joint_bus::cmd_drive_to) pending_status_ = joint_bus::status_bad_data;
    received_.clear();
  }
  // Hands every queued byte to `sink` (the master or the core).
  template <typename Sink>
  void pump(Sink&& sink) {
    while (!wire_.empty()) {
      const std::uint8_t b = wire_.front();
      wire_.pop_front();
      sink(b);
    }
  }
  std::vector<SentCommand> commands_of(int command) const {
    std::vector<SentCommand> out;
    for (const auto& c : log)
      if (c.command == command) out.push_back(c);
    return out;
  }
  // Every drive_to sent to a joint of `setup` was within its soft limits.
  bool drives_within_soft_limits(const JointSetup* setup, int count) const {
    for (const auto& c : log) {
      if (c.command != joint_bus::cmd_drive_to) continue;
      for (int i = 0; i < count; ++i)
        if (setup[i].number == c.joint && (c.data < setup[i].soft_min || c.data > setup[i].soft_max)) return false;
    }
    return true;
  }

  // From now on each joint runs its setpoint ramp as the joint firmware does (1 ms ticks,
  // the joint's limits from `setup`), at rest where it is, and tracks it exactly: its
  // position is its setpoint. Time moves with advance_to().
  void ramps_from(const JointSetup* setup, int count, std::uint32_t now_us) {
    ramping_ = true;
    tick_us_ = now_us;
    for (int i = 0; i < count && i < 7; ++i) {
      const int j = setup[i].number;
      ramp_[j].configure((std::int32_t{setup[i].max_speed_cps} * 32 + 62) / 125,
                         (static_cast<std::int32_t>(setup[i].max_accel_cps2) * 32 + 62500) / 125000);
      ramp_[j].set_speed_percent(0);
      ramp_[j].reset(std::int32_t{position[j]} * 256);
      target_q8_[j] = std::int32_t{position[j]} * 256;
    }
  }
  void advance_to(std::uint32_t now_us) {
    if (!ramping_) return;
    while (static_cast<std::int32_t>(now_us - (tick_us_ + 1000)) >= 0) {
      tick_us_ += 1000;
      for (int j = 1; j < 8; ++j) {
        if (stuck[j]) continue;
        const std::int32_t q8 = ramp_[j].step(target_q8_[j]);
        position[j] = static_cast<std::int16_t>(q8 >= 0 ? (q8 + 128) / 256 : -((-q8 + 128) / 256));
      }
    }
  }

  std::int16_t position[8] = {};
  bool dead[8] = {};
  int answers_as[8] = {};  // != 0: READY says this number instead
  bool drives_move = true;
  bool refuses_drives[8] = {};
  bool stuck[8] = {};  // blocked: its drives never move it (its STATUS says success)
  std::int16_t diagnostics[8][joint_bus::diagnostic_count] = {};
  std::vector<SentCommand> log;

 private:
  bool silent(int joint) const { return dead[joint]; }
  int ready_word(int joint) const { return answers_as[joint] != 0 ? answers_as[joint] : joint; }
  void queue_word(int word) {
    wire_.push_back(joint_bus::word_low(static_cast<std::int16_t>(word)));
    wire_.push_back(joint_bus::word_high(static_cast<std::int16_t>(word)));
  }
  bool ramping_ = false;
  std::uint32_t tick_us_ = 0;
  joint_bus::SetpointRamp ramp_[8];
  std::int32_t target_q8_[8] = {};
  int selected_ = 0;
  std::vector<std::uint8_t> received_;
  std::optional<std::int16_t> pending_status_;
  std::deque<std::uint8_t> wire_;
};

// What the core sent upstream, frame by frame.
struct SentFrame {
  int command;
  std::vector<std::uint8_t> data;
};

class RecordingUpstream final : public UpstreamPort {
 public:
  void send_frame(std::uint8_t command, const std::uint8_t* data, std::uint8_t length) override {
    frames.push_back(SentFrame{command, {data, data + length}});
  }
  std::vector<SentFrame> frames;
};

// Runs `core` against `joints` from `now` for `us`, a main-loop pass every `step_us`: the
// joints' bytes in, then the core's bus work (as firmware/mega/main.cpp does).
inline void run_core(ControllerCore& core, FakeJoints& joints, std::uint32_t& now, std::uint32_t us,
                     std::uint32_t step_us) {
  const std::uint32_t end = now + us;
  while (static_cast<std::int32_t>(now - end) < 0) {
    joints.advance_to(now);
    joints.pump([&](std::uint8_t b) { core.on_bus_byte(b, now); });
    core.poll(now);
    now += step_us;
  }
}

}  // namespace armctl::controller::testing
