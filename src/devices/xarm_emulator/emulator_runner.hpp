// Serves an emulated xArm on a pty in real time: the host opens device_path() like a
// serial port (transport::SerialPort, `armctl xarm --device serial:PATH`, any xArm tool).
//
// One loop (transport::ServeLoop), paced by the steady clock: bytes in -> Board, group playback at
// its instants, replies out. With wire timing, bytes take as long as they would on a real
// 8N1 line at `baud` in each direction (a request is handled only once its last byte would
// have arrived; reply bytes leave no faster than the line allows).
//
// Use in-process (start()/stop(): a background thread) or as the main loop of a process
// (run(), ended by request_stop(), which is async-signal-safe).
#pragma once

#include <atomic>
#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "core/clock.hpp"
#include "devices/rc_board/board_stats.hpp"
#include "devices/xarm_emulator/xarm_emulator.hpp"
#include "transport/pty.hpp"
#include "transport/serve_loop.hpp"

namespace armctl::xarm {

struct EmulatorRunnerOptions {
  XarmEmulatorOptions emulator;
  bool wire_timing = false;
  std::uint32_t baud = 9600;  // only used with wire_timing
};

class EmulatorRunner {
 public:
  using Log = std::function<void(const std::string&)>;

  // Creates the pty and the emulator. Throws ArmctlError (pty, state dir, bad baud).
  explicit EmulatorRunner(EmulatorRunnerOptions options, Log log = {});
  ~EmulatorRunner();
  EmulatorRunner(const EmulatorRunner&) = delete;
  EmulatorRunner& operator=(const EmulatorRunner&) = delete;

  // The pty slave, e.g. /dev/pts/7.
  const std::string& device_path() const { return pty_.slave_path(); }

  void start();         // serve on a background thread
  void stop();          // request_stop() and join; idempotent
  void run();           // serve on this thread until request_stop()
  void request_stop();  // from any thread or a signal handler

  // A snapshot, safe from any thread.
  rc_board::BoardStats stats() const;
  // Runs `f` on the emulated servos between two turns of the serving loop, from any thread:
  // what a test does to the physical arm (XarmServos::true_position, move_by_hand_to,
  // set_connected) while a host talks to the board.
  void with_servos(const std::function<void(XarmServos&)>& f);
  std::size_t dropped_output_bytes() const { return dropped_output_.load(); }

 private:
  struct Timed {
    TimePoint at;
    std::vector<std::uint8_t> bytes;
  };
  void on_output(const rc::Frame& frame);
  void read_input(TimePoint now);
  void flush_output(TimePoint now);
  Duration byte_time() const;

  EmulatorRunnerOptions options_;
  Log log_;
  SteadyClock clock_;
  transport::Pty pty_;
  XarmEmulator emulator_;
  transport::ServeLoop loop_;
  std::thread thread_;
  std::atomic<std::size_t> dropped_output_{0};
  mutable std::mutex stats_mutex_;
  std::mutex emulator_mutex_;  // held by the loop while it drives the emulator: with_servos
  rc_board::BoardStats stats_;

  std::deque<Timed> input_;   // wire timing: bytes waiting for their arrival instant
  TimePoint input_free_{};    // when the incoming line is next idle
  std::deque<Timed> output_;  // bytes not yet due (wire timing) or not yet accepted by the pty
  TimePoint output_free_{};
  std::optional<TimePoint> reply_origin_;  // while handling a wire-timed byte: its arrival
};

}  // namespace armctl::xarm
