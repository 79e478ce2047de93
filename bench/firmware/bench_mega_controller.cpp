// Mega controller budgets: flash and static RAM from the ELF (limits: 64 KiB and 4 KiB of
// the ATmega2560's 8 KiB), and on emulated silicon (the Mega ELF on an emulated ATmega2560
// driving seven emulated joints, joint_avr::AvrMegaArm) at 9600 and 115200 baud:
//   mega_refresh_<baud>     position sweeps of all seven joints per second, idle upstream,
//                           against the joint bus floor (7 get_position = 56 bytes of wire
//                           time per sweep, at the AVR UARTs' real rate); ratio = rate /
//                           floor (higher is better)
//   mega_round_trip_<baud>  ServoPositionRead of seven joints: first request byte sent to
//                           last reply byte received, worst of 200 requests spread over
//                           the poll cycle; limit = its wire time (12 + 26 bytes) / 0.90,
//                           i.e. wire time / round trip >= 0.90 (lower ratio is better)
//   mega_loop_worst_<baud>  the longest pass of the firmware's main loop, in CPU cycles
//                           (interrupt handlers included), timed by the loop's heartbeat (a
//                           write to GPIOR0 per pass). `_polling`: while it polls the joints
//                           and answers the 200 reads above; limit one word on the bus at
//                           115200 (2 bytes, 2,778 cycles, the joint firmware's turnaround
//                           budget: such a pass never delays a joint's answer by more than a
//                           word). Without suffix: also planning seven-joint moves (floating
//                           point, between transactions); limit the 128-byte receive ring at
//                           115200 (11.1 ms, 177,778 cycles): no byte a host sends back to
//                           back is lost meanwhile. `_moving`: polling seven joints during
//                           a move, each reading checked against the joint's ramp (the
//                           planning pass left out); limit one word at 115200, as polling.
#include <algorithm>
#include <memory>
#include <string>
#include <cstdio>
#include <vector>

#include "devices/joint_avr/avr_mega_arm.hpp"
#include "devices/joint_sim/arm_config.hpp"
#include "elf_sizes.hpp"

namespace {

using namespace armctl;

double seconds(Duration d) { return std::chrono::duration<double>(d).count(); }

joint_avr::AvrMegaArm make_arm(std::uint32_t baud) {
  joint_sim::ArmConfig config = joint_sim::load_arm_config(joint_sim::default_arm_config_path());
  config.baud = baud;
  const std::string elf =
      baud == 115200 ? joint_avr::mega_firmware_elf_115200() : joint_avr::default_mega_firmware_elf();
  return joint_avr::AvrMegaArm(std::move(config), elf, baud);
}

// A 7-joint MultiServoMove: every joint to `position` in `ms`.
std::vector<std::uint8_t> move_all(std::uint16_t position, std::uint16_t ms) {
  std::vector<std::uint8_t> f{0x55, 0x55, 2 + 3 + 3 * 7, 0x03, 7, std::uint8_t(ms & 0xFF), std::uint8_t(ms >> 8)};
  for (std::uint8_t j = 1; j <= 7; ++j) {
    f.push_back(j);
    f.push_back(std::uint8_t(position & 0xFF));
    f.push_back(std::uint8_t(position >> 8));
  }
  return f;
}

// Times every pass of the Mega's main loop from its heartbeat (GPIOR0 written once a pass).
class LoopWatch {
 public:
  explicit LoopWatch(joint_avr::AvrMegaArm& arm) : arm_(arm) {
    arm_.mega().watch_register_write(gpior0, [this](std::uint8_t, std::uint64_t cycle) {
      if (last_ != 0) worst_ = std::max(worst_, cycle - last_);
      last_ = cycle;
      ++passes_;
    });
  }
  ~LoopWatch() { arm_.mega().watch_register_write(gpior0, nullptr); }
  std::uint64_t worst() const { return worst_; }
  std::uint64_t passes() const { return passes_; }

