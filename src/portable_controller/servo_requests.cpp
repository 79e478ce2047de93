// ControllerCore: per-joint offsets (ServoOffsetAdjust / ServoOffsetRead) and motor mode
// (ServoSpeed), as the Linux arm controller maps them (docs/arm-controller.md).
#include "portable_controller/controller_core.hpp"
#include "portable_controller/counting.hpp"
#include "portable_controller/rc_codes.hpp"

namespace armctl {
namespace controller {

void ControllerCore::on_offset_adjust(const uint8_t* data, uint8_t length) {
  const int8_t index = length == 3 ? index_of(data[0]) : -1;
  const int16_t offset = index < 0 ? 0 : static_cast<int16_t>(rc_u16(data + 1));
  if (index < 0 || offset < -rc_max_offset || offset > rc_max_offset) {
    count_up(stats_.ignored_frames);
    return;
  }
  state_[index].offset = static_cast<int8_t>(offset);
}

void ControllerCore::on_offset_read(const uint8_t* data, uint8_t length) {
  if (length < 1 || length != 1 + data[0] || data[0] > max_joints) {
    count_up(stats_.ignored_frames);
    return;
  }
  uint8_t reply[1 + 2 * max_joints];
  reply[0] = data[0];
  for (uint8_t k = 0; k < data[0]; ++k) {
    const int8_t index = index_of(data[1 + k]);
    if (index < 0) {
      count_up(stats_.ignored_frames);
      return;
    }
    reply[1 + 2 * k] = data[1 + k];
    reply[2 + 2 * k] = static_cast<uint8_t>(state_[index].offset);
  }
  upstream_->send_frame(rc_servo_offset_read, reply, static_cast<uint8_t>(1 + 2 * data[0]));
}

void ControllerCore::on_servo_speed(const uint8_t* data, uint8_t length, uint32_t now_us) {
  const int8_t found = length == 4 ? index_of(data[0]) : -1;
  const uint8_t mode = found < 0 ? 0 : data[1];
  const int16_t speed = found < 0 ? 0 : static_cast<int16_t>(rc_u16(data + 2));  // motor mode: signed
  if (found < 0 || mode > 1 || (mode == 1 && (speed < -rc_max_motor_speed || speed > rc_max_motor_speed))) {
    count_up(stats_.ignored_frames);
    return;
  }
  const uint8_t index = static_cast<uint8_t>(found);
  JointState& s = state_[index];
  if (mode == 0) {  // servo mode: a jog ends where it is
    if (s.jogging) {
      cancel_ops(index, false);
      schedule(now_us, index, OpKind::speed, 0);
      s.jogging = false;
    }
    return;
  }
  // Motor mode: 1000 = the joint's top speed, toward the soft limit in that direction; the
  // joint stops there at the latest.
  cancel_ops(index, false);
  if (!s.loop_on) schedule(now_us, index, OpKind::loop_on, 1);
  s.loop_on = true;
  s.jogging = true;
  s.planned = false;
  const int16_t magnitude = speed < 0 ? static_cast<int16_t>(-speed) : speed;
  schedule(now_us, index, OpKind::speed, static_cast<int16_t>((magnitude + 9) / 10));
  if (speed != 0) {
    const JointSetup& j = joints_[index];
    const bool up = (speed > 0) == (j.clicks_at_1000 > j.clicks_at_0);
    schedule(now_us, index, OpKind::drive_to, up ? j.soft_max : j.soft_min);
  }
}

}  // namespace controller
}  // namespace armctl
