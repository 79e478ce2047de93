#include "portable/joint_controller.hpp"

#include "portable/fixed_point.hpp"

namespace armctl {
namespace joint_bus {

namespace {
CommandResult success(int16_t command) { return CommandResult{success_status(command), false, 0}; }

CommandResult answer(int16_t command, int16_t value) {
  return CommandResult{success_status(command), true, value};
}

const CommandResult kBadData = CommandResult{status_bad_data, false, 0};

bool fits_int16(int32_t v) { return v >= -32768 && v <= 32767; }
}  // namespace

bool JointController::begin(uint8_t joint_number, const JointTuning& tuning, uint32_t baud,
                            const JointOptions& options) {
  configured_ = joint_number >= 1 && joint_number <= max_joints && baud != 0;
  options_ = options;
  settings_ = static_cast<uint8_t>((options.polarity == MotorPolarity::reversed ? setting_motor_reversed : 0) |
                                   (options.legacy_master ? setting_legacy_master : 0));
  faults_ = 0;
  monitor_.reset();
  joint_number_ = joint_number;
  decoder_.set_count(0);
  sampled_count_ = 0;
  decoder_.clear_errors();
  loop_.begin(tuning, 0);
  if (!configured_) loop_.set_enabled(false, 0);
  transaction_.begin(static_cast<int16_t>(joint_number), baud, options.legacy_master,
                     options.legacy_master ? legacy_status_unknown_command : int16_t{status_unknown_command});
  last_output_ = DriveOutput{0, false};
  return configured_;
}

void JointController::on_rx_byte(uint8_t byte, uint32_t now_us) {
  if (!configured_) return;
  if (transaction_.on_rx_byte(byte, now_us) != BusTransaction::Event::command_ready) return;
  const int16_t command = transaction_.command();
  int16_t data = transaction_.data();
  const bool legacy = options_.legacy_master;
  // Legacy dialect: set_speed is 0..255 (scaled to 0..100 %, rounded up so that only 0
  // stops), STATUS is the command code on success, 93 unknown, 94 bad data.
  if (legacy && command == cmd_set_speed) {
    data = static_cast<uint16_t>(data) > 255u ? int16_t{-1}
                                    : static_cast<int16_t>((static_cast<uint16_t>(data) * 100u + 255u) >> 8);
  }
  const CommandResult r = execute(command, data);
  int16_t status = r.status;
  if (legacy) {
    status = command;
    if (r.status == status_bad_data) status = legacy_status_bad_data;
    if (r.status == status_unknown_command) status = legacy_status_unknown_command;
  }
  transaction_.complete(status, r.has_response, r.response);
}

DriveOutput JointController::control_compute() {
  if (!configured_) return DriveOutput{0, false};
  DriveOutput out = DriveOutput{0, false};
  if (faults_ == 0) {
    out = loop_.tick(sampled_count_);
    if (!out.enable) {
      monitor_.reset();
    } else {
      const int16_t raised = monitor_.tick(loop_.error_q8(), static_cast<uint16_t>(sampled_count_), out.duty);
      if (raised != 0) {
        faults_ = raised;
        brake_ticks_ = fault_brake_ticks;
      }
    }
  }
  if (faults_ != 0) {
    // Brake first (bridge on, both inputs LOW: the motor's own back-EMF stops it within
    // tens of ms), then bridge off: a heavy joint left to coast would roll on for seconds.
    loop_.hold(sampled_count_);
    out = DriveOutput{0, brake_ticks_ != 0};
    if (brake_ticks_ != 0) --brake_ticks_;
  }
  if (options_.polarity == MotorPolarity::reversed) out.duty = static_cast<int16_t>(-out.duty);
  last_output_ = out;
  return out;
}

int16_t JointController::diagnostic(int16_t index) const {
  // Counters go out as unsigned 16-bit words (they saturate, never wrap; the decoder's
  // count stops at 65535, the board's at 255).
  if (index == diagnostic_faults) return faults_;
  if (index == diagnostic_abandoned) return static_cast<int16_t>(transaction_.abandoned_count());
  if (index == diagnostic_settings) return settings_;
  uint16_t word = board_.counts[index - diagnostic_bus_events_lost];
  if (index == diagnostic_encoder_edges_lost) word = static_cast<uint16_t>(word + decoder_.errors());
  return static_cast<int16_t>(word);
}

// Out of line: get_position and the RESPONSE a board sends ahead share it (flash).
__attribute__((noinline)) int16_t JointController::position() const { return saturate_to_int16(decoder_.count()); }

CommandResult JointController::execute(int16_t command, int16_t data) {
  // Every branch validates first and changes state last, so a rejected command leaves
  // every value as it was (spec: state changes are atomic).
  // The count is clamped before arithmetic so that count + data cannot overflow int32.
  const int32_t count = clamp32(decoder_.count(), -INT32_C(0x200000), INT32_C(0x200000));
  switch (command) {
    case cmd_ping: return answer(command, data);
    case cmd_home:
      decoder_.set_count(0);
      sampled_count_ = 0;  // a sample taken before home must not reach the homed loop
      loop_.home();
      return success(command);
    case cmd_set_pid_state:
      if (data != 0 && data != 1) return kBadData;
      loop_.set_enabled(data == 1, count);
      return success(command);
    case cmd_get_position: return answer(command, position());
    case cmd_get_target: return answer(command, loop_.target());
    case cmd_get_joint_number: return answer(command, static_cast<int16_t>(joint_number_));
    case cmd_drive_dist:
    case cmd_drive_dist_max:
    case cmd_drive_to: {
      // A held fault keeps the bridge off: a new target would only be overwritten by the
      // position. Refused as a whole, nothing changes (read_diagnostic tells why).
      if (faults_ != 0) return kBadData;
      int32_t next = data;
      if (command == cmd_drive_dist) next += loop_.target();
      if (command == cmd_drive_dist_max) next += count;
      if (!fits_int16(next)) return kBadData;
      loop_.set_target(static_cast<int16_t>(next));
      return success(command);
    }
    case cmd_set_speed:
      if (data < 0 || data > 100) return kBadData;
      loop_.set_speed_percent(static_cast<uint8_t>(data));
      return success(command);
    case cmd_set_zone:
      if (data < 0) return kBadData;
      loop_.set_zone(data);
      return success(command);
    case cmd_check_target_reached: return answer(command, loop_.target_reached(count) ? 1 : 0);
    case cmd_read_diagnostic:
      // Refused, it still sends its RESPONSE word (0): the transaction keeps its shape.
      if (data < 0 || data >= diagnostic_count) return CommandResult{status_bad_data, true, 0};
      return answer(command, diagnostic(data));
    case cmd_clear_faults:
      faults_ = 0;
      brake_ticks_ = 0;
      monitor_.reset();
      loop_.hold(count);  // holds where it is: clearing never moves the joint
      return success(command);
    default: return CommandResult{status_unknown_command, false, 0};
  }
}

}  // namespace joint_bus
}  // namespace armctl