 private:
  static constexpr std::uint16_t gpior0 = 0x3E;  // data-space address (I/O 0x1E)
  joint_avr::AvrMegaArm& arm_;
  std::uint64_t last_ = 0, worst_ = 0, passes_ = 0;
};

// Ten seven-joint moves, each followed by a read of all positions.
void run_moves(joint_avr::AvrMegaArm& arm) {
  const std::vector<std::uint8_t> read{0x55, 0x55, 0x0A, 0x15, 0x07, 1, 2, 3, 4, 5, 6, 7};
  for (int i = 0; i < 10; ++i) {
    arm.send_upstream(move_all(i % 2 == 0 ? 450 : 550, 600));
    arm.advance(std::chrono::milliseconds(100));
    arm.send_upstream(read);
    arm.advance(std::chrono::milliseconds(700));
    arm.take_upstream();
  }
}

// Where a get_position's time goes: the six turnarounds the spec makes sequential (select
// rise -> READY starts, READY in -> COMMAND starts, COMMAND out -> RESPONSE starts,
// RESPONSE in -> select falls, select fall -> STATUS starts, STATUS in -> next select
// rises), averaged over the transactions traced, and what is left of a transaction beyond
// its wire time and those six (the emulated UARTs' second byte of a word).
class TurnaroundTrace {
 public:
  explicit TurnaroundTrace(joint_avr::AvrMegaArm& arm) : arm_(arm), byte_(arm.arm().bus().byte_time()) {
    arm_.set_bus_trace([this](const joint_avr::BusTraceEvent& e) { on_event(e); });
  }
  ~TurnaroundTrace() { arm_.set_bus_trace(nullptr); }

  void print(std::uint32_t baud) const {
    if (count_ == 0) return;
    const char* names[6] = {"rise->READY", "READY->COMMAND", "COMMAND->RESPONSE", "RESPONSE->fall", "fall->STATUS",
                            "STATUS->rise"};
    std::printf("# mega_turnarounds_%u (mean of %d get_position, us):", baud, count_);
    double total = 0;
    for (int i = 0; i < 6; ++i) {
      std::printf(" %s %.1f%s", names[i], us(sum_[i]) / count_, i % 2 == 0 ? " (joint)" : " (Mega)");
      total += us(sum_[i]);
    }
    const double wire = us(byte_) * 8;
    std::printf("; transaction %.1f = wire %.1f + turnarounds %.1f + other %.1f\n", us(whole_) / count_, wire,
                total / count_, (us(whole_) - total) / count_ - wire);
  }

 private:
  using Kind = joint_avr::BusTraceEvent::Kind;
  static double us(Duration d) { return std::chrono::duration<double, std::micro>(d).count(); }

  void on_event(const joint_avr::BusTraceEvent& e) {
    if (e.kind == Kind::select_rise) {
      finish(e.at);
      events_.clear();
    }
    events_.push_back(e);
  }
  // A get_position: rise, READY (2 joint bytes), COMMAND (2 Mega bytes), RESPONSE (2),
  // fall, STATUS (2); `next_rise` ends it.
  void finish(TimePoint next_rise) {
    const Kind shape[10] = {Kind::select_rise, Kind::joint_byte,  Kind::joint_byte,  Kind::master_byte,
                            Kind::master_byte, Kind::joint_byte,  Kind::joint_byte,  Kind::select_fall,
                            Kind::joint_byte,  Kind::joint_byte};
    if (events_.size() != 10) return;
    for (int i = 0; i < 10; ++i)
      if (events_[i].kind != shape[i]) return;
    const auto& v = events_;
    // Joint bytes are stamped at their end, the Mega's at their start (the write).
    const TimePoint command_end = std::max(v[4].at, v[3].at + byte_) + byte_;
    const Duration gaps[6] = {v[1].at - byte_ - v[0].at, v[3].at - v[2].at, v[5].at - byte_ - command_end,
                              v[7].at - v[6].at,         v[8].at - byte_ - v[7].at, next_rise - v[9].at};
    for (int i = 0; i < 6; ++i) sum_[i] += gaps[i];
    whole_ += next_rise - v[0].at;
    ++count_;
  }

