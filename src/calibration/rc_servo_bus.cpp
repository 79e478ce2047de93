#include "calibration/rc_servo_bus.hpp"

#include <fmt/core.h>

namespace armctl::calibration {

namespace {

Status check_id(int id) {
  if (id < 1 || id > 253)
    return Error{ErrorKind::invalid_argument, fmt::format("servo ID {}: allowed 1..253", id)};
  return Ok{};
}

}  // namespace

Result<std::optional<double>> RcServoBus::read_position(int id) {
  if (Status s = check_id(id); !s) return s.error();
  auto r = client_.read_positions({std::uint8_t(id)});
  // A read nobody answered usably times out (no servo with the ID, or two whose replies
  // collided): that is the answer, not a failure of the link.
  if (!r && r.error().kind == ErrorKind::timeout) return std::optional<double>{};
  if (!r) return r.error();
  for (const rc::ServoPosition& p : *r)
    if (p.servo == id) return std::optional<double>(p.position);
  return std::optional<double>{};
}

Status RcServoBus::set_id_of_only_servo(int id) {
  if (Status s = check_id(id); !s) return s;
  rc::BusServoInfoWrite info;  // the factory limits, with the new ID
  info.servo = std::uint8_t(id);
  return client_.write_bus_servo_info(info);
}

Result<int> RcServoBus::read_offset(int id) {
  if (Status s = check_id(id); !s) return s.error();
  auto r = client_.read_offsets({std::uint8_t(id)});
  if (!r) return r.error();
  for (const rc::ServoOffset& o : *r)
    if (o.servo == id) return int(o.offset);
  return Error{ErrorKind::protocol, fmt::format("servo {}: no offset in the reply", id)};
}

Status RcServoBus::adjust_offset(int id, int units) {
  if (Status s = check_id(id); !s) return s;
  return client_.adjust_offset(std::uint8_t(id), units);
}

Status RcServoBus::save_offset(int id) {
  if (Status s = check_id(id); !s) return s;
  return client_.save_offsets({std::uint8_t(id)});
}

}  // namespace armctl::calibration
