#include "devices/robot_commands/client.hpp"

#include <fmt/core.h>

namespace armctl::robot_commands {
namespace {

// More would hide a dead link for minutes behind retries.
constexpr int kMaxReadAttempts = 10;

std::string servo_list_text(const std::vector<std::uint8_t>& servos) {
  std::string out;
  for (auto s : servos) {
    if (!out.empty()) out += ',';
    out += std::to_string(s);
  }
  return out;
}


}  // namespace

Client::Client(RcLink& link, ClientOptions options)
    : link_(link), options_(options), servos_(rc::ServoRange::of_count(options.servo_count)) {
  if (options.servo_count < 1 || options.servo_count > static_cast<int>(rc::kMaxServosPerFrame)) {
    throw ArmctlError(ErrorKind::invalid_argument,
                      fmt::format("servo count {} is out of range (allowed 1..{})",
                                  options.servo_count, rc::kMaxServosPerFrame));
  }
  if (options.read_attempts < 1 || options.read_attempts > kMaxReadAttempts) {
    throw ArmctlError(ErrorKind::invalid_argument,
                      fmt::format("read attempts {} is out of range (allowed 1..{})",
                                  options.read_attempts, kMaxReadAttempts));
  }
}

std::vector<std::uint8_t> Client::all_servos() const {
  std::vector<std::uint8_t> out;
  for (int s = servos_.first; s <= servos_.last; ++s) out.push_back(static_cast<std::uint8_t>(s));
  return out;
}

Result<rc::Frame> Client::build(const rc::Request& request) const {
  return rc::encode(request, servos_);
}

Status Client::send(const rc::Frame& frame) {
  try {
    link_.send(frame);
  } catch (const ArmctlError& e) {  // links throw on OS failures; the SDK returns them
    return e.error();
  }
  ++stats_.frames_sent;
  return Ok{};
}

Result<std::optional<rc::Frame>> Client::receive(TimePoint deadline) {
  try {
    return link_.receive(deadline);
  } catch (const ArmctlError& e) {
    return e.error();
  }
}

void Client::deliver(const rc::GroupNotification& n) {
  GroupEvent e;
  e.group = n.group;
  e.count = n.count;
  e.received = link_.clock().now();
  switch (n.kind) {
    case GroupEventKind::started:
      e.kind = GroupEventKind::started;
      e.variant = !n.group;
      stop_sent_ = false;
      break;
    case GroupEventKind::stopped:
      // A bare CMD 7 answers our GroupStop; if we sent none, it is a board telling us the
      // group finished (spec "Action groups": real-board variant).
      e.kind = stop_sent_ ? GroupEventKind::stopped : GroupEventKind::finished;
      e.variant = !stop_sent_;
      stop_sent_ = false;
      break;
    case GroupEventKind::finished:
      e.kind = GroupEventKind::finished;
      break;
  }
  events_.push_back(e);
  if (callback_) callback_(e);
}

std::optional<rc::BoardMessage> Client::take(const rc::Frame& frame) {
  ++stats_.frames_received;
  if (frame.cmd == rc::kJointFaultReadCmd) {
    ++stats_.stale_replies;  // an extension's reply that came after its timeout
    return std::nullopt;
  }
  auto msg = rc::decode_board_message(frame);
  if (!msg) {
    ++stats_.unreadable_frames;
    return std::nullopt;
  }
  if (auto* n = std::get_if<rc::GroupNotification>(&msg.value())) {
    deliver(*n);
    return std::nullopt;
  }
  if (auto* positions = std::get_if<rc::ServoPositionReply>(&msg.value()); positions && pending_read_ &&
                                                                          !pending_read_->reply) {
    pending_read_->reply = std::move(*positions);  // request_positions' reply: kept for collect_positions
    return std::nullopt;
  }
  return msg.value();
}

Status Client::take_arrived() {
  const TimePoint now = link_.clock().now();
  for (;;) {
    auto f = receive(now);
    if (!f) return f.error();
    if (!*f) return Ok{};
    if (take(**f)) ++stats_.stale_replies;
  }
}

Error Client::no_reply(const rc::Frame& frame, std::optional<std::uint8_t> sub, Duration timeout) const {
  const char* name = "reply";
  if (auto c = rc::command_from_byte(frame.cmd)) name = rc::command_name(*c);
  // Robot Commands has no refusal: a board that refuses a request (a frame it finds
  // invalid, a group it cannot store) answers nothing, which looks like this timeout.
  return Error{ErrorKind::timeout,
               fmt::format("no {} reply (CMD {}{}) from {} within {} ms: the board may have refused "
                           "it (a board answers nothing to a request it refuses, e.g. one it "
                           "could not store; see its log) or be unreachable",
                           name, frame.cmd, sub ? fmt::format(" sub {}", *sub) : std::string(), link_.describe(),
                           std::chrono::duration_cast<std::chrono::milliseconds>(timeout).count())};
}

Result<rc::BoardMessage> Client::transact_read(const rc::Frame& frame, int attempts_made) {
  for (int attempt = attempts_made + 1;; ++attempt) {
    auto reply = transact(frame, std::nullopt, options_.reply_timeout);
    if (reply || reply.error().kind != ErrorKind::timeout || attempt >= options_.read_attempts) {
      if (!reply && attempt > 1) {
        return Error{reply.error().kind,
                     fmt::format("{} (sent {} times)", reply.error().message, attempt)};
      }
      return reply;
    }
    ++stats_.read_retries;
  }
}

Result<rc::BoardMessage> Client::transact(const rc::Frame& frame, std::optional<std::uint8_t> sub,
                                          Duration timeout) {
  if (auto drained = take_arrived(); !drained) return drained.error();
  if (auto sent = send(frame); !sent) return sent.error();
  const TimePoint deadline = link_.clock().now() + timeout;
  const char* name = "reply";
  if (auto c = rc::command_from_byte(frame.cmd)) name = rc::command_name(*c);
  for (;;) {
    auto received = receive(deadline);
    if (!received) return received.error();
    const std::optional<rc::Frame>& incoming = *received;
    if (!incoming) return no_reply(frame, sub, timeout);
    if (incoming->cmd == frame.cmd) {
      // Same CMD: a reply, or (CMD 8 with DATA) a notification, or garbage we must report.
      auto msg = rc::decode_board_message(*incoming);
      if (!msg) {
        ++stats_.frames_received;
        ++stats_.unreadable_frames;
        return Error{ErrorKind::protocol,
                     fmt::format("{} reply from {} is malformed ({}): {}", name, link_.describe(),
                                 rc::to_hex(rc::encode_frame(*incoming)), msg.error().message)};
      }
    }
    auto reply = take(*incoming);
    if (!reply) continue;
    if (rc::cmd_byte_of(*reply) != frame.cmd) {
      ++stats_.stale_replies;
      continue;
    }
    if (sub) {
      const auto* ack = std::get_if<rc::GroupDownloadAck>(&*reply);
      if (!ack || ack->sub != *sub) {
        ++stats_.stale_replies;
        continue;
      }
    }
    return *reply;
  }
}

// ------------------------------------------------------------------------------- servos

Status Client::move(const std::vector<ServoTarget>& targets, std::uint16_t time_ms) {
  auto f = build(rc::MultiServoMove{time_ms, targets});
  if (!f) return f.error();
  return send(*f);
}

Result<std::vector<ServoPosition>> Client::read_positions(const std::vector<std::uint8_t>& servos) {
  return read_positions_after(servos, 0);
}

Result<std::vector<ServoPosition>> Client::read_positions_after(const std::vector<std::uint8_t>& servos,
                                                                int attempts_made) {
  auto f = build(rc::ServoPositionRead{servos});
  if (!f) return f.error();
  if (pending_read_) (void)collect_positions();  // its reply must not be taken for this one's
  auto reply = transact_read(*f, attempts_made);
  if (!reply) return reply.error();
  return positions_answering(servos, std::move(std::get<rc::ServoPositionReply>(*reply).positions));
}

Status Client::request_positions(const std::vector<std::uint8_t>& servos) {
  auto f = build(rc::ServoPositionRead{servos});
  if (!f) return f.error();
  if (pending_read_) (void)collect_positions();
  if (auto drained = take_arrived(); !drained) return drained;
  if (auto sent = send(*f); !sent) return sent;
  pending_read_ = PendingRead{servos, *f, link_.clock().now() + options_.reply_timeout, std::nullopt};
  return Ok{};
}

Result<std::vector<ServoPosition>> Client::collect_positions() {
  if (!pending_read_)
    return Error{ErrorKind::invalid_argument, "collect_positions: no position request is in flight"};
  while (!pending_read_->reply) {
    auto f = receive(pending_read_->deadline);
    if (!f) {
      pending_read_.reset();
      return f.error();
    }
    if (!*f) {
      // No reply in time: the request was the first attempt; read_positions makes the rest.
      const PendingRead missed = std::move(*pending_read_);
      pending_read_.reset();
      if (options_.read_attempts <= 1) return no_reply(missed.request, std::nullopt, options_.reply_timeout);
      ++stats_.read_retries;
      return read_positions_after(missed.servos, 1);
    }
    if (take(**f)) ++stats_.stale_replies;
  }
  PendingRead done = std::move(*pending_read_);
  pending_read_.reset();
  return positions_answering(done.servos, std::move(done.reply->positions));
}

Result<std::vector<ServoPosition>> Client::positions_answering(const std::vector<std::uint8_t>& servos,
                                                               std::vector<ServoPosition> positions) const {
  std::vector<std::uint8_t> answered;
  for (const auto& p : positions) answered.push_back(p.servo);
  if (answered != servos) {
    return Error{ErrorKind::protocol,
                 fmt::format("ServoPositionRead: asked for servos {}, {} answered for {}",
                             servo_list_text(servos), link_.describe(),
                             servo_list_text(answered))};
  }
  return positions;
}

Result<std::vector<ServoPosition>> Client::read_all_positions() {
  return read_positions(all_servos());
}

Status Client::servos_off(const std::vector<std::uint8_t>& servos) {
  std::vector<rc::Frame> frames;
  if (options_.servo_off_per_servo) {
    for (auto s : servos) {
      auto f = build(rc::MultiServoOff{{s}});
      if (!f) return f.error();
      frames.push_back(std::move(*f));
    }
  }
  // The whole list is validated (and built) before anything is sent.
  auto all = build(rc::MultiServoOff{servos});
  if (!all) return all.error();
  if (!options_.servo_off_per_servo) frames.push_back(std::move(*all));
  for (const auto& f : frames) {
    if (auto sent = send(f); !sent) return sent;
  }
  auto back = read_positions(servos);
  if (!back) {
    return Error{back.error().kind,
                 fmt::format("torque-off sent, but the read-back that confirms the board "
                             "handled it failed: {}",
                             back.error().message)};
  }
  return Ok{};
}

Result<std::uint16_t> Client::battery_millivolts() {
  auto f = build(rc::GetBatteryVoltage{});
  if (!f) return f.error();
  auto reply = transact_read(*f);
  if (!reply) return reply.error();
  return std::get<rc::BatteryVoltageReply>(*reply).millivolts;
}

Result<std::vector<ServoOffset>> Client::read_offsets(const std::vector<std::uint8_t>& servos) {
  auto f = build(rc::ServoOffsetRead{servos});
  if (!f) return f.error();
  auto reply = transact_read(*f);
  if (!reply) return reply.error();
  const auto& offsets = std::get<rc::ServoOffsetReply>(*reply).offsets;
  std::vector<std::uint8_t> answered;
  for (const auto& o : offsets) answered.push_back(o.servo);
  if (answered != servos) {
    return Error{ErrorKind::protocol,
                 fmt::format("ServoOffsetRead: asked for servos {}, {} answered for {}",
                             servo_list_text(servos), link_.describe(),
                             servo_list_text(answered))};
  }
  for (const auto& o : offsets) held_offsets_[o.servo] = o.offset;
  return offsets;
}

Result<std::vector<int>> Client::held_offsets(const std::vector<std::uint8_t>& servos) {
  std::vector<std::uint8_t> unknown;
  for (std::uint8_t s : servos)
    if (!held_offsets_.contains(s)) unknown.push_back(s);
  if (!unknown.empty())
    if (auto read = read_offsets(unknown); !read) return read.error();
  std::vector<int> out;
  for (std::uint8_t s : servos) out.push_back(held_offsets_.at(s));
  return out;
}

Status Client::adjust_offset(std::uint8_t servo, int offset) {
  if (offset < rc::kOffsetMin || offset > rc::kOffsetMax) {
    return Error{ErrorKind::invalid_argument,
                 fmt::format("ServoOffsetAdjust: offset {} is out of range (allowed {}..{})",
                             offset, rc::kOffsetMin, rc::kOffsetMax)};
  }
  auto f = build(rc::ServoOffsetAdjust{servo, static_cast<std::int16_t>(offset)});
  if (!f) return f.error();
  held_offsets_.erase(servo);  // read again when next asked: what the servo took, not what was sent
  return send(*f);
}

Status Client::save_offsets(const std::vector<std::uint8_t>& servos) {
  auto f = build(rc::ServoOffsetWrite{servos});
  if (!f) return f.error();
  return send(*f);
}

Status Client::set_mode(std::uint8_t servo, ServoMode mode, std::int16_t speed) {
  if (speed < -rc::kMotorSpeedMax || speed > rc::kMotorSpeedMax) {
    return Error{ErrorKind::invalid_argument,
                 fmt::format("ServoSpeed: speed {} is out of range (allowed -{}..{}; negative "
                             "turns in reverse, servo mode ignores it)",
                             speed, rc::kMotorSpeedMax, rc::kMotorSpeedMax)};
  }
  auto f = build(rc::ServoSpeed{servo, mode, static_cast<std::uint16_t>(speed)});
  if (!f) return f.error();
  return send(*f);
}

Result<BusServoInfoReply> Client::read_bus_servo_info() {
  auto f = build(rc::BusServoInfoRead{});
  if (!f) return f.error();
  auto reply = transact_read(*f);
  if (!reply) return reply.error();
  return std::get<rc::BusServoInfoReply>(*reply);
}

Status Client::write_bus_servo_info(const BusServoInfoWrite& info) {
  auto f = build(info);
  if (!f) return f.error();
  held_offsets_.clear();  // a servo took a new ID: which servo holds which offset is read again
  return send(*f);
}

// ------------------------------------------------------------------------ extensions

Result<std::optional<rc::Frame>> Client::transact_raw(const rc::Frame& frame, Duration timeout) {
  if (auto drained = take_arrived(); !drained) return drained.error();
  if (auto sent = send(frame); !sent) return sent.error();
  const TimePoint deadline = link_.clock().now() + timeout;
  for (;;) {
    auto received = receive(deadline);
    if (!received) return received.error();
    if (!*received) return std::optional<rc::Frame>{};
    if ((*received)->cmd == frame.cmd) {
      ++stats_.frames_received;
      return *received;
    }
    if (take(**received)) ++stats_.stale_replies;
  }
}

template <typename Reply>
Result<std::optional<Reply>> Client::extension_request(const Result<rc::Frame>& request, const char* name,
                                                       std::uint8_t servo, Result<Reply> (*decode)(const rc::Frame&)) {
  if (!request) return request.error();
  if (has_joint_faults_ == false) return std::optional<Reply>{};
  auto reply = transact_raw(*request, options_.extension_timeout);
  if (!reply) return reply.error();
  if (!*reply) {
    if (has_joint_faults_ == true)
      return Error{ErrorKind::timeout,
                   fmt::format("no {} reply (CMD {}) for servo {} from {} within {} ms, though it answered before",
                               name, request->cmd, servo, link_.describe(),
                               std::chrono::duration_cast<std::chrono::milliseconds>(options_.extension_timeout)
                                   .count())};
    has_joint_faults_ = false;  // a board without armctl's extensions: ask no more
    return std::optional<Reply>{};
  }
  auto decoded = decode(**reply);
  if (!decoded) {
    ++stats_.unreadable_frames;
    return Error{decoded.error().kind, fmt::format("{} (from {})", decoded.error().message, link_.describe())};
  }
  if (decoded->servo != servo)
    return Error{ErrorKind::protocol, fmt::format("{}: asked for servo {}, {} answered for servo {}", name, servo,
                                                  link_.describe(), decoded->servo)};
  has_joint_faults_ = true;
  return std::optional<Reply>{*decoded};
}

Result<std::optional<rc::JointFaultReport>> Client::read_joint_faults(std::uint8_t servo) {
  return extension_request(rc::encode_joint_fault_read(servo, servos_), "JointFaultRead", servo,
                           &rc::decode_joint_fault_reply);
}

Result<std::optional<rc::JointFaultClearReply>> Client::clear_joint_faults(std::uint8_t servo) {
  return extension_request(rc::encode_joint_fault_clear(servo, servos_), "JointFaultClear", servo,
                           &rc::decode_joint_fault_clear_reply);
}

// ------------------------------------------------------------------------ action groups

Result<std::vector<rc::Frame>> Client::group_download_frames(
    std::uint8_t group, const std::vector<GroupAction>& actions) const {
  if (actions.empty() || actions.size() > static_cast<std::size_t>(rc::kActionsMax)) {
    return Error{ErrorKind::invalid_argument,
                 fmt::format("GroupDownload: {} actions given (allowed 1..{})", actions.size(),
                             rc::kActionsMax)};
  }
  const std::size_t per_action = actions.front().targets.size();
  for (std::size_t i = 0; i < actions.size(); ++i) {
    if (actions[i].targets.size() != per_action) {
      return Error{ErrorKind::invalid_argument,
                   fmt::format("GroupDownload: action {} has {} servos but action 1 has {} (every "
                               "action of a group needs the same number)",
                               i + 1, actions[i].targets.size(), per_action)};
    }
  }
  std::vector<rc::Request> requests;
  requests.push_back(rc::GroupDownloadBegin{group, static_cast<std::uint16_t>(actions.size())});
  requests.push_back(rc::GroupDownloadServoCount{group, static_cast<std::uint8_t>(per_action)});
  requests.push_back(
      rc::GroupDownloadBlocks{group, rc::blocks_for_actions(static_cast<int>(actions.size()))});
  for (std::size_t i = 0; i < actions.size(); ++i) {
    requests.push_back(rc::GroupDownloadAction{
        group, static_cast<std::uint8_t>(i / rc::kActionsPerBlock),
        static_cast<std::uint8_t>(i % rc::kActionsPerBlock), actions[i].time_ms,
        actions[i].targets});
  }
  requests.push_back(rc::GroupDownloadEnd{group});
  std::vector<rc::Frame> frames;
  for (std::size_t i = 0; i < requests.size(); ++i) {
    auto f = build(requests[i]);
    if (!f) {
      // Name the action so a user can find it in a long group file.
      if (i >= 3 && i < 3 + actions.size()) {
        return Error{f.error().kind, fmt::format("action {}: {}", i - 2, f.error().message)};
      }
      return f.error();
    }
    frames.push_back(std::move(f.value()));
  }
  return frames;
}

Status Client::download_group(std::uint8_t group, const std::vector<GroupAction>& actions) {
  auto frames = group_download_frames(group, actions);
  if (!frames) return frames.error();
  for (const auto& f : *frames) {
    auto ack = transact(f, f.data.at(0), options_.download_timeout);
    if (!ack) return ack.error();
  }
  return Ok{};
}

Status Client::run_group(std::uint8_t group, std::uint16_t times) {
  auto f = build(rc::GroupRun{group, times});
  if (!f) return f.error();
  stop_sent_ = false;
  return send(*f);
}

Status Client::stop_group() {
  auto f = build(rc::GroupStop{});
  if (!f) return f.error();
  stop_sent_ = true;
  return send(*f);
}

Status Client::erase_group(std::uint8_t group) {
  auto f = build(rc::GroupErase{group});
  if (!f) return f.error();
  auto reply = transact(*f, std::nullopt, options_.download_timeout);
  if (!reply) return reply.error();
  return Ok{};
}

Status Client::set_group_speed(std::uint8_t group, std::uint16_t percent) {
  auto f = build(rc::GroupSpeed{group, percent});
  if (!f) return f.error();
  return send(*f);
}

// ------------------------------------------------------------------------ notifications

std::optional<GroupEvent> Client::next_event() {
  if (events_.empty()) return std::nullopt;
  GroupEvent e = events_.front();
  events_.pop_front();
  return e;
}

Result<std::size_t> Client::pump_events(TimePoint deadline) {
  std::size_t delivered = 0;
  for (;;) {
    auto f = receive(deadline);
    if (!f) return f.error();
    if (!*f) return delivered;
    const std::size_t queued = events_.size();
    if (take(**f)) ++stats_.stale_replies;
    delivered += events_.size() - queued;
  }
}

Result<GroupEvent> Client::wait_event(TimePoint deadline) {
  const TimePoint asked_at = link_.clock().now();
  while (events_.empty()) {
    auto f = receive(deadline);
    if (!f) return f.error();
    if (!*f) {
      return Error{ErrorKind::timeout,
                   fmt::format("no action-group notification from {} within {} ms",
                               link_.describe(),
                               std::chrono::duration_cast<std::chrono::milliseconds>(deadline - asked_at)
                                   .count())};
    }
    if (take(**f)) ++stats_.stale_replies;
  }
  return *next_event();
}

}  // namespace armctl::robot_commands