  joint_avr::AvrMegaArm& arm_;
  Duration byte_;
  std::vector<joint_avr::BusTraceEvent> events_;
  Duration sum_[6]{};
  Duration whole_{};
  int count_ = 0;
};

void loop_line(const std::string& name, const LoopWatch& w, double limit) {
  std::printf("# %s: %llu passes, worst %.1f us\n", name.c_str(), static_cast<unsigned long long>(w.passes()),
              double(w.worst()) / 16.0);
  bench::bench_line(name.c_str(), double(w.worst()), "cycles", limit);
}

int bench_baud(std::uint32_t baud) {
  joint_avr::AvrMegaArm arm = make_arm(baud);
  arm.advance(std::chrono::milliseconds(500));  // start-up commands done, polling
  // Refresh: every transaction while idle is a get_position (two select edges each).
  const auto edges0 = arm.select_edges();
  const TimePoint t0 = arm.now();
  {
    const TurnaroundTrace trace(arm);
    arm.advance(std::chrono::seconds(3));
    trace.print(baud);
    // The joints' own share, on their chips: from the event (as the chip saw it) to the
    // first byte written to UDR0, in cycles.
    joint_avr::LatencyStats rise, rx, fall;
    for (int j = 1; j <= arm.arm().joint_count(); ++j) {
      const auto& joint = arm.arm().joint(j);
      for (auto [to, from] : {std::pair{&rise, &joint.select_rise_to_tx()}, std::pair{&rx, &joint.rx_to_tx()},
                              std::pair{&fall, &joint.select_fall_to_tx()}}) {
        to->count += from->count;
        to->total_cycles += from->total_cycles;
        to->max_cycles = std::max(to->max_cycles, from->max_cycles);
      }
    }
    auto mean = [](const joint_avr::LatencyStats& s) { return s.count == 0 ? 0.0 : double(s.total_cycles) / s.count; };
    std::printf("# joint chips, event -> first reply byte written (cycles, mean / worst since start): select rise "
                "%.0f / %llu, last byte in %.0f / %llu, select fall %.0f / %llu\n",
                mean(rise), static_cast<unsigned long long>(rise.max_cycles), mean(rx),
                static_cast<unsigned long long>(rx.max_cycles), mean(fall),
                static_cast<unsigned long long>(fall.max_cycles));
  }
  const double sweeps = double(arm.select_edges() - edges0) / 2.0 / 7.0;
  const double rate = sweeps / seconds(arm.now() - t0);
  // The floor at the rate the wire really runs: the AVRs' U2X rate (117,647 baud for 115200).
  const double floor_rate = 1.0 / seconds(arm.arm().bus().byte_time() * (8 * 7));
  std::printf("BENCH mega_refresh_%u %.3f sweeps/s limit %.3f ratio %.3f\n", baud, rate, floor_rate,
              rate / floor_rate);

  const std::vector<std::uint8_t> request{0x55, 0x55, 0x0A, 0x15, 0x07, 1, 2, 3, 4, 5, 6, 7};
  const std::size_t reply_bytes = 2 + 1 + 1 + 1 + 3 * 7;
  const Duration wire = wire_time(request.size() + reply_bytes, baud);
  Duration worst{};
  int lost = 0;
  auto polling = std::make_unique<LoopWatch>(arm);
  for (int i = 0; i < 200; ++i) {
    arm.advance(std::chrono::microseconds(2000 + (i * 7919) % 9000));  // spread over the poll cycle
    arm.take_upstream();
    const TimePoint sent = arm.now();
    arm.send_upstream(request);
    std::size_t got = 0;
    TimePoint last{};
    while (got < reply_bytes && arm.now() - sent < std::chrono::milliseconds(500)) {
      arm.advance(std::chrono::microseconds(100));
      for (const auto& b : arm.take_upstream()) {
        ++got;
        last = b.at;
      }
    }
    if (got < reply_bytes) {
      ++lost;
      continue;
    }
    worst = std::max(worst, last - sent);
  }
  std::printf("# mega_round_trip_%u: worst %.2f ms, wire time %.2f ms, %d of 200 unanswered\n", baud,
              seconds(worst) * 1e3, seconds(wire) * 1e3, lost);
  const double limit_ms = seconds(wire) * 1e3 / 0.9;
  std::printf("BENCH mega_round_trip_%u %.3f ms limit %.3f ratio %.3f\n", baud, seconds(worst) * 1e3, limit_ms,
              seconds(worst) * 1e3 / limit_ms);
  loop_line("mega_loop_worst_polling_" + std::to_string(baud), *polling, 2778);
  polling.reset();
  {
    LoopWatch moving(arm);
    run_moves(arm);
    loop_line("mega_loop_worst_" + std::to_string(baud), moving, 177778);
  }
  {
    // Polling seven moving joints, each reading checked against the joint's setpoint ramp
    // (the stall check, floating point, after the next transaction has started): the
    // move's planning pass is left out (watched from 200 ms after the request).
    arm.send_upstream(move_all(300, 2500));
    arm.advance(std::chrono::milliseconds(200));
    LoopWatch ramp(arm);
    arm.advance(std::chrono::milliseconds(2000));
    loop_line("mega_loop_worst_moving_" + std::to_string(baud), ramp, 2778);
  }
  return lost;
}

}  // namespace

int main() {
  const std::string elf = joint_avr::default_mega_firmware_elf();
  const bench::Sizes sizes = bench::elf_sizes(elf);
  if (!sizes.ok) {
    std::fprintf(stderr, "bench_mega_controller: cannot read sizes of %s with avr-size\n", elf.c_str());
    return 1;
  }
  bench::bench_line("mega_flash", double(sizes.text + sizes.data), "bytes", 65536);
  bench::bench_line("mega_static_ram", double(sizes.data + sizes.bss + sizes.noinit), "bytes", 4096);
  int lost = 0;
  for (const std::uint32_t baud : {9600u, 115200u}) lost += bench_baud(baud);
  return lost == 0 ? 0 : 1;
}
