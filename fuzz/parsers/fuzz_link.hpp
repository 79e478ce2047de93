// A JointBusLink for fuzzing the bus master: the joints' side of the bus is whatever bytes
// the fuzzer gives. Each master operation gets a chunk of them, which arrive back to back
// at wire speed after a delay the fuzzer chooses; when a chunk is used up the bus is
// silent. Time is simulated (SimClock): a read with nothing to read jumps to its deadline.
// Every byte the master reads is logged per transaction (a transaction starts with the
// master's drain()), so the fuzzer can check that a success was built from bytes the
// joints really sent; select edges and writes are checked as they happen.
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <optional>
#include <span>
#include <vector>

#include "core/clock.hpp"
#include "transport/joint_bus_link.hpp"

namespace armctl::fuzz {

class FuzzJointBusLink final : public transport::JointBusLink {
 public:
  FuzzJointBusLink(int joints, std::uint32_t baud) : joints_(joints), baud_(baud), selected_(8, false) {}

  // The joints' bytes for the next operation: they arrive from now + delay on.
  void give(std::span<const std::uint8_t> bytes, Duration delay) {
    TimePoint t = std::max(clock_.now() + delay, last_arrival_);
    for (std::uint8_t b : bytes) {
      t += wire_time(1, baud_);
      pending_.push_back({b, t});
    }
    last_arrival_ = t;
  }

  int joint_count() const override { return joints_; }
  void set_select(int joint, bool high) override {
    expect(joint >= 1 && joint <= joints_, "select line of a joint that does not exist");
    if (high) expect(selected_count() == 0, "two joints selected at once");
    selected_[static_cast<std::size_t>(joint)] = high;
  }
  void write(std::span<const std::uint8_t> bytes) override {
    expect(selected_count() == 1, "bytes written with no joint selected");
    expect(bytes.size() == 2 || bytes.size() == 4, "a COMMAND word and at most one DATA word");
    unflushed_ += bytes.size();
  }
  void flush() override {
    clock_.advance(wire_time(unflushed_, baud_));
    unflushed_ = 0;
  }
  std::optional<std::uint8_t> read_byte(TimePoint deadline) override {
    expect(++reads_ < 1000000, "the master keeps reading (hang)");
    if (!pending_.empty() && pending_.front().at <= deadline) {
      clock_.advance_to(pending_.front().at);
      const std::uint8_t b = pending_.front().value;
      pending_.pop_front();
      if (!transactions_.empty()) transactions_.back().push_back(b);
      return b;
    }
    clock_.advance_to(deadline);
    return std::nullopt;
  }
  std::size_t drain() override {
    std::size_t n = 0;
    while (!pending_.empty() && pending_.front().at <= clock_.now()) {
      pending_.pop_front();
      ++n;
    }
    transactions_.emplace_back();  // the master drains at the start of every transaction
    return n;
  }
  const Clock& clock() const override { return clock_; }
  std::uint32_t baud() const override { return baud_; }

  int selected_count() const {
    int n = 0;
    for (bool s : selected_) n += s ? 1 : 0;
    return n;
  }
  // Bytes the master read, one entry per transaction (attempt), oldest first.
  const std::vector<std::vector<std::uint8_t>>& transactions() const { return transactions_; }
  void clear_transactions() { transactions_.clear(); }

  static void expect(bool ok, const char* what) {
    if (ok) return;
    std::fprintf(stderr, "fuzz_bus_master: %s\n", what);
    std::abort();
  }

 private:
  struct Arrival {
    std::uint8_t value;
    TimePoint at;
  };
  int joints_;
  std::uint32_t baud_;
  std::vector<bool> selected_;
  std::deque<Arrival> pending_;
  TimePoint last_arrival_{};
  std::size_t unflushed_ = 0;
  std::uint64_t reads_ = 0;
  SimClock clock_;
  std::vector<std::vector<std::uint8_t>> transactions_;
};

}  // namespace armctl::fuzz
