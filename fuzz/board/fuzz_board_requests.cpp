// Arbitrary bytes into the Board over an in-memory arm: never a crash, never a call the
// Board should have refused (CheckingBackend aborts on those), replies always encodable.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "checking_backend.hpp"
#include "devices/rc_board/board.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace armctl;
  if (size == 0) return 0;
  SimClock clock;
  fuzz::CheckingBackend arm;
  auto store = rc_board::GroupStore::in_memory();
  rc_board::Board board(arm, store, clock, [](const rc::Frame& f) {
    if (f.data.size() > rc::kMaxData) std::abort();
  });
  // The first byte sets the chunk size, so frames also arrive split across reads; time
  // moves between chunks so group playback runs too.
  std::size_t chunk = data[0] % 16 + 1;
  for (std::size_t at = 1; at < size; at += chunk) {
    std::size_t n = size - at < chunk ? size - at : chunk;
    board.receive(std::span(data + at, n));
    clock.advance(std::chrono::milliseconds(data[at] * 3));
    board.poll();
  }
  return 0;
}
