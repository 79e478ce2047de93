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

bool JointController::begin(uint8_t joint_number, const JointTuning& tuning, uint32_t baud) {
  configured_ = joint_number >= 1 && joint_number <= max_joints && baud != 0;
  joint_number_ = joint_number;
  decoder_.set_count(0);
  sampled_count_ = 0;
  decoder_.clear_errors();
  loop_.begin(tuning, 0);
  if (!configured_) loop_.set_enabled(false, 0);
  transaction_.begin(static_cast<int16_t>(joint_number), baud);
  last_output_ = DriveOutput{0, false};
  return configured_;
}

void JointController::on_rx_byte(uint8_t byte, uint32_t now_us) {
  if (!configured_) return;
  if (transaction_.on_rx_byte(byte, now_us) == BusTransaction::Event::command_ready) {
    const CommandResult r = execute(transaction_.command(), transaction_.data());
    transaction_.complete(r.status, r.has_response, r.response);
  }
}

DriveOutput JointController::control_compute() {
  if (!configured_) return DriveOutput{0, false};
  last_output_ = loop_.tick(sampled_count_);
  return last_output_;
}

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
    case cmd_get_position: return answer(command, saturate_to_int16(count));
    case cmd_get_target: return answer(command, loop_.target());
    case cmd_get_joint_number: return answer(command, static_cast<int16_t>(joint_number_));
    case cmd_drive_dist: {
      const int32_t next = static_cast<int32_t>(loop_.target()) + data;
      if (!fits_int16(next)) return kBadData;
      loop_.set_target(static_cast<int16_t>(next));
      return success(command);
    }
    case cmd_drive_dist_max: {
      const int32_t next = count + data;
      if (!fits_int16(next)) return kBadData;
      loop_.set_target(static_cast<int16_t>(next));
      return success(command);
    }
    case cmd_drive_to:
      loop_.set_target(data);
      return success(command);
    case cmd_set_speed:
      if (data < 0 || data > 100) return kBadData;
      loop_.set_speed_percent(static_cast<uint8_t>(data));
      return success(command);
    case cmd_set_zone:
      if (data < 0) return kBadData;
      loop_.set_zone(data);
      return success(command);
    case cmd_check_target_reached: return answer(command, loop_.target_reached(count) ? 1 : 0);
    default: return CommandResult{status_unknown_command, false, 0};
  }
}

}  // namespace joint_bus
}  // namespace armctl
