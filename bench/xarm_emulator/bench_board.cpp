// How much headroom the board side has over the wire: requests handled per second in
// process (SimClock, no pty) against the most a 115200-baud line can deliver, and a full
// 1,020-action group download (in-memory store) against its wire time at 115200 baud.
#include <chrono>
#include <cstdio>
#include <vector>

#include "devices/xarm_emulator/xarm_emulator.hpp"
#include "protocol/robot_commands/messages.hpp"

namespace {

using namespace armctl;

std::vector<std::uint8_t> bytes_of(const rc::Request& r) {
  return rc::encode_frame(*rc::encode(r, rc::ServoRange::xarm()));
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main() {
  SimClock clock;
  std::size_t replies = 0;
  xarm::XarmEmulator emu(clock, {}, [&](const rc::Frame&) { ++replies; });

  // A mix of a six-servo move and a position read: 23 + 10 bytes in, 23 bytes out.
  auto move = bytes_of(
      rc::MultiServoMove{500, {{1, 100}, {2, 200}, {3, 300}, {4, 400}, {5, 500}, {6, 600}}});
  auto read = bytes_of(rc::ServoPositionRead{{1, 2, 3, 4, 5, 6}});
  const int rounds = 200000;
  auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < rounds; ++i) {
    emu.receive(move);
    emu.receive(read);
    clock.advance(std::chrono::milliseconds(1));
    emu.poll();
  }
  double per_s = 2.0 * rounds / seconds_since(t0);
  // Wire limit: requests per second a 115200-baud line can carry for the same mix.
  double wire_per_s =
      2.0 / (std::chrono::duration<double>(wire_time(move.size() + read.size(), 115200)).count());
  std::printf("BENCH board_requests_per_s %.0f req/s limit %.0f ratio %.1f\n", per_s, wire_per_s,
              per_s / wire_per_s);

  std::vector<std::vector<std::uint8_t>> frames;
  frames.push_back(bytes_of(rc::GroupDownloadBegin{1, 1020}));
  frames.push_back(bytes_of(rc::GroupDownloadServoCount{1, 6}));
  frames.push_back(bytes_of(rc::GroupDownloadBlocks{1, 4}));
  for (int i = 0; i < 1020; ++i) {
    rc::GroupDownloadAction a{
        1, static_cast<std::uint8_t>(i / 255), static_cast<std::uint8_t>(i % 255), 100, {}};
    for (std::uint8_t s = 1; s <= 6; ++s)
      a.targets.push_back({s, static_cast<std::uint16_t>((i * s) % 1001)});
    frames.push_back(bytes_of(a));
  }
  frames.push_back(bytes_of(rc::GroupDownloadEnd{1}));
  std::size_t total = 0;
  for (const auto& f : frames) total += f.size() + 6;  // + the 6-byte ack
  const int downloads = 50;
  t0 = std::chrono::steady_clock::now();
  for (int d = 0; d < downloads; ++d)
    for (const auto& f : frames) emu.receive(f);
  double ms = seconds_since(t0) * 1000.0 / downloads;
  double wire_ms = std::chrono::duration<double, std::milli>(wire_time(total, 115200)).count();
  std::printf("BENCH board_group_download_1020 %.2f ms limit %.0f ratio %.1f\n", ms, wire_ms,
              wire_ms / ms);
  return emu.board().stats().ignored() == 0 && replies > 0 ? 0 : 1;
}
