// Arbitrary bytes as the arm controller's group memory when it starts: the Mega's EEPROM
// after a reset mid-write or a flash from another program, or the Linux controller's
// core-memory.bin after a disk fault or a hand edit (both read it as outside input). The
// first byte chooses the layout (the Mega's 16-entry directory in 4 KiB, or Linux's 255
// entries, here in 12 KiB), the rest is the memory image (0xFF after it, as erased). The
// core then plays every group the directory claims and takes a download. Must never crash
// nor read outside the memory, never drive a joint outside its soft limits, and what it
// writes stays inside the memory.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "fake_joints.hpp"
#include "memory_rig.hpp"
#include "portable_controller/controller_core.hpp"
#include "portable_controller/rc_codes.hpp"
#include "portable_controller/scara_arm.hpp"

namespace {

using namespace armctl::controller;
using namespace armctl::controller::testing;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const bool linux_layout = (data[0] & 1) != 0;
  const std::uint8_t entries = linux_layout ? 255 : GroupStore::mega_entries;
  RamMemory memory(linux_layout ? 12288 : 4096);
  std::copy_n(data + 1, std::min(size - 1, memory.bytes.size()), memory.bytes.begin());
  std::vector<GroupStore::Entry> directory(entries);
  FakeJoints joints;
  RecordingUpstream upstream;
  ControllerCore core;
  std::uint32_t now = 1000;
  core.begin(scara_joints, scara_joint_count, &joints, &upstream, 115200, now, &memory, directory.data(), entries);
  run_core(core, joints, now, 20000, 100);
  // Every group the directory claims, played once (a group's actions are read from the
  // memory as the directory says), a little of each.
  for (int g = 0; g < 255; ++g) {
    GroupInfo info;
    if (!core.groups().find(static_cast<std::uint8_t>(g), &info)) continue;
    const std::uint8_t run[3] = {static_cast<std::uint8_t>(g), 1, 0};
    core.on_frame(rc_group_run, run, 3, now);
    run_core(core, joints, now, 3000, 500);
  }
  // A download into whatever space the store believes free.
  const std::uint8_t begin[3] = {1, 200, 1};
  core.on_frame(rc_group_download, begin, 3, now);
  run_core(core, joints, now, 2000, 500);
  const std::uint8_t servos[5] = {2, 200, 0, 1, 0};
  core.on_frame(rc_group_download, servos, 5, now);
  run_core(core, joints, now, 2000, 500);
  if (!joints.drives_within_soft_limits(scara_joints, scara_joint_count)) std::abort();
  if (memory.bytes.size() != (linux_layout ? 12288u : 4096u)) std::abort();
  return 0;
}
