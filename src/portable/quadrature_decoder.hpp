// 4x quadrature decoding: every edge of A or B is one click. Fed with both channel levels
// on each edge (from the INT0/INT1 pin-change interrupts on the AVR, from the motor model
// in the simulator). A transition that changes both channels at once means an edge was
// missed: it is counted as an error and does not move the count (the direction is unknown).
#pragma once

#include <stdint.h>

namespace armctl {
namespace joint_bus {

class QuadratureDecoder {
 public:
  // Takes the current levels as the reference without counting (call at start-up).
  void reset(bool a, bool b);
  // One edge. Levels written AB: 00 -> 01 -> 11 -> 10 -> 00 (B leads A) counts up, the
  // reverse counts down. Same levels as last time: ignored (a glitch or a repeated call).
  void on_edge(bool a, bool b) {
    const uint8_t now = static_cast<uint8_t>((a ? 2u : 0u) | (b ? 1u : 0u));
    const int8_t step = kSteps[(state_ << 2) | now];
    state_ = now;
    if (step == kInvalid) {
      if (errors_ != 0xFFFFu) ++errors_;
    } else {
      count_ += step;
    }
  }
  int32_t count() const { return count_; }
  void set_count(int32_t count) { count_ = count; }
  uint16_t errors() const { return errors_; }  // saturates at 65535
  void clear_errors() { errors_ = 0; }

 private:
  static const int8_t kInvalid = 2;
  static const int8_t kSteps[16];
  int32_t count_ = 0;
  uint16_t errors_ = 0;
  uint8_t state_ = 0;
};

}  // namespace joint_bus
}  // namespace armctl
