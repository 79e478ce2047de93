#include "program/program_values.hpp"

#include <cmath>

#include <fmt/core.h>

namespace armctl::program {

namespace {

struct Suffix {
  std::string_view text;
  Unit unit;
  double factor;
};
constexpr double kDeg = M_PI / 180;
constexpr Suffix kSuffixes[] = {
    {"mm", Unit::length, 1e-3},          {"cm", Unit::length, 1e-2},
    {"m", Unit::length, 1},              {"deg", Unit::angle, kDeg},
    {"rad", Unit::angle, 1},             {"s", Unit::time, 1},
    {"ms", Unit::time, 1e-3},            {"%", Unit::percent, 1e-2},
    {"mm/s", Unit::speed, 1e-3},         {"m/s", Unit::speed, 1},
    {"deg/s", Unit::angular_speed, kDeg}, {"rad/s", Unit::angular_speed, 1},
    {"mm/s^2", Unit::acceleration, 1e-3}, {"m/s^2", Unit::acceleration, 1},
    {"deg/s^2", Unit::angular_acceleration, kDeg}, {"rad/s^2", Unit::angular_acceleration, 1},
};

}  // namespace

const char* describe(Unit u) {
  switch (u) {
    case Unit::number: return "a plain number";
    case Unit::length: return "a length";
    case Unit::angle: return "an angle";
    case Unit::time: return "a time";
    case Unit::percent: return "a percentage";
    case Unit::speed: return "a speed";
    case Unit::angular_speed: return "an angular speed";
    case Unit::acceleration: return "an acceleration";
    case Unit::angular_acceleration: return "an angular acceleration";
  }
  return "?";
}

const char* example(Unit u) {
  switch (u) {
    case Unit::number: return "3";
    case Unit::length: return "40mm";
    case Unit::angle: return "90deg";
    case Unit::time: return "0.5s";
    case Unit::percent: return "50%";
    case Unit::speed: return "40mm/s";
    case Unit::angular_speed: return "30deg/s";
    case Unit::acceleration: return "500mm/s^2";
    case Unit::angular_acceleration: return "180deg/s^2";
  }
  return "?";
}

std::string_view allowed_suffixes() {
  return "mm, cm, m, deg, rad, s, ms, %, mm/s, m/s, deg/s, rad/s, mm/s^2, m/s^2, deg/s^2, rad/s^2";
}

Result<UnitSuffix> unit_suffix(std::string_view text) {
  for (const Suffix& s : kSuffixes)
    if (s.text == text) return UnitSuffix{s.unit, s.factor};
  return Error{ErrorKind::invalid_config, std::string(allowed_suffixes())};
}

std::string format_value(const Value& v) {
  auto num = [](double x) { return fmt::format("{:.6g}", x == 0 ? 0.0 : x); };
  switch (v.unit) {
    case Unit::number: return num(v.si);
    case Unit::length: return num(v.si * 1e3) + " mm";
    case Unit::angle: return num(v.si / kDeg) + " deg";
    case Unit::time: return num(v.si) + " s";
    case Unit::percent: return num(v.si * 100) + " %";
    case Unit::speed: return num(v.si * 1e3) + " mm/s";
    case Unit::angular_speed: return num(v.si / kDeg) + " deg/s";
    case Unit::acceleration: return num(v.si * 1e3) + " mm/s^2";
    case Unit::angular_acceleration: return num(v.si / kDeg) + " deg/s^2";
  }
  return num(v.si);
}

}  // namespace armctl::program
