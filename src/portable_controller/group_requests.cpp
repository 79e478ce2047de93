// ControllerCore: action groups — GroupDownload (sub 1..5), GroupRun, GroupErase,
// GroupSpeed and playback. The decisions are those of docs/action-groups.md: anything
// inconsistent abandons the download without a reply; the stored group is only replaced
// by sub 5's commit (group_store.hpp).
#include "portable_controller/controller_core.hpp"
#include "portable_controller/counting.hpp"
#include "portable_controller/rc_codes.hpp"

namespace armctl {
namespace controller {

namespace {
const uint16_t max_actions = 1020;  // 4 blocks of 255
const uint8_t actions_per_block = 255;
const uint16_t max_group_speed = 1000;  // percent

uint8_t blocks_for(uint16_t actions) {
  return static_cast<uint8_t>((actions + actions_per_block - 1) / actions_per_block);
}
}  // namespace

void ControllerCore::notify(uint8_t command, uint8_t group, uint16_t passes) {
  const uint8_t data[3] = {group, static_cast<uint8_t>(passes & 0xFFu), static_cast<uint8_t>(passes >> 8)};
  upstream_->send_frame(command, data, 3);
}

void ControllerCore::service_groups() {
  groups_.service();
  if (awaiting_ == Awaiting::nothing || !groups_.idle()) return;
  // Acknowledged only once durably written.
  if (awaiting_ == Awaiting::erase) {
    upstream_->send_frame(rc_group_erase, nullptr, 0);
  } else {
    const uint8_t ack[2] = {static_cast<uint8_t>(awaiting_ == Awaiting::download_action ? 4 : 5), 0};
    upstream_->send_frame(rc_group_download, ack, 2);
  }
  awaiting_ = Awaiting::nothing;
}

void ControllerCore::on_group_download(const uint8_t* data, uint8_t length) {
  if (!download_step(data, length)) {
    download_stage_ = 0;  // abandoned: the host starts again at sub 1
    count_up(stats_.download_rejected);
  }
}

bool ControllerCore::download_step(const uint8_t* data, uint8_t length) {
  if (length < 2 || awaiting_ != Awaiting::nothing) return false;
  const uint8_t sub = data[0];
  const uint8_t group = data[1];
  if (sub == 1) {
    // group, then the action count as a run of bytes summing to it.
    download_stage_ = 0;
    if (group == GroupStore::no_group || length < 3 || length > 7) return false;
    uint16_t total = 0;
    for (uint8_t i = 2; i < length; ++i) total = static_cast<uint16_t>(total + data[i]);
    if (total < 1 || total > max_actions) return false;
    download_group_ = group;
    download_count_ = total;
    download_stage_ = 1;
    for (uint8_t i = 0; i < sizeof download_got_; ++i) download_got_[i] = 0;
    const uint8_t ack[2] = {1, 0};
    upstream_->send_frame(rc_group_download, ack, 2);
    return true;
  }
  if (download_stage_ == 0 || group != download_group_) return false;
  if (sub == 2) {
    // group 00 n 00; the whole group must fit now, or the download is refused.
    if (download_stage_ != 1 || length != 5 || data[2] != 0 || data[4] != 0) return false;
    const uint8_t n = data[3];
    if (n < 1 || n > count_) return false;
    const uint32_t bytes = uint32_t(download_count_) * GroupStore::action_bytes(n);
    if (!groups_.allocate(bytes, &download_start_)) {
      count_up(stats_.download_too_big);
      return false;
    }
    download_servos_ = n;
    download_stage_ = 2;
  } else if (sub == 3) {
    // group 00, then the blocks in use in order.
    const uint8_t blocks = blocks_for(download_count_);
    if (download_stage_ != 2 || length != 3 + blocks || data[2] != 0) return false;
    for (uint8_t b = 0; b < blocks; ++b)
      if (data[3 + b] != b) return false;
    download_stage_ = 3;
  } else if (sub == 4) {
    // group block index N ms {servo position} x n, N = 2 + 3n bytes.
    const uint8_t n = download_servos_;
    const uint8_t record = static_cast<uint8_t>(GroupStore::action_bytes(n));
    if (download_stage_ != 3 || length != 5 + record || data[4] != record) return false;
    const uint8_t block = data[2];
    const uint8_t index = data[3];
    const uint16_t slot = static_cast<uint16_t>(block * actions_per_block + index);
    if (block >= blocks_for(download_count_) || index >= actions_per_block || slot >= download_count_) return false;
    const uint8_t* action = data + 5;
    if (rc_u16(action) > rc_max_move_ms) return false;
    uint8_t servos[max_joints];
    uint16_t positions[max_joints];
    rc_read_targets(action + 2, n, servos, positions);
    Target targets[max_joints];
    uint8_t moving = 0;
    if (check_targets(servos, positions, n, targets, &moving) == Check::invalid) return false;
    if (!groups_.write(download_start_ + uint32_t(slot) * record, action, record)) return false;
    download_got_[slot / 8] = static_cast<uint8_t>(download_got_[slot / 8] | (1u << (slot % 8)));
    awaiting_ = Awaiting::download_action;
    return true;
  } else if (sub == 5) {
    if (download_stage_ != 3 || length != 2) return false;
    for (uint16_t slot = 0; slot < download_count_; ++slot)
      if ((download_got_[slot / 8] & (1u << (slot % 8))) == 0) return false;
    const GroupInfo info{download_group_, download_servos_, download_count_, download_start_};
    if (!groups_.commit(info)) return false;
    download_stage_ = 0;
    count_up(stats_.downloads);
    awaiting_ = Awaiting::download_end;
    return true;
  } else {
    return false;
  }
  const uint8_t ack[2] = {sub, 0};
  upstream_->send_frame(rc_group_download, ack, 2);
  return true;
}

void ControllerCore::stop_playing(bool notify_stop) {
  if (!playing_) return;
  playing_ = false;
  if (notify_stop) upstream_->send_frame(rc_group_stop, nullptr, 0);
}

void ControllerCore::on_group_run(const uint8_t* data, uint8_t length, uint32_t now_us) {
  GroupInfo info;
  // A group whose writes are still queued is not played from half-written memory.
  if (length != 3 || !groups_.idle() || !groups_.find(data[0], &info)) {
    count_up(stats_.ignored_frames);
    return;
  }
  stop_playing(true);  // the new run replaces the old one
  playing_ = true;
  play_ = info;
  play_count_ = rc_u16(data + 1);
  play_pass_ = 0;
  play_index_ = 0;
  play_due_us_ = now_us;
  notify(rc_group_run, info.group, play_count_);
}

void ControllerCore::play_next(uint32_t now_us) {
  if (play_index_ == play_.action_count) {
    play_index_ = 0;
    ++play_pass_;
    if (play_count_ != 0 && play_pass_ >= play_count_) {
      playing_ = false;
      notify(rc_group_erase, play_.group, play_count_);  // CMD 8: finished
      return;
    }
  }
  uint16_t ms = 0;
  uint8_t servos[max_joints];
  uint16_t positions[max_joints];
  groups_.read_action(play_, play_index_++, &ms, servos, positions);
  Target targets[max_joints];
  uint8_t moving = 0;
  uint32_t took_ms = 1;  // at least 1 ms per action: a group of 0 ms actions cannot spin
  if (check_targets(servos, positions, play_.servo_count, targets, &moving) == Check::ok && moving > 0) {
    uint32_t scaled = uint32_t(ms) * 100u / speeds_[play_.group];
    // Planned to end when it would have from its due instant: the action starts up to a
    // transaction late (the bus was busy), and that must not add up over a group.
    const uint32_t late_ms = (now_us - play_due_us_) / 1000u;
    scaled = scaled > late_ms + 1u ? scaled - late_ms : 1u;
    plan_move(targets, moving, static_cast<uint16_t>(scaled > rc_max_move_ms ? rc_max_move_ms : scaled), now_us);
    count_up(stats_.actions_played);
    if (planned_ms_ > took_ms) took_ms = planned_ms_;
  } else {
    count_up(stats_.actions_skipped);
  }
  play_due_us_ = now_us + took_ms * 1000u;
}

void ControllerCore::on_group_erase(const uint8_t* data, uint8_t length, uint32_t now_us) {
  if (length != 1 || awaiting_ != Awaiting::nothing || !groups_.erase(data[0])) {
    count_up(stats_.ignored_frames);
    return;
  }
  if (playing_ && (data[0] == GroupStore::no_group || data[0] == play_.group)) {
    stop_playing(true);
    halt(now_us);
  }
  awaiting_ = Awaiting::erase;
}

void ControllerCore::on_group_speed(const uint8_t* data, uint8_t length) {
  const uint16_t percent = length == 3 ? rc_u16(data + 1) : 0;
  if (percent < 1 || percent > max_group_speed) {
    count_up(stats_.ignored_frames);
    return;
  }
  for (uint8_t g = 0; g < 255; ++g)
    if (data[0] == GroupStore::no_group || data[0] == g) speeds_[g] = percent;
}

}  // namespace controller
}  // namespace armctl
