#include "devices/xarm_emulator/xarm_servos.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include <fmt/core.h>

#include "core/error.hpp"
#include "core/atomic_file.hpp"
#include "devices/rc_board/crc32.hpp"
#include "devices/xarm_emulator/bus_replies.hpp"

namespace armctl::xarm {
namespace {

constexpr char kMagic[8] = {'A', 'R', 'M', 'S', 'R', 'V', '1', '\n'};
constexpr std::size_t kPerServo = 14;
constexpr const char* kSettingsFile = "xarm-servos.dat";

double seconds(Duration d) {
  return std::chrono::duration<double>(d).count();
}

void put16(std::vector<std::uint8_t>& out, std::uint16_t v) {
  out.push_back(static_cast<std::uint8_t>(v & 0xFF));
  out.push_back(static_cast<std::uint8_t>(v >> 8));
}

}  // namespace

XarmServos::XarmServos(XarmServosOptions options, TimePoint now)
    : options_(std::move(options)), now_(now) {
  for (std::size_t i = 0; i < kServoCount; ++i) {
    servos_[i].limits.servo = ids_[i];
    servos_[i].start = servos_[i].end = now;
  }
  if (options_.miscal) {
    if (options_.miscal->arm != MiscalArm::xarm)
      throw ArmctlError(ErrorKind::invalid_argument, "emulated xArm: a miscalibration for the SCARA given to the xArm");
    options_.state_dir.reset();  // a fresh arm every start (XarmServosOptions::miscal)
    if (const auto& d = options_.miscal->duplicate) at(ServoId(d->place)).limits.servo = ServoId(d->answers_as);
  }
  if (options_.state_dir) load_settings();
}

std::vector<XarmServos::Servo*> XarmServos::answering(ServoId id) {
  std::vector<Servo*> out;
  for (Servo& s : servos_)
    if (s.connected && s.limits.servo == id) out.push_back(&s);
  return out;
}

std::vector<const XarmServos::Servo*> XarmServos::answering(ServoId id) const {
  std::vector<const Servo*> out;
  for (const Servo& s : servos_)
    if (s.connected && s.limits.servo == id) out.push_back(&s);
  return out;
}

bool XarmServos::all_connected() const {
  return std::all_of(servos_.begin(), servos_.end(), [](const Servo& s) { return s.connected; });
}

bool XarmServos::touching(std::array<double, kServoCount> shafts) const {
  if (options_.miscal)
    for (std::size_t i = 0; i < kServoCount; ++i) shafts[i] = options_.miscal->true_position(int(i + 1), shafts[i]);
  return options_.touches(shafts);
}

PositionRange XarmServos::position_range(ServoId servo) const {
  // Several servos answering one ID: the board checks against the first (whose limits it
  // would read); nobody answering: anything goes, nothing moves.
  const auto those = answering(servo);
  if (those.empty()) return {};
  const auto& l = those.front()->limits;
  return {l.position_min, l.position_max};
}

bool XarmServos::moving(ServoId servo) const {
  const Servo& s = at(servo);
  return s.torque && ((s.mode == ServoMode::motor && s.motor_speed != 0) || now_ < s.end);
}

double XarmServos::planned(const Servo& s, TimePoint t) const {
  if (t >= s.end) return s.target;
  return s.from + (s.target - s.from) * seconds(t - s.start) / seconds(s.end - s.start);
}

void XarmServos::advance_to(TimePoint now) {
  if (now <= now_) return;
  if (options_.touches) {
    while (now_ < now) step_against_obstacle(std::min(now, now_ + kContactStep));
    return;
  }
  double dt = seconds(now - now_);
  for (Servo& s : servos_) {
    if (!s.torque || s.blocked) continue;
    if (s.mode == ServoMode::motor) {
      double p = std::fmod(s.position + s.motor_speed * kMotorUnitsPerSpeed * dt, kTurn);
      s.position = p < 0 ? p + kTurn : p;
    } else {
      s.position = planned(s, now);
    }
  }
  now_ = now;
}

void XarmServos::step_against_obstacle(TimePoint t) {
  const double dt = seconds(t - now_);
  std::array<double, kServoCount> shafts;
  for (std::size_t i = 0; i < kServoCount; ++i) shafts[i] = servos_[i].position + servos_[i].offset;
  // An arm already touching (started there, put there by hand) is let move: which way is out
  // is not for the servos to judge.
  const bool free = !touching(shafts);
  for (std::size_t i = 0; i < kServoCount; ++i) {
    Servo& s = servos_[i];
    if (!s.torque || s.blocked) continue;
    if (s.mode == ServoMode::motor) {
      const double p = std::fmod(s.position + s.motor_speed * kMotorUnitsPerSpeed * dt, kTurn);
      s.position = p < 0 ? p + kTurn : p;
      continue;
    }
    // Towards where its move has it, never faster than it can: a servo held back catches up
    // along the way, not by a jump through what held it.
    const double limit = kMaxSpeed * dt * 1.001;
    const double step = std::clamp(planned(s, t) - s.position, -limit, limit);
    if (step == 0) continue;
    shafts[i] += step;
    if (free && touching(shafts)) {
      shafts[i] -= step;  // stalled against the obstacle
      continue;
    }
    s.position += step;
  }
  now_ = t;
}

Result<Duration> XarmServos::move(std::span<const ServoTarget> targets, Duration time,
                                  TimePoint now) {
  advance_to(now);
  Duration longest = time;
  for (const ServoTarget& t : targets) {
    for (const Servo* s : answering(t.servo)) {
      double distance = std::abs(*t.position - s->position);  // never "leave alone" here
      auto fastest =
          std::chrono::duration_cast<Duration>(std::chrono::duration<double>(distance / kMaxSpeed));
      longest = std::max(longest, fastest);
    }
  }
  // One synchronized move: every servo arrives at the same moment (the slowest decides).
  // Every connected servo answering a target's ID hears it (two, with a duplicated ID).
  for (const ServoTarget& t : targets) {
    for (Servo* answer : answering(t.servo)) {
    Servo& s = *answer;
    s.torque = true;
    s.mode = ServoMode::servo;
    s.motor_speed = 0;
    s.from = s.position;
    s.target = *t.position;
    s.start = now_;
    s.end = now_ + longest;
    if (longest == Duration::zero()) s.position = s.target;
    }
  }
  return longest;
}

std::int16_t XarmServos::position(ServoId place) const {
  const Servo& s = at(place);
  return static_cast<std::int16_t>(std::lround(s.position) + s.offset);
}

std::optional<std::int16_t> XarmServos::read_position(ServoId servo) const {
  std::vector<std::vector<std::uint8_t>> answers;
  for (const Servo* s : answering(servo)) {
    const auto p = static_cast<std::uint16_t>(std::lround(s->position) + s->offset);
    answers.push_back({static_cast<std::uint8_t>(p & 0xFF), static_cast<std::uint8_t>(p >> 8)});
  }
  const auto got = read_over_bus(servo, kServoPositionReadCmd, answers);
  if (!got) return std::nullopt;
  return static_cast<std::int16_t>((*got)[0] | ((*got)[1] << 8));
}

std::optional<std::int8_t> XarmServos::read_offset(ServoId servo) const {
  std::vector<std::vector<std::uint8_t>> answers;
  for (const Servo* s : answering(servo)) answers.push_back({static_cast<std::uint8_t>(s->offset)});
  const auto got = read_over_bus(servo, kServoOffsetReadCmd, answers);
  if (!got) return std::nullopt;
  return static_cast<std::int8_t>((*got)[0]);
}

void XarmServos::torque_off(std::span<const ServoId> ids) {
  for (ServoId id : ids) {
    for (Servo* answer : answering(id)) {
    Servo& s = *answer;
    s.torque = false;
    s.mode = ServoMode::servo;
    s.motor_speed = 0;
    s.from = s.target = s.position;
    s.end = now_;
    }
  }
}

bool XarmServos::move_by_hand(ServoId id, double position) {
  Servo& s = at(id);
  if (s.torque) return false;
  s.position = s.from = s.target = position;
  s.end = now_;
  return true;
}

void XarmServos::halt(TimePoint now) {
  advance_to(now);
  for (Servo& s : servos_) {
    if (!s.connected) continue;
    s.mode = ServoMode::servo;
    s.motor_speed = 0;
    s.from = s.target = s.position;
    s.end = now_;
  }
}

std::uint16_t XarmServos::battery_millivolts() const {
  int moving_servos = 0;
  for (ServoId id : ids_) moving_servos += moving(id) ? 1 : 0;
  int mv = options_.battery_millivolts - moving_servos * kSagPerMovingServo;
  return static_cast<std::uint16_t>(std::max(mv, 0));
}

void XarmServos::adjust_offset(ServoId servo, std::int8_t offset) {
  for (Servo* s : answering(servo)) s->offset = offset;
}

std::int8_t XarmServos::offset(ServoId place) const {
  return at(place).offset;
}

Status XarmServos::save_offsets(std::span<const ServoId> ids) {
  std::array<std::int8_t, kServoCount> before{};
  for (std::size_t i = 0; i < kServoCount; ++i) before[i] = servos_[i].saved_offset;
  for (ServoId id : ids)
    for (Servo* s : answering(id)) s->saved_offset = s->offset;
  if (save_settings()) return Ok{};
  for (std::size_t i = 0; i < kServoCount; ++i) servos_[i].saved_offset = before[i];
  return Error{ErrorKind::io, "the servo settings could not be stored in the state directory: " + last_save_error_};
}

void XarmServos::set_mode(ServoId servo, ServoMode mode, std::int16_t speed, TimePoint now) {
  advance_to(now);
  for (Servo* answer : answering(servo)) {
    Servo& s = *answer;
    s.mode = mode;
    s.motor_speed = mode == ServoMode::motor ? speed : std::int16_t{0};
    s.torque = true;
    s.from = s.target = s.position;
    s.end = now_;
  }
}

BusServoInfoReply XarmServos::bus_servo_info() const {
  const Servo& s = at(info_servo_);
  return rc::bus_servo_info_reply(s.limits, s.offset, position(info_servo_),
                                  options_.temperature, battery_millivolts());
}

std::optional<BusServoInfoReply> XarmServos::read_bus_servo_info() const {
  // Every servo plugged in: the emulator's shortcut (the servo last written), as before.
  if (all_connected()) return bus_servo_info();
  // Unplugged ones: what a real bus does. One servo answers; several collide on every
  // register the board reads; none leaves the board waiting.
  const Servo* only = nullptr;
  for (const Servo& s : servos_) {
    if (!s.connected) continue;
    if (only != nullptr) return std::nullopt;
    only = &s;
  }
  if (only == nullptr) return std::nullopt;
  return rc::bus_servo_info_reply(only->limits, only->offset,
                                  static_cast<std::int16_t>(std::lround(only->position) + only->offset),
                                  options_.temperature, battery_millivolts());
}

Status XarmServos::write_bus_servo_info(const BusServoLimits& limits) {
  if (!has_servo(limits.servo)) {
    return Error{ErrorKind::device,
                 fmt::format("servo {} is not on this arm (servos 1..{})", limits.servo, kServoCount)};
  }
  const auto before_servos = servos_;
  ServoId info_before = info_servo_;
  if (all_connected()) {
    // The emulator's shortcut: the servos answering that ID take the limits (both, if two do).
    for (Servo* s : answering(limits.servo)) {
      s->limits = limits;
      info_servo_ = static_cast<ServoId>(s - servos_.data() + 1);
    }
  } else {
    // A real bus: the write reaches every plugged-in servo, and each takes the ID written.
    for (Servo& s : servos_)
      if (s.connected) s.limits = limits;
  }
  if (save_settings()) return Ok{};
  servos_ = before_servos;
  info_servo_ = info_before;
  return Error{ErrorKind::io, "the servo settings could not be stored in the state directory: " + last_save_error_};
}

double XarmServos::true_position(ServoId place) const {
  const Servo& s = at(place);
  const double shaft = s.position + s.offset;
  return options_.miscal ? options_.miscal->true_position(place, shaft) : shaft;
}

bool XarmServos::move_by_hand_to(ServoId place, double true_units) {
  const Servo& s = at(place);
  const double shaft = options_.miscal ? options_.miscal->device_position(place, true_units) : true_units;
  return move_by_hand(place, shaft - s.offset);
}

void XarmServos::set_connected(ServoId place, bool connected) {
  Servo& s = at(place);
  if (!connected && s.connected) {
    // No power: limp where it stands, whatever it was doing.
    s.torque = false;
    s.mode = ServoMode::servo;
    s.motor_speed = 0;
    s.from = s.target = s.position;
    s.end = now_;
  }
  s.connected = connected;
}

bool XarmServos::save_settings() {
  if (!options_.state_dir) return true;
  std::vector<std::uint8_t> out(kMagic, kMagic + sizeof kMagic);
  out.push_back(static_cast<std::uint8_t>(kServoCount));
  for (const Servo& s : servos_) {
    const auto& l = s.limits;
    out.push_back(l.servo);
    out.push_back(static_cast<std::uint8_t>(s.saved_offset));
    for (std::uint16_t v :
         {l.position_min, l.position_max, l.millivolts_min, l.millivolts_max, l.temp_max})
      put16(out, v);
    out.push_back(l.led_status);
    out.push_back(l.led_warning);
  }
  std::uint32_t crc = rc_board::crc32(out);
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(crc >> (8 * i)));
  std::error_code ec;
  std::filesystem::create_directories(*options_.state_dir, ec);
  auto status = write_file_atomically(*options_.state_dir / kSettingsFile, out);
  last_save_error_ = status ? std::string() : status.error().message;
  return status.ok();
}

