// Counters a board keeps about what it received: every ignored frame is counted under one
// reason, so tests, logs and `armctl sim xarm` can show what a host got wrong.
#pragma once

#include <cstddef>

namespace armctl::rc_board {

struct BoardStats {
  std::size_t frames = 0;             // complete frames seen
  std::size_t handled = 0;            // frames acted on
  std::size_t unknown_command = 0;    // CMD not a Robot Commands code: ignored
  std::size_t invalid_frame = 0;      // DATA length/count disagrees, or a field the codec refuses
  std::size_t unknown_servo = 0;      // names a servo this arm does not have
  std::size_t out_of_range = 0;       // a value outside what this arm allows (limits, speed)
  std::size_t download_rejected = 0;  // inconsistent GroupDownload (download abandoned)
  std::size_t refused = 0;            // valid but not possible now (empty group, I/O failure)
  std::size_t refused_moves = 0;      // a valid move the arm refused (a joint not answering)
  std::size_t no_answer = 0;          // a read no servo answered (or two, colliding): no reply
  std::size_t discarded_bytes = 0;    // wire bytes dropped while hunting for a frame
  std::size_t bad_lengths = 0;        // headers with LEN < 2 or too long for a report
  std::size_t torn_frames = 0;        // partial frames dropped: their bytes stopped (rc::frame_gap)

  std::size_t ignored() const {
    return unknown_command + invalid_frame + unknown_servo + out_of_range + download_rejected +
           refused + refused_moves + no_answer;
  }
};

}  // namespace armctl::rc_board
