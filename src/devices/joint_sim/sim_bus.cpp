#include "devices/joint_sim/sim_bus.hpp"

#include <algorithm>
#include <cstdio>

#include "core/error.hpp"

namespace armctl::joint_sim {

namespace {

constexpr std::size_t max_log_lines = 1000;

std::string hex(std::uint8_t b) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "%02X", b);
  return buf;
}

}  // namespace

SimBus::SimBus(std::uint32_t baud, std::vector<BusEndpoint*> endpoints, Duration byte_time)
    : baud_(baud), endpoints_(std::move(endpoints)) {
  if (baud_ == 0) {
    throw ArmctlError(ErrorKind::invalid_argument, "simulated bus: baud 0 (allowed: > 0)");
  }
  byte_time_ = byte_time > Duration::zero() ? byte_time : wire_time(1, baud_);
  lines_.resize(endpoints_.size());
  for (std::size_t i = 0; i < endpoints_.size(); ++i) {
    lines_[i].endpoint = endpoints_[i];
    lines_[i].synced = clock_.now();
  }
}

void SimBus::check_joint(int joint, const char* what) const {
  if (joint < 1 || joint > joint_count()) {
    throw ArmctlError(ErrorKind::invalid_argument,
                      std::string("simulated bus: ") + what + " joint " + std::to_string(joint) +
                          " has no select line (allowed: 1.." + std::to_string(joint_count()) +
                          ")");
  }
}

bool SimBus::select(int joint) const {
  check_joint(joint, "select of");
  return lines_[static_cast<std::size_t>(joint - 1)].select;
}

void SimBus::set_fault_plan(FaultPlan plan) {
  garbage_ = plan.garbage_bursts();
  std::stable_sort(garbage_.begin(), garbage_.end(),
                   [](const auto& a, const auto& b) { return a.at < b.at; });
  faults_ = FaultInjector(std::move(plan));
}

void SimBus::log(TimePoint t, const std::string& line) {
  char stamp[48];
  std::snprintf(stamp, sizeof stamp, "t=%.6f s: ",
                std::chrono::duration<double>(t.time_since_epoch()).count());
  std::string entry = stamp + line;
  if (log_sink_) log_sink_(entry);
  log_.push_back(std::move(entry));
  if (log_.size() > max_log_lines) log_.pop_front();
}

void SimBus::bring_to(JointLine& line, TimePoint t) {
  if (line.endpoint == nullptr || line.synced > t) return;
  line.endpoint->advance_to(t);
  line.synced = t;
}

void SimBus::sync() {
  const TimePoint t = clock_.now();
  for (std::size_t i = 0; i < lines_.size(); ++i) {
    JointLine& line = lines_[i];
    if (line.endpoint == nullptr) continue;
    bring_to(line, t);
    // A byte the endpoint began while being brought here goes on the wire now: its event
    // time is at or before `synced`, so next_event_time() would never look at it again
    // (an emulated chip stepped in short spans left a reply there until the next select
    // edge: issue 26, the 115200 move that moved nothing).
    if (!line.tx.busy) poll_joint_tx(static_cast<int>(i), t);
  }
  check_tx_contention(t);
}

TimePoint SimBus::next_event_time() const {
  TimePoint t = TimePoint::max();
  if (master_.busy) t = std::min(t, master_.end);
  for (const JointLine& line : lines_) {
    if (line.tx.busy) t = std::min(t, line.tx.end);
    if (line.endpoint != nullptr) {
      // An event at or before the time the endpoint was last brought to is already handled.
      const TimePoint e = line.endpoint->next_event_time();
      if (e > line.synced) t = std::min(t, e);
    }
  }
  if (!garbage_.empty()) t = std::min(t, garbage_.front().at);
  if (watch_) t = std::min(t, next_watch_);
  return t;
}

void SimBus::set_watch(Duration every, std::function<void(TimePoint)> watch) {
  watch_ = std::move(watch);
  watch_every_ = every;
  next_watch_ = watch_ ? clock_.now() + every : TimePoint::max();
}

TimePoint SimBus::next_byte_to_master() const {
  TimePoint t = TimePoint::max();
  for (const JointLine& line : lines_)
    if (line.tx.busy) t = std::min(t, line.tx.end);
  return t;
}