void XarmServos::load_settings() {
  auto path = *options_.state_dir / kSettingsFile;
  // Exactly this long when valid: anything larger (or not a regular file) is refused unread.
  constexpr std::size_t kSettingsFileBytes = sizeof kMagic + 1 + kServoCount * kPerServo + 4;
  auto bytes = read_whole_file(path, kSettingsFileBytes);
  if (!bytes) throw ArmctlError(bytes.error());
  if (!*bytes) return;  // nothing saved yet: factory settings
  const auto& b = **bytes;
  auto corrupt = [&](const char* why) {
    return ArmctlError(
        ErrorKind::invalid_config,
        fmt::format("{}: {} (delete it to return to factory settings)", path.string(), why));
  };
  if (b.size() != sizeof kMagic + 1 + kServoCount * kPerServo + 4 ||
      std::memcmp(b.data(), kMagic, sizeof kMagic) != 0 || b[8] != kServoCount)
    throw corrupt("not an xArm servo settings file");
  std::uint32_t stored = 0;
  for (int i = 0; i < 4; ++i) stored |= std::uint32_t{b[b.size() - 4 + i]} << (8 * i);
  if (rc_board::crc32(std::span(b).first(b.size() - 4)) != stored) throw corrupt("CRC mismatch");
  auto get16 = [&](std::size_t at) { return static_cast<std::uint16_t>(b[at] | (b[at + 1] << 8)); };
  for (std::size_t i = 0; i < kServoCount; ++i) {
    std::size_t at = sizeof kMagic + 1 + i * kPerServo;
    BusServoLimits l{b[at],         get16(at + 2),  get16(at + 4), get16(at + 6),
                     get16(at + 8), get16(at + 10), b[at + 12],    b[at + 13]};
    auto offset = static_cast<std::int8_t>(b[at + 1]);
    // A servo's ID is its EEPROM's: one re-numbered with a single servo plugged in keeps it.
    if (l.servo < 1 || l.servo > kServoCount || l.position_min > l.position_max || l.position_max > 1000 ||
        offset < -125 || offset > 125)
      throw corrupt("servo entry out of range");
    servos_[i].limits = l;
    servos_[i].saved_offset = servos_[i].offset = offset;
  }
}

}  // namespace armctl::xarm
