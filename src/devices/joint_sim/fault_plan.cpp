#include "devices/joint_sim/fault_plan.hpp"

#include <algorithm>
#include <string>

#include "core/error.hpp"

namespace armctl::joint_sim {

namespace {

void check_joint(int joint, const char* what) {
  if (joint < 1 || joint > 7) {
    throw ArmctlError(ErrorKind::invalid_argument, std::string(what) + ": joint " +
                                                       std::to_string(joint) +
                                                       " does not exist (allowed: 1..7)");
  }
}

void check_rate(double rate, const char* name) {
  if (!(rate >= 0.0 && rate <= 1.0)) {
    throw ArmctlError(ErrorKind::invalid_argument, std::string("random faults: ") + name +
                                                       " rate " + std::to_string(rate) +
                                                       " is not a probability (allowed: 0..1)");
  }
}

constexpr Duration max_fault_delay = std::chrono::seconds(10);

}  // namespace

FaultPlan& FaultPlan::drop_byte(Wire wire, std::uint64_t index) {
  ByteFault f{wire, index};
  f.drop = true;
  byte_faults_.push_back(f);
  return *this;
}

FaultPlan& FaultPlan::flip_bits(Wire wire, std::uint64_t index, std::uint8_t mask) {
  if (mask == 0) {
    throw ArmctlError(ErrorKind::invalid_argument,
                      "flip_bits: mask 0 flips nothing (allowed: 0x01..0xFF)");
  }
  ByteFault f{wire, index};
  f.flip_mask = mask;
  byte_faults_.push_back(f);
  return *this;
}

FaultPlan& FaultPlan::delay_byte(Wire wire, std::uint64_t index, Duration delay) {
  if (delay <= Duration::zero() || delay > max_fault_delay) {
    throw ArmctlError(ErrorKind::invalid_argument,
                      "delay_byte: delay of " + std::to_string(delay.count()) +
                          " ns is out of range (allowed: > 0 and <= 10 s)");
  }
  ByteFault f{wire, index};
  f.delay = delay;
  byte_faults_.push_back(f);
  return *this;
}

FaultPlan& FaultPlan::dead_joint(int joint) {
  check_joint(joint, "dead_joint");
  dead_joints_.push_back(joint);
  return *this;
}

FaultPlan& FaultPlan::wrong_number(int joint, std::int16_t number) {
  check_joint(joint, "wrong_number");
  wrong_numbers_.push_back({joint, number});
  return *this;
}

FaultPlan& FaultPlan::garbage(TimePoint at, std::vector<std::uint8_t> bytes) {
  if (bytes.empty()) {
    throw ArmctlError(ErrorKind::invalid_argument,
                      "garbage: no bytes given (allowed: one or more bytes)");
  }
  garbage_.push_back({at, std::move(bytes)});
  return *this;
}

FaultPlan& FaultPlan::random(std::uint64_t seed, RandomFaultRates rates) {
  check_rate(rates.drop, "drop");
  check_rate(rates.flip, "flip");
  check_rate(rates.delay, "delay");
  check_rate(rates.garbage, "garbage");
  if (rates.max_delay <= Duration::zero() || rates.max_delay > max_fault_delay) {
    throw ArmctlError(ErrorKind::invalid_argument,
                      "random faults: max_delay out of range (allowed: > 0 and <= 10 s)");
  }
  random_ = Random{seed, rates};
  return *this;
}

FaultInjector::FaultInjector(FaultPlan plan) : plan_(std::move(plan)) {
  if (plan_.random_faults()) rng_state_ = plan_.random_faults()->seed;
}

// splitmix64: tiny, fast and identical on every platform (std distributions are not).
std::uint64_t FaultInjector::next_random() {
  std::uint64_t z = (rng_state_ += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

double FaultInjector::next_unit() { return double(next_random() >> 11) * 0x1.0p-53; }

ByteFate FaultInjector::next_byte(Wire wire) {
  const std::uint64_t index = wire == Wire::to_joints ? count_to_joints_++ : count_to_master_++;
  ByteFate fate;
  for (const FaultPlan::ByteFault& f : plan_.byte_faults()) {
    if (f.wire != wire || f.index != index) continue;
    fate.drop = fate.drop || f.drop;
    fate.flip_mask = static_cast<std::uint8_t>(fate.flip_mask ^ f.flip_mask);
    fate.delay += f.delay;
  }
  if (const auto& r = plan_.random_faults()) {
    // Always draw the same number of values per byte so one fate does not shift the next.
    const double u_drop = next_unit();
    const double u_flip = next_unit();
    const double u_delay = next_unit();
    const double u_garbage = next_unit();
    const std::uint64_t bits = next_random();
    if (u_drop < r->rates.drop) fate.drop = true;
    if (u_flip < r->rates.flip) {
      fate.flip_mask = static_cast<std::uint8_t>(fate.flip_mask ^ (1u << (bits & 7u)));
    }
    if (u_delay < r->rates.delay) {
      const auto span = static_cast<std::uint64_t>(r->rates.max_delay.count());
      fate.delay += Duration(static_cast<std::int64_t>(1 + ((bits >> 8) % span)));
    }
    if (wire == Wire::to_master && u_garbage < r->rates.garbage) {
      fate.garbage_before = static_cast<std::uint8_t>(bits >> 56);
    }
  }
  return fate;
}

bool FaultInjector::dead(int joint) const {
  const auto& d = plan_.dead_joints();
  return std::find(d.begin(), d.end(), joint) != d.end();
}

std::optional<std::int16_t> FaultInjector::wrong_number(int joint) const {
  for (const auto& w : plan_.wrong_numbers()) {
    if (w.joint == joint) return w.number;
  }
  return std::nullopt;
}

}  // namespace armctl::joint_sim