void SimBus::start_master_byte(TimePoint t) {
  const std::uint8_t value = master_queue_.front();
  master_queue_.pop_front();
  const ByteFate fate = faults_.next_byte(Wire::to_joints);
  ++stats_.bytes_to_joints;
  master_.busy = true;
  master_.deliver = !fate.drop;
  master_.corrupt = false;
  master_.value = static_cast<std::uint8_t>(value ^ fate.flip_mask);
  master_.start = t + fate.delay;
  master_.end = master_.start + byte_time_;
  if (fate.drop) {
    ++stats_.dropped;
    log(t, "fault: master byte " + hex(value) + " dropped");
  }
  if (fate.flip_mask != 0) {
    ++stats_.flipped;
    log(t, "fault: master byte " + hex(value) + " flipped to " + hex(master_.value));
  }
  if (fate.delay > Duration::zero()) {
    ++stats_.delayed;
    log(t, "fault: master byte " + hex(value) + " delayed by " +
               std::to_string(fate.delay.count() / 1000) + " us");
  }
}

void SimBus::poll_joint_tx(int index, TimePoint t) {
  JointLine& line = lines_[static_cast<std::size_t>(index)];
  const int joint = index + 1;
  for (;;) {
    const std::optional<TxByte> b = line.endpoint->next_tx_byte(t);
    if (!b) return;
    if (faults_.dead(joint)) {
      ++stats_.suppressed_dead;  // its TX is cut: take the bytes, put nothing on the wire
      continue;
    }
    std::uint8_t value = b->value;
    if (line.bytes_since_select < 2) {
      if (const auto number = faults_.wrong_number(joint)) {
        const auto word = static_cast<std::uint16_t>(*number);
        value = static_cast<std::uint8_t>(line.bytes_since_select == 0 ? word & 0xFF : word >> 8);
        ++stats_.wrong_number_rewrites;
        if (line.bytes_since_select == 0) {
          log(t, "fault: joint " + std::to_string(joint) + " answers READY as joint " +
                     std::to_string(*number));
        }
      }
    }
    ++line.bytes_since_select;

    const ByteFate fate = faults_.next_byte(Wire::to_master);
    WireByte& w = line.tx;
    w.busy = true;
    w.deliver = !fate.drop;
    w.corrupt = false;
    w.value = static_cast<std::uint8_t>(value ^ fate.flip_mask);
    // On the wire from when the joint's UART had it (an emulated chip is polled every few
    // microseconds, its byte was written in between), after the byte before it; one that
    // would already have ended (an endpoint advanced lazily) starts now.
    TimePoint begins = std::max(b->written, w.end);
    if (begins + byte_time_ <= t) begins = t;
    w.start = begins + fate.delay;
    w.end = w.start + byte_time_;
    const std::string who = "joint " + std::to_string(joint) + " byte " + hex(value);
    if (fate.drop) {
      ++stats_.dropped;
      log(t, "fault: " + who + " dropped");
    }
    if (fate.flip_mask != 0) {
      ++stats_.flipped;
      log(t, "fault: " + who + " flipped to " + hex(w.value));
    }
    if (fate.delay > Duration::zero()) {
      ++stats_.delayed;
      log(t, "fault: " + who + " delayed by " + std::to_string(fate.delay.count() / 1000) +
                 " us");
    }
    if (fate.garbage_before) {
      ++stats_.garbage_bytes;
      master_rx_.push_back(*fate.garbage_before);
      log(t, "fault: noise byte " + hex(*fate.garbage_before) + " on the master's RX");
    }

    // Bytes of two joints overlapping on the wire: the master's UART sees one garbled byte.
    for (std::size_t k = 0; k < lines_.size(); ++k) {
      WireByte& other = lines_[k].tx;
      if (static_cast<int>(k) == index || !other.busy) continue;
      if (!(other.start < w.end && w.start < other.end)) continue;
      WireByte& first = other.end <= w.end ? other : w;
      WireByte& second = other.end <= w.end ? w : other;
      first.value = static_cast<std::uint8_t>(first.value & second.value);
      first.corrupt = true;
      second.deliver = false;
      ++stats_.corrupted_bytes;
      log(t, "contention: joints " + std::to_string(k + 1) + " and " + std::to_string(joint) +
                 " send bytes at once; the master gets " + hex(first.value));
      if (!in_contention_) {
        in_contention_ = true;
        ++stats_.contentions;
      }
    }
    return;
  }
}

