// The emulated xArm board: the generic Robot Commands board side (rc_board::Board) over six
// emulated bus servos, with action groups and servo settings kept in an optional state
// directory. Single-threaded and clock-driven (SimClock in tests); EmulatorRunner serves
// it on a pty in real time.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>

#include "core/clock.hpp"
#include "devices/rc_board/board.hpp"
#include "devices/rc_board/group_store.hpp"
#include "devices/xarm_emulator/xarm_servos.hpp"

namespace armctl::xarm {

struct XarmEmulatorOptions {
  // Groups (group-NNN.grp) and servo settings (xarm-servos.dat) live here; nothing = in
  // memory only, lost when the emulator ends.
  std::optional<std::filesystem::path> state_dir;
  std::uint16_t battery_millivolts = 7500;
  std::uint8_t temperature = 35;  // C, what every servo reports
  // Something the arm meets (XarmServosOptions::touches): its servos stall against it.
  std::function<bool(std::span<const double>)> touches;
  // Mis-assembled on purpose (XarmServosOptions::miscal): then nothing is kept in state_dir.
  std::optional<Miscalibration> miscal;
};

class XarmEmulator {
 public:
  // Throws ArmctlError if the state directory cannot be used. `clock` must outlive this.
  XarmEmulator(const Clock& clock, XarmEmulatorOptions options, rc_board::Board::Output output);

  rc_board::Board& board() { return *board_; }
  const rc_board::Board& board() const { return *board_; }
  XarmServos& servos() { return servos_; }
  rc_board::GroupStore& groups() { return *groups_; }

  // Shortcuts to the board.
  void receive(std::span<const std::uint8_t> bytes) { board_->receive(bytes); }
  void poll() { board_->poll(); }

 private:
  XarmServos servos_;
  std::unique_ptr<rc_board::GroupStore> groups_;
  std::unique_ptr<rc_board::Board> board_;
};

}  // namespace armctl::xarm
