#include "core/miscalibration.hpp"

#include <charconv>
#include <cmath>

#include <fmt/core.h>

namespace armctl {

namespace {

// SplitMix64: tiny, well mixed, and its output is fixed by its definition (std::'s
// distributions are not the same on every standard library).
class SeedStream {
 public:
  explicit SeedStream(std::uint32_t seed) : state_(0x6d697363616c0000ULL ^ seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  // A whole number in lo..hi.
  int between(int lo, int hi) { return lo + int(next() % std::uint64_t(hi - lo + 1)); }
  int sign() { return (next() & 1) ? 1 : -1; }
  // lo..hi in steps of 0.1 (a length error a ruler could tell).
  double tenths(double lo, double hi) { return between(int(lo * 10), int(hi * 10)) / 10.0; }

 private:
  std::uint64_t state_;
};

}  // namespace

const char* to_string(MiscalArm arm) { return arm == MiscalArm::scara ? "scara" : "xarm"; }

const JointMiscal& Miscalibration::joint(int id) const {
  if (id < 1 || id > int(joints.size()))
    throw ArmctlError(ErrorKind::invalid_argument,
                      fmt::format("miscalibration: no device ID {} (allowed: 1..{})", id, joints.size()));
  return joints[std::size_t(id - 1)];
}

double Miscalibration::true_position(int id, double device) const {
  const JointMiscal& j = joint(id);
  return pivot + (j.flipped ? -1.0 : 1.0) * (device - pivot) + j.zero_shift;
}

double Miscalibration::device_position(int id, double true_pos) const {
  const JointMiscal& j = joint(id);
  return pivot + (j.flipped ? -1.0 : 1.0) * (true_pos - j.zero_shift - pivot);
}

double Miscalibration::link_error_mm(std::string_view urdf_joint) const {
  for (const LinkError& l : links)
    if (l.joint == urdf_joint) return l.error_mm;
  return 0;
}

Miscalibration make_miscalibration(MiscalArm arm, std::uint32_t seed) {
  SeedStream r(seed);
  Miscalibration m;
  m.arm = arm;
  m.seed = seed;
  if (arm == MiscalArm::xarm) {
    m.pivot = 500;
    m.joints.resize(6);
    for (JointMiscal& j : m.joints) j.zero_shift = r.sign() * r.between(8, 60);
    m.joints[std::size_t(r.between(2, 6) - 1)].flipped = true;
    if (seed % 2 == 1) {  // beyond the servo's own offset range: the arm file must take it
      const int big = r.between(2, 6);
      m.joints[std::size_t(big - 1)].zero_shift = r.sign() * r.between(130, 170);
    }
    for (const char* joint : {"servo5", "servo4", "servo3", "servo2"})
      m.links.push_back({joint, r.sign() * r.tenths(1.0, 5.0)});
    const int place = r.between(2, 6);
    int answers_as = r.between(2, 5);
    if (answers_as >= place) ++answers_as;  // another chain servo's ID
    m.duplicate = DuplicateId{place, answers_as};
  } else {
    m.pivot = 0;
    m.joints.resize(7);
    m.joints[0].zero_shift = r.sign() * r.between(200, 1500);  // Z: 100 clicks per mm
    for (int id = 2; id <= 6; ++id) m.joints[std::size_t(id - 1)].zero_shift = r.sign() * r.between(56, 420);
    m.joints[std::size_t(r.between(2, 6) - 1)].flipped = true;
    for (const char* joint : {"UAE", "UAJ"}) m.links.push_back({joint, r.sign() * r.tenths(1.0, 5.0)});
  }
  return m;
}

Miscalibration no_miscalibration(MiscalArm arm) {
  Miscalibration m;
  m.arm = arm;
  m.pivot = arm == MiscalArm::xarm ? 500 : 0;
  m.joints.resize(arm == MiscalArm::xarm ? 6 : 7);
  return m;
}

std::string describe(const Miscalibration& m) {
  const char* what = m.arm == MiscalArm::xarm ? "servo" : "joint";
  std::string out = fmt::format("miscal {} ({}):", m.seed, to_string(m.arm));
  for (std::size_t i = 0; i < m.joints.size(); ++i) {
    out += fmt::format("{} {} {} zero {:+g}{}", i == 0 ? "" : ",", what, i + 1, m.joints[i].zero_shift,
                       m.joints[i].flipped ? " flipped" : "");
  }
  out += ";";
  for (std::size_t i = 0; i < m.links.size(); ++i)
    out += fmt::format("{} link {} {:+g} mm", i == 0 ? "" : ",", m.links[i].joint, m.links[i].error_mm);
  if (m.duplicate)
    out += fmt::format("; the servo in place {} answers ID {}", m.duplicate->place, m.duplicate->answers_as);
  return out;
}

Result<std::uint32_t> parse_miscal_seed(std::string_view key, std::string_view text) {
  std::uint32_t seed = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), seed);
  if (text.empty() || ec != std::errc{} || end != text.data() + text.size())
    return Error{ErrorKind::invalid_argument,
                 fmt::format("{} '{}' is not a seed (allowed: a whole number 0..4294967295)", key, text)};
  return seed;
}

}  // namespace armctl
