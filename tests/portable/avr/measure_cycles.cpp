// Cycle counts of the joint controller's entry points on the ATmega328P, run in simavr by
// scripts/measure_portable_avr_cycles.sh. Timer1 runs at the CPU clock (prescaler 1); each
// call is bracketed by two TCNT1 reads and the cost of an empty bracket is subtracted.
// A small motor model (integer, on the chip) closes the loop through on_encoder_edge(), and
// a pseudo-random schedule of bus commands (drive_to anywhere in int16, drive_dist,
// set_speed 0..100, set_zone, set_pid_state, home) keeps the loop in every regime: at
// rest, accelerating, cruising, braking (square root), saturated, stalled, loop off.
// Results go out on the UART as "name worst mean count" lines; simavr prints them.
#include <avr/interrupt.h>
#include <avr/io.h>
#include <avr/sleep.h>

#include "portable/joint_controller.hpp"

using namespace armctl::joint_bus;

namespace {

JointController joint;

struct Stat {
  uint16_t worst;
  uint32_t sum;
  uint32_t count;
};
Stat tick_stat, sample_stat, compute_stat, edge_stat, rx_stat;
// control_compute() per tuning: the default one, and everything at its upper bound.
Stat default_tuning_stat, strong_tuning_stat;
uint16_t overhead;

inline uint16_t now_cycles() { return TCNT1; }

void record(Stat* s, uint16_t start, uint16_t end) {
  const uint16_t dt = static_cast<uint16_t>(end - start - overhead);
  if (dt > s->worst) s->worst = dt;
  s->sum += dt;
  ++s->count;
}

uint16_t lfsr = 0xACE1u;
uint16_t random16() {
  // 16-bit xorshift: deterministic, so every run measures the same schedule.
  lfsr ^= static_cast<uint16_t>(lfsr << 7);
  lfsr ^= static_cast<uint16_t>(lfsr >> 9);
  lfsr ^= static_cast<uint16_t>(lfsr << 8);
  return lfsr;
}

void put_char(char c) {
  while (!(UCSR0A & (1 << UDRE0))) {
  }
  UDR0 = static_cast<uint8_t>(c);
}
void put_text(const char* s) {
  while (*s) put_char(*s++);
}
void put_number(uint32_t v) {
  char digits[11];
  uint8_t n = 0;
  do {
    digits[n++] = static_cast<char>('0' + v % 10);
    v /= 10;
  } while (v != 0);
  while (n != 0) put_char(digits[--n]);
}
void put_stat(const char* name, const Stat& s) {
  put_text(name);
  put_char(' ');
  put_number(s.worst);
  put_char(' ');
  put_number(s.count ? s.sum / s.count : 0);
  put_char(' ');
  put_number(s.count);
  put_char('\n');
}

// Motor model: velocity in 1/256 click per tick follows duty with a first-order lag; the
// encoder levels follow the position through the 4x sequence 00 01 11 10.
int32_t motor_velocity_q8 = 0;
int32_t motor_position_q8 = 0;
int32_t encoder_clicks = 0;
bool stalled = false;
const uint8_t gray[4] = {0, 1, 3, 2};

void edge_to(int32_t clicks) {
  while (encoder_clicks != clicks) {
    encoder_clicks += clicks > encoder_clicks ? 1 : -1;
    const uint8_t levels = gray[static_cast<uint8_t>(encoder_clicks) & 3u];
    const uint16_t t0 = now_cycles();
    joint.on_encoder_edge((levels & 2) != 0, (levels & 1) != 0);
    const uint16_t t1 = now_cycles();
    record(&edge_stat, t0, t1);
  }
}

void motor_step(const DriveOutput& out) {
  // 255 duty = 25 clicks/tick (25,000 clicks/s) no-load; time constant 16 ticks.
  const int32_t drive = out.enable ? static_cast<int32_t>(out.duty) * 25 : 0;
  motor_velocity_q8 += (drive - motor_velocity_q8) / 16;
  if (stalled) motor_velocity_q8 = 0;
  motor_position_q8 += motor_velocity_q8;
  edge_to(motor_position_q8 / 256);
}

void send_word(int16_t w, uint32_t now) {
  uint16_t t0 = now_cycles();
  joint.on_rx_byte(word_low(w), now);
  uint16_t t1 = now_cycles();
  record(&rx_stat, t0, t1);
  t0 = now_cycles();
  joint.on_rx_byte(word_high(w), now);
  t1 = now_cycles();
  record(&rx_stat, t0, t1);
}

void transaction(int16_t command, int16_t data, bool takes_data, uint32_t now) {
  uint8_t byte;
  joint.on_select(true, now);
  while (joint.next_tx_byte(&byte)) {
  }
  send_word(command, now);
  if (takes_data) send_word(data, now);
  while (joint.next_tx_byte(&byte)) {
  }
  joint.on_select(false, now);
  while (joint.next_tx_byte(&byte)) {
  }
}

void random_command(uint32_t now) {
  const uint16_t r = random16();
  const int16_t value = static_cast<int16_t>(random16());
  switch (r % 16) {
    case 0: case 1: case 2: case 3: case 4:
      // Mostly moves the motor model can follow; sometimes anywhere in int16.
      transaction(cmd_drive_to, (r & 0x100) ? value : static_cast<int16_t>(value / 16), true, now);
      break;
    case 5: transaction(cmd_drive_dist, static_cast<int16_t>(value / 64), true, now); break;
    case 6: transaction(cmd_drive_dist_max, static_cast<int16_t>(value / 64), true, now); break;
    case 7: case 8:
      transaction(cmd_set_speed, static_cast<int16_t>(static_cast<uint16_t>(value) % 101u), true, now);
      break;
    case 9: transaction(cmd_set_zone, static_cast<int16_t>(static_cast<uint16_t>(value) % 50u), true, now); break;
    case 10: transaction(cmd_set_pid_state, (r & 0x200) ? 1 : 0, true, now); break;
    case 11: transaction(cmd_set_pid_state, 1, true, now); break;
    case 12: if ((r & 0x700) == 0) transaction(cmd_home, 0, false, now); break;
    case 13: transaction(cmd_check_target_reached, 0, false, now); break;
    case 14: transaction(cmd_get_position, 0, false, now); break;
    default: stalled = !stalled && (r & 0x300) == 0; break;
  }
}

}  // namespace

