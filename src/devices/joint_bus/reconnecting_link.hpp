// A joint-bus link that survives its peer going away: `armctl sim scara` restarted under a
// controller on `--bus unix:...`, a USB-serial adapter pulled out. The link it wraps throws
// when the connection closes (or the peer breaks the protocol); this one then counts a loss,
// logs it, and from then on behaves like a bus with every joint unplugged (bytes go nowhere,
// nothing is received, so each transaction ends as "no answer", exactly as for a dead joint)
// while it opens the link again with back-off: 0.1 s, doubling, at most 2 s between tries.
// Each attempt and the recovery are logged. Nothing is replayed on recovery: what the
// controller does about a loss (drop pending commands, stop group playback) is its business
// (CoreDevice watches losses()).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "core/clock.hpp"
#include "core/error.hpp"
#include "transport/joint_bus_link.hpp"

namespace armctl::joint_bus {

struct ReconnectOptions {
  Duration first_delay = std::chrono::milliseconds(100);
  Duration max_delay = std::chrono::seconds(2);
  // What a caller sees while there is no link. The arm controller wants a bus with every
  // joint unplugged (its joints report no answer, as the spec has it); a host application
  // (`armctl serve`) wants the loss itself: the error that ended the link, then "lost ...;
  // reconnecting" from every call until it is back.
  enum class WhileLost { unplugged, refuse } while_lost = WhileLost::unplugged;
};

// The detail of what a ReconnectingLink in WhileLost::refuse throws once its link is lost
// (the error that ended it, then "the joint bus link is lost ...; reconnecting" from every
// call until it is back): the device is lost and being reopened. The joint-bus master keeps
// it as JointFailure::link_lost; device_lost() reads either.
struct LinkLost {
  std::string why;             // the error that ended the link
  std::uint64_t attempts = 0;  // reconnection attempts so far in this outage
};
// True when `error` says the device's link is lost and being reopened.
bool device_lost(const Error& error);

class ReconnectingLink final : public transport::JointBusLink {
 public:
  // Opens a link, or throws ArmctlError saying why not.
  using Opener = std::function<std::shared_ptr<transport::JointBusLink>()>;
  using Log = std::function<void(const std::string&)>;
  // Waits until the given instant of `clock` (a real wait on the steady clock; tests pass one
  // that advances a SimClock).
  using WaitUntil = std::function<void(TimePoint)>;

  // Opens the first link at once (its error is thrown: a controller that cannot reach its
  // bus at start should say so and exit). Later links must announce the same joint count
  // and baud as the first; one that does not is refused like a failed attempt.
  ReconnectingLink(Opener open, const Clock& clock, WaitUntil wait_until, Log log, ReconnectOptions options = {});

  int joint_count() const override { return joints_; }
  void set_select(int joint, bool high) override;
  void write(std::span<const std::uint8_t> bytes) override;
  void flush() override;
  std::optional<std::uint8_t> read_byte(TimePoint deadline) override;
  std::size_t drain() override;
  const Clock& clock() const override { return clock_; }
  std::uint32_t baud() const override { return baud_; }

  bool connected() const { return link_ != nullptr; }
  std::uint64_t losses() const { return losses_; }          // times the link was lost
  std::uint64_t attempts() const { return attempts_; }      // reconnection attempts, in all
  std::uint64_t recoveries() const { return recoveries_; }  // attempts that succeeded

 private:
  // Runs `use` on the link; a throw from it (other than a caller's invalid argument) is a
  // loss. False when there is no link (or it was just lost).
  template <typename Use>
  bool with_link(Use&& use);
  void lose(const std::string& why);
  // One attempt if one is due; true if the link is back.
  bool try_reconnect();
  // In WhileLost::refuse: throws the loss (io) when there is no link and none came back.
  void refuse_if_lost();

  Opener open_;
  const Clock& clock_;
  WaitUntil wait_until_;
  Log log_;
  ReconnectOptions options_;
  std::shared_ptr<transport::JointBusLink> link_;
  int joints_ = 0;
  std::uint32_t baud_ = 0;
  Duration delay_{};
  TimePoint next_attempt_{};
  TimePoint lost_at_{};
  std::string lost_why_;
  std::uint64_t attempts_in_outage_ = 0;
  std::uint64_t losses_ = 0;
  std::uint64_t attempts_ = 0;
  std::uint64_t recoveries_ = 0;
};

}  // namespace armctl::joint_bus
