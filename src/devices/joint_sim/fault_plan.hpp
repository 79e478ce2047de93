// Programmable, deterministic faults for the simulated joint bus. A FaultPlan lists
// one-shot faults on numbered bytes, per-joint faults, noise at given times and seeded
// random faults; SimBus::set_fault_plan() installs it and byte numbering starts there.
//
// Bytes are numbered per wire in the order they start (0 = the first byte after the plan was
// installed): Wire::to_joints is the master's TX (seen by every joint), Wire::to_master the
// joints' TX (seen by the master; bytes of all joints counted together).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "core/clock.hpp"

namespace armctl::joint_sim {

enum class Wire { to_joints, to_master };

struct RandomFaultRates {
  double drop = 0.0;     // probability that a byte is lost
  double flip = 0.0;     // probability that one random bit of a byte is inverted
  double delay = 0.0;    // probability that a byte starts late by up to max_delay
  double garbage = 0.0;  // probability that a noise byte reaches the master before a byte
  Duration max_delay = std::chrono::milliseconds(5);
};

class FaultPlan {
 public:
  struct ByteFault {
    Wire wire;
    std::uint64_t index;
    bool drop = false;
    std::uint8_t flip_mask = 0;
    Duration delay{0};
  };
  struct WrongNumber {
    int joint;
    std::int16_t number;
  };
  struct Garbage {
    TimePoint at;
    std::vector<std::uint8_t> bytes;
  };
  struct Random {
    std::uint64_t seed;
    RandomFaultRates rates;
  };

  // Each of these throws ArmctlError(invalid_argument) naming the bad value.
  // The byte never reaches the other side (it still takes its time on the wire).
  FaultPlan& drop_byte(Wire wire, std::uint64_t index);
  // The bits set in `mask` (non-zero) arrive inverted.
  FaultPlan& flip_bits(Wire wire, std::uint64_t index, std::uint8_t mask);
  // The byte starts `delay` (> 0, <= 10 s) later than it would have; later bytes queue up.
  FaultPlan& delay_byte(Wire wire, std::uint64_t index, Duration delay);
  // The joint (1..7) never answers: nothing it sends reaches the wire.
  FaultPlan& dead_joint(int joint);
  // The joint answers READY with `number` instead of its own joint number.
  FaultPlan& wrong_number(int joint, std::int16_t number);
  // Noise: `bytes` (non-empty) appear on the master's RX at `at`.
  FaultPlan& garbage(TimePoint at, std::vector<std::uint8_t> bytes);
  // Random faults on every byte, reproducible from `seed`; rates in [0, 1].
  FaultPlan& random(std::uint64_t seed, RandomFaultRates rates);

  const std::vector<ByteFault>& byte_faults() const { return byte_faults_; }
  const std::vector<int>& dead_joints() const { return dead_joints_; }
  const std::vector<WrongNumber>& wrong_numbers() const { return wrong_numbers_; }
  const std::vector<Garbage>& garbage_bursts() const { return garbage_; }
  const std::optional<Random>& random_faults() const { return random_; }

 private:
  std::vector<ByteFault> byte_faults_;
  std::vector<int> dead_joints_;
  std::vector<WrongNumber> wrong_numbers_;
  std::vector<Garbage> garbage_;
  std::optional<Random> random_;
};

// What happens to one byte as it goes on the wire.
struct ByteFate {
  bool drop = false;
  std::uint8_t flip_mask = 0;
  Duration delay{0};
  std::optional<std::uint8_t> garbage_before;  // to_master only
};

// Applies a FaultPlan byte by byte (used by SimBus). Deterministic: same plan, same bytes,
// same fates.
class FaultInjector {
 public:
  FaultInjector() = default;
  explicit FaultInjector(FaultPlan plan);

  ByteFate next_byte(Wire wire);
  bool dead(int joint) const;
  std::optional<std::int16_t> wrong_number(int joint) const;
  const FaultPlan& plan() const { return plan_; }

 private:
  std::uint64_t next_random();
  double next_unit();

  FaultPlan plan_;
  std::uint64_t count_to_joints_ = 0;
  std::uint64_t count_to_master_ = 0;
  std::uint64_t rng_state_ = 0;
};

}  // namespace armctl::joint_sim
