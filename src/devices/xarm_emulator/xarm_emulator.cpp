#include "devices/xarm_emulator/xarm_emulator.hpp"

namespace armctl::xarm {

XarmEmulator::XarmEmulator(const Clock& clock, XarmEmulatorOptions options,
                           rc_board::Board::Output output)
    : servos_(XarmServosOptions{options.state_dir, options.battery_millivolts, options.temperature,
                                options.touches, options.miscal},
              clock.now()),
      groups_(options.state_dir && !options.miscal
                  ? std::make_unique<rc_board::GroupStore>(*options.state_dir)
                  : std::make_unique<rc_board::GroupStore>(rc_board::GroupStore::in_memory())),
      board_(std::make_unique<rc_board::Board>(servos_, *groups_, clock, std::move(output))) {}

}  // namespace armctl::xarm