int main() {
  UBRR0 = 0;
  UCSR0B = (1 << TXEN0);
  TCCR1A = 0;
  TCCR1B = (1 << CS10);  // Timer1 at the CPU clock

  {
    const uint16_t t0 = now_cycles();
    const uint16_t t1 = now_cycles();
    overhead = static_cast<uint16_t>(t1 - t0);
  }

  JointTuning tuning = default_tuning();
  joint.begin(3, tuning, 115200);
  joint.init_encoder(false, false);

  uint32_t now_us = 0;
  for (uint16_t tick = 0; tick < 30000; ++tick) {
    now_us += 1000;
    if (random16() % 64 == 0) random_command(now_us);
    // Some joints get a much stronger tuning: large gains, fast ramps.
    if (tick == 15000) {
      tuning.max_speed_cps = max_speed_cps_limit;
      tuning.max_accel_cps2 = max_accel_cps2_limit;
      tuning.kp_q8 = 65535;
      tuning.ki_q8 = 65535;
      tuning.kd_q8 = 65535;
      joint.begin(3, tuning, 115200);
      joint.init_encoder(false, false);
      encoder_clicks = 0;
      motor_position_q8 = 0;
    }
    DriveOutput out;
    if (tick & 1) {
      const uint16_t t0 = now_cycles();
      out = joint.control_tick();
      const uint16_t t1 = now_cycles();
      record(&tick_stat, t0, t1);
    } else {
      uint16_t t0 = now_cycles();
      joint.control_sample();
      uint16_t t1 = now_cycles();
      record(&sample_stat, t0, t1);
      t0 = now_cycles();
      out = joint.control_compute();
      t1 = now_cycles();
      record(&compute_stat, t0, t1);
      record(tick < 15000 ? &default_tuning_stat : &strong_tuning_stat, t0, t1);
    }
    motor_step(out);
  }

  put_stat("control_tick", tick_stat);
  put_stat("control_sample", sample_stat);
  put_stat("control_compute", compute_stat);
  put_stat("compute_default", default_tuning_stat);
  put_stat("compute_strongest", strong_tuning_stat);
  put_stat("on_encoder_edge", edge_stat);
  put_stat("on_rx_byte", rx_stat);
  put_text("done\n");
  cli();
  sleep_mode();
}
