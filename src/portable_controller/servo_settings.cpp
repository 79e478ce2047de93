// ControllerCore: the settings a Robot Commands board keeps per servo, persisted in the
// last ControllerCore::settings_bytes of the group memory (the Mega's EEPROM) through the
// group store's write queue (never blocking; written in the order asked):
//   ServoOffsetWrite    the listed joints' current offsets (ServoOffsetAdjust is volatile)
//   BusServoInfoWrite   the addressed joint (the servo byte; joint 1 after a reset): its
//                       position limits narrow what a move may ask, the voltage,
//                       temperature and LED fields are kept and read back
//   BusServoInfoRead    the addressed joint: limits, offset, polled position, temperature
//                       0 (no sensor), the battery value
// Layout: 'S', format 1, then per joint 13 bytes: offset s8, position min/max, millivolts
// min/max, temperature max (u16 each), LED status, LED warning. The marker is written
// after the defaults, so a memory without it holds no record; a record that is out of
// range (a reset mid-write) is taken as the defaults.
#include "portable_controller/controller_core.hpp"
#include "portable_controller/counting.hpp"
#include "portable_controller/rc_codes.hpp"

namespace armctl {
namespace controller {

namespace {
const uint8_t marker[2] = {'S', 1};
const uint8_t record_bytes = 13;

void put_u16(uint8_t* at, uint16_t v) {
  at[0] = static_cast<uint8_t>(v & 0xFFu);
  at[1] = static_cast<uint8_t>(v >> 8);
}

// The 12 bytes of limits and LED fields, as BusServoInfoWrite sends them after its servo
// byte and as a record keeps them after its offset: into `s` if all are in the spec's
// ranges, else nothing changes (false).
bool take_limits(const uint8_t* p, JointState* s) {
  const uint16_t pmin = rc_u16(p), pmax = rc_u16(p + 2), vmin = rc_u16(p + 4), vmax = rc_u16(p + 6),
                 temp = rc_u16(p + 8);
  const bool valid = pmin <= pmax && pmax <= rc_max_position && vmin >= rc_min_millivolts && vmin <= vmax &&
                     vmax <= rc_max_millivolts && temp >= rc_min_temp_max && temp <= rc_max_temp_max && p[10] <= 1 &&
                     p[11] <= rc_max_led_warning;
  if (!valid) return false;
  s->position_min = pmin;
  s->position_max = pmax;
  s->millivolts_min = vmin;
  s->millivolts_max = vmax;
  s->temp_max = temp;
  s->led_status = p[10];
  s->led_warning = p[11];
  return true;
}

// The same 12 bytes from `s` (a record, BusServoInfoRead's reply).
void put_limits(const JointState& s, uint8_t* p) {
  put_u16(p, s.position_min);
  put_u16(p + 2, s.position_max);
  put_u16(p + 4, s.millivolts_min);
  put_u16(p + 6, s.millivolts_max);
  put_u16(p + 8, s.temp_max);
  p[10] = s.led_status;
  p[11] = s.led_warning;
}
}  // namespace

void ControllerCore::default_settings(JointState& s) const {
  s.offset = 0;
  s.position_min = 0;
  s.position_max = rc_max_position;
  s.millivolts_min = rc_min_millivolts;
  s.millivolts_max = rc_max_millivolts;
  s.temp_max = 85;
  s.led_status = 0;
  s.led_warning = 0;
}

uint32_t ControllerCore::settings_at(uint8_t index) const {
  return memory_->size() - settings_bytes + 2 + uint32_t(record_bytes) * index;
}

void ControllerCore::load_settings() {
  for (uint8_t i = 0; i < max_joints; ++i) default_settings(state_[i]);
  if (memory_ == nullptr) return;
  const uint32_t at = memory_->size() - settings_bytes;
  if (memory_->read(at) != marker[0] || memory_->read(at + 1) != marker[1]) {
    for (uint8_t i = 0; i < count_; ++i) save_settings(i);
    groups_.write(at, marker, 2);
    return;
  }
  for (uint8_t i = 0; i < count_; ++i) {
    uint8_t r[record_bytes];
    for (uint8_t k = 0; k < record_bytes; ++k) r[k] = memory_->read(settings_at(i) + k);
    const int8_t offset = static_cast<int8_t>(r[0]);
    if (offset < -rc_max_offset || offset > rc_max_offset) continue;  // the defaults
    if (take_limits(r + 1, &state_[i])) state_[i].offset = offset;
  }
}

bool ControllerCore::save_settings(uint8_t index) {
  if (memory_ == nullptr) return true;  // volatile: nothing to write
  const JointState& s = state_[index];
  uint8_t r[record_bytes];
  r[0] = static_cast<uint8_t>(s.offset);
  put_limits(s, r + 1);
  return groups_.write(settings_at(index), r, record_bytes);
}

void ControllerCore::on_offset_write(const uint8_t* data, uint8_t length) {
  const bool shaped = length >= 2 && length == 1 + data[0] && data[0] <= max_joints;
  bool known = shaped;
  for (uint8_t k = 0; known && k < data[0]; ++k) known = index_of(data[1 + k]) >= 0;
  // Whole or not at all: each joint's record is one queued run.
  if (!known || (memory_ != nullptr && groups_.queue_room() < data[0] * record_bytes)) {
    count_up(stats_.ignored_frames);
    return;
  }
  for (uint8_t k = 0; k < data[0]; ++k) save_settings(static_cast<uint8_t>(index_of(data[1 + k])));
}

void ControllerCore::on_bus_servo_info_write(const uint8_t* data, uint8_t length) {
  const int8_t found = length == 13 ? index_of(data[0]) : -1;
  // Room first: a write that cannot be saved changes nothing.
  if (found < 0 || (memory_ != nullptr && groups_.queue_room() < record_bytes) || !take_limits(data + 1, &state_[found])) {
    count_up(stats_.ignored_frames);
    return;
  }
  info_index_ = static_cast<uint8_t>(found);
  save_settings(info_index_);
}

void ControllerCore::on_bus_servo_info_read(uint8_t length) {
  if (length != 0 || count_ == 0) {
    count_up(stats_.ignored_frames);
    return;
  }
  const JointState& s = state_[info_index_];
  uint8_t r[19];
  r[0] = joints_[info_index_].number;
  put_limits(s, r + 1);
  r[13] = static_cast<uint8_t>(s.offset);
  put_u16(r + 14, static_cast<uint16_t>(s.position));
  r[16] = 0;  // the joint controllers have no temperature sensor
  put_u16(r + 17, battery_mv_);
  upstream_->send_frame(rc_bus_servo_info_read, r, sizeof r);
}

}  // namespace controller
}  // namespace armctl
