#include "portable/quadrature_decoder.hpp"

namespace armctl {
namespace joint_bus {

// Index: previous AB levels * 4 + new AB levels. Up: 00 -> 01 -> 11 -> 10 -> 00.
const int8_t QuadratureDecoder::kSteps[16] = {
    // new: 00        01        10        11
    0,  +1, -1, kInvalid,  // from 00
    -1, 0,  kInvalid, +1,  // from 01
    +1, kInvalid, 0,  -1,  // from 10
    kInvalid, -1, +1, 0,   // from 11
};

void QuadratureDecoder::reset(bool a, bool b) {
  state_ = static_cast<uint8_t>((a ? 2u : 0u) | (b ? 1u : 0u));
}

}  // namespace joint_bus
}  // namespace armctl
