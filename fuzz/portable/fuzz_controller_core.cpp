// Arbitrary bytes on the Mega controller's USB serial port: through the board's frame
// reader into the arm-controller core (the same code the firmware runs), over scripted
// joints (tests/portable_controller/fake_joints.hpp) and a RAM standing in for the EEPROM.
// Must never crash, and whatever the bytes say, no joint is ever driven outside its soft
// limits and no reply is longer than a frame can carry.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "fake_joints.hpp"
#include "memory_rig.hpp"
#include "portable_controller/controller_core.hpp"
#include "portable_controller/rc_frame_reader.hpp"
#include "portable_controller/scara_arm.hpp"

namespace {

using namespace armctl::controller;
using namespace armctl::controller::testing;

// Bus work between two upstream bytes: the time one byte takes at 115200 baud (the core
// sees requests as often as the firmware would), in steps as long as a main-loop pass.
constexpr std::uint32_t kByteUs = 87;
constexpr std::size_t kMaxBytes = 1024;  // longer inputs add nothing but time

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FakeJoints joints;
  RecordingUpstream upstream;
  RamMemory memory;
  ControllerCore core;
  std::uint32_t now = 1000;
  core.begin(scara_joints, scara_joint_count, &joints, &upstream, 115200, now, &memory);
  run_core(core, joints, now, 20000, kByteUs);
  RcFrameReader reader(frame_gap_us(115200));
  for (std::size_t i = 0; i < size && i < kMaxBytes; ++i) {
    if (reader.on_byte(data[i], now)) core.on_frame(reader.command(), reader.data(), reader.data_length(), now);
    run_core(core, joints, now, kByteUs, kByteUs);
  }
  run_core(core, joints, now, 200000, 500);  // what was queued goes out
  if (!joints.drives_within_soft_limits(scara_joints, scara_joint_count)) std::abort();
  for (const auto& f : upstream.frames)
    if (f.data.size() + 2 > RcFrameReader::max_length) std::abort();
  return 0;
}
