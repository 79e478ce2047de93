#include "devices/joint_bus/reconnecting_link.hpp"

#include <algorithm>
#include <chrono>

#include <fmt/core.h>

#include "core/error.hpp"
#include "devices/joint_bus/bus_failure.hpp"

namespace armctl::joint_bus {
namespace {

double seconds(Duration d) { return std::chrono::duration<double>(d).count(); }

}  // namespace

bool device_lost(const Error& error) {
  if (error.detail_as<LinkLost>()) return true;
  const JointFailure* failure = joint_failure(error);
  return failure && failure->link_lost;
}

ReconnectingLink::ReconnectingLink(Opener open, const Clock& clock, WaitUntil wait_until, Log log,
                                   ReconnectOptions options)
    : open_(std::move(open)),
      clock_(clock),
      wait_until_(std::move(wait_until)),
      log_(std::move(log)),
      options_(options),
      link_(open_()),
      joints_(link_->joint_count()),
      baud_(link_->baud()),
      delay_(options.first_delay) {}

template <typename Use>
bool ReconnectingLink::with_link(Use&& use) {
  if (!link_ && !try_reconnect()) return false;
  try {
    use(*link_);
    return true;
  } catch (const ArmctlError& e) {
    if (e.error().kind == ErrorKind::invalid_argument) throw;  // a caller's mistake, not the link's
    lose(e.error().message);
    if (options_.while_lost == ReconnectOptions::WhileLost::refuse)
      throw ArmctlError(Error{e.error().kind, e.error().message, LinkLost{lost_why_, 0}});
    return false;
  }
}

void ReconnectingLink::lose(const std::string& why) {
  link_.reset();
  lost_why_ = why;
  ++losses_;
  attempts_in_outage_ = 0;
  lost_at_ = clock_.now();
  delay_ = options_.first_delay;
  next_attempt_ = lost_at_ + delay_;
  if (log_)
    log_(fmt::format("joint bus link lost: {}; every joint counts as not answering, pending commands are "
                     "dropped; reconnecting in {:.1f} s",
                     why, seconds(delay_)));
}

bool ReconnectingLink::try_reconnect() {
  if (clock_.now() < next_attempt_) return false;
  ++attempts_;
  ++attempts_in_outage_;
  std::string failure;
  try {
    auto link = open_();
    if (link->joint_count() != joints_ || link->baud() != baud_) {
      failure = fmt::format("the bus now has {} joints at {} baud, not {} at {} (restart the controller to use it)",
                            link->joint_count(), link->baud(), joints_, baud_);
    } else {
      link_ = std::move(link);
    }
  } catch (const ArmctlError& e) {
    failure = e.what();
  }
  if (link_) {
    ++recoveries_;
    if (log_)
      log_(fmt::format("joint bus link back after {} attempt{} ({:.1f} s without it); joints hold where they "
                       "are until a new command",
                       attempts_in_outage_, attempts_in_outage_ == 1 ? "" : "s", seconds(clock_.now() - lost_at_)));
    return true;
  }
  delay_ = std::min(delay_ * 2, options_.max_delay);
  next_attempt_ = clock_.now() + delay_;
  if (log_)
    log_(fmt::format("joint bus reconnect attempt {} failed: {}; next in {:.1f} s", attempts_in_outage_, failure,
                     seconds(delay_)));
  return false;
}

void ReconnectingLink::refuse_if_lost() {
  if (options_.while_lost != ReconnectOptions::WhileLost::refuse || link_ || try_reconnect()) return;
  throw ArmctlError(Error{ErrorKind::io,
                          fmt::format("the joint bus link is lost ({}); reconnecting: {} attempt{} so far, the next "
                                      "in {:.1f} s",
                                      lost_why_, attempts_in_outage_, attempts_in_outage_ == 1 ? "" : "s",
                                      std::max(0.0, seconds(next_attempt_ - clock_.now()))),
                          LinkLost{lost_why_, attempts_in_outage_}});
}

void ReconnectingLink::set_select(int joint, bool high) {
  if (joint < 1 || joint > joints_)
    throw ArmctlError(ErrorKind::invalid_argument,
                      fmt::format("select line for joint {} does not exist: joints are 1..{}", joint, joints_));
  refuse_if_lost();
  with_link([&](transport::JointBusLink& l) { l.set_select(joint, high); });
}

void ReconnectingLink::write(std::span<const std::uint8_t> bytes) {
  refuse_if_lost();
  with_link([&](transport::JointBusLink& l) { l.write(bytes); });  // no link: like a cut wire
}

void ReconnectingLink::flush() {
  refuse_if_lost();
  with_link([](transport::JointBusLink& l) { l.flush(); });
}

std::optional<std::uint8_t> ReconnectingLink::read_byte(TimePoint deadline) {
  refuse_if_lost();
  if (link_) {
    std::optional<std::uint8_t> byte;
    if (with_link([&](transport::JointBusLink& l) { byte = l.read_byte(deadline); })) return byte;
  }
  // No link: nothing can arrive before the deadline. Attempts due meanwhile are made; a link
  // that comes back serves the next transaction, not this one (its request went nowhere).
  while (clock_.now() < deadline) {
    if (try_reconnect()) break;
    wait_until_(std::min(deadline, next_attempt_));
  }
  if (clock_.now() < deadline) wait_until_(deadline);
  return std::nullopt;
}

std::size_t ReconnectingLink::drain() {
  std::size_t n = 0;
  if (link_) with_link([&](transport::JointBusLink& l) { n = l.drain(); });
  return n;
}

}  // namespace armctl::joint_bus