void SimBus::check_tx_contention(TimePoint t) {
  int driving = 0;
  std::string who;
  for (std::size_t i = 0; i < lines_.size(); ++i) {
    const JointLine& line = lines_[i];
    if (line.endpoint == nullptr || faults_.dead(static_cast<int>(i) + 1)) continue;
    if (line.endpoint->tx_enabled() || line.tx.busy) {
      ++driving;
      who += (who.empty() ? "" : ", ") + std::to_string(i + 1);
    }
  }
  if (driving >= 2) {
    if (!in_contention_) {
      in_contention_ = true;
      ++stats_.contentions;
      log(t, "contention: joints " + who + " drive TX at once");
    }
  } else {
    in_contention_ = false;
  }
}

void SimBus::process_events_at(TimePoint t) {
  clock_.advance_to(t);
  std::vector<bool>& touched = touched_;
  touched.assign(lines_.size(), false);

  if (master_.busy && master_.end <= t) {
    master_.busy = false;
    for (std::size_t i = 0; i < lines_.size(); ++i) {
      JointLine& line = lines_[i];
      if (line.endpoint == nullptr) continue;
      bring_to(line, t);
      if (master_.deliver) line.endpoint->on_rx_byte(master_.value, t);
      touched[i] = true;
    }
    if (!master_queue_.empty()) start_master_byte(t);
  }

  for (std::size_t i = 0; i < lines_.size(); ++i) {
    WireByte& w = lines_[i].tx;
    if (!w.busy || w.end > t) continue;
    w.busy = false;
    touched[i] = true;
    if (!w.deliver) continue;
    master_rx_.push_back(w.value);
    ++stats_.bytes_to_master;
  }

  while (!garbage_.empty() && garbage_.front().at <= t) {
    const auto& g = garbage_.front();
    for (std::uint8_t b : g.bytes) master_rx_.push_back(b);
    stats_.garbage_bytes += g.bytes.size();
    log(t, "fault: " + std::to_string(g.bytes.size()) + " noise bytes on the master's RX");
    garbage_.erase(garbage_.begin());
  }

  for (std::size_t i = 0; i < lines_.size(); ++i) {
    JointLine& line = lines_[i];
    if (line.endpoint == nullptr) continue;
    if (!touched[i]) {
      const TimePoint e = line.endpoint->next_event_time();
      touched[i] = e > line.synced && e <= t;
    }
    if (!touched[i]) continue;
    bring_to(line, t);
    if (!line.tx.busy) poll_joint_tx(static_cast<int>(i), t);
  }
  check_tx_contention(t);
  if (watch_ && t >= next_watch_) {
    sync();
    watch_(t);
    next_watch_ = t + watch_every_;
  }
}

void SimBus::set_select(int joint, bool high) {
  check_joint(joint, "set_select:");
  const std::size_t i = static_cast<std::size_t>(joint - 1);
  JointLine& line = lines_[i];
  if (line.select == high) return;
  const TimePoint t = clock_.now();
  line.select = high;
  if (high) line.bytes_since_select = 0;
  if (line.endpoint == nullptr) return;
  bring_to(line, t);
  line.endpoint->on_select(high, t);
  if (!line.tx.busy) poll_joint_tx(static_cast<int>(i), t);
  check_tx_contention(t);
}

void SimBus::write(std::span<const std::uint8_t> bytes) {
  master_queue_.insert(master_queue_.end(), bytes.begin(), bytes.end());
  if (!master_.busy && !master_queue_.empty()) start_master_byte(clock_.now());
}

void SimBus::flush() {
  while (master_tx_busy()) {
    process_events_at(std::max(next_event_time(), clock_.now()));
  }
}

std::optional<std::uint8_t> SimBus::read_byte(TimePoint deadline) {
  while (master_rx_.empty()) {
    const TimePoint t = next_event_time();
    if (t > deadline) {
      run_until(deadline);
      if (master_rx_.empty()) return std::nullopt;
      break;
    }
    process_events_at(std::max(t, clock_.now()));
  }
  const std::uint8_t b = master_rx_.front();
  master_rx_.pop_front();
  return b;
}

std::size_t SimBus::drain() {
  const std::size_t n = master_rx_.size();
  master_rx_.clear();
  return n;
}

void SimBus::run_until(TimePoint t) {
  for (;;) {
    const TimePoint next = next_event_time();
    if (next > t) break;
    process_events_at(std::max(next, clock_.now()));
  }
  clock_.advance_to(t);
  sync();
}

}  // namespace armctl::joint_sim
