// Arbitrary bytes into the FrameReceiver; every frame it yields goes through every typed
// decoder (board side with 6 and 7 servos, host side) and, when it decodes, back through
// the encoder, which must reproduce the same frame (armctl's JointFault extensions too).
// Must never crash.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "protocol/robot_commands/frame_receiver.hpp"
#include "protocol/robot_commands/hid_report.hpp"
#include "protocol/robot_commands/joint_faults.hpp"
#include "protocol/robot_commands/messages.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace armctl::rc;
  FrameReceiver rx;
  // Feed in two pieces split by the first byte, to exercise partial frames.
  const std::size_t split = size ? data[0] % (size + 1) : 0;
  rx.feed(std::span<const std::uint8_t>(data, split));
  rx.feed(std::span<const std::uint8_t>(data + split, size - split));
  while (auto f = rx.next()) {
    for (int servos : {6, 7}) {
      auto request = decode_request(*f, ServoRange::of_count(servos));
      if (request) {
        auto again = encode(*request, ServoRange::of_count(servos));
        if (!again || encode_frame(*again) != encode_frame(*f)) {
          // GroupDownload begin accepts any run of count bytes but re-encodes canonically.
          if (!std::holds_alternative<GroupDownloadBegin>(*request)) std::abort();
        }
      }
    }
    auto message = decode_board_message(*f);
    if (message) {
      auto again = encode(*message);
      if (!again || *again != *f) std::abort();
    }
    // armctl's extensions (JointFaultRead / JointFaultClear replies).
    if (auto report = decode_joint_fault_reply(*f); report && encode_joint_fault_reply(*report) != *f) std::abort();
    if (auto cleared = decode_joint_fault_clear_reply(*f); cleared && encode_joint_fault_clear_reply(*cleared) != *f)
      std::abort();
  }
  (void)decode_hid_report(std::span<const std::uint8_t>(data, size));
  return 0;
}
