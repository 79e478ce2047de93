#include "portable_controller/group_store.hpp"

namespace armctl {
namespace controller {

namespace {
const uint8_t header[3] = {'A', 'G', 1};

uint16_t read_u16(GroupMemory* m, uint32_t at) {
  return static_cast<uint16_t>(m->read(at) | (m->read(at + 1) << 8));
}
bool newer(uint8_t a, uint8_t b) { return static_cast<int8_t>(a - b) > 0; }
}  // namespace

void GroupStore::begin(GroupMemory* memory, uint32_t end, Entry* directory, uint8_t entries) {
  memory_ = memory;
  dir_ = directory;
  entries_ = entries;
  end_ = end == 0 || end > memory->size() ? memory->size() : end;
  head_ = 0;
  count_ = 0;
  bool formatted = true;
  for (uint8_t i = 0; i < 3; ++i) formatted = formatted && memory_->read(i) == header[i];
  for (uint8_t i = 0; i < entries_; ++i) {
    const uint32_t at = entry_at(i);
    Entry& e = dir_[i];
    e.group = formatted ? memory_->read(at) : no_group;
    e.servo_count = memory_->read(at + 1);
    e.action_count = read_u16(memory_, at + 2);
    const uint8_t high = memory_->read(at + 7);
    e.start = read_u16(memory_, at + 4) | (uint32_t(high == 0xFF ? 0 : high) << 16);
    e.seq = memory_->read(at + 6);
    const bool sane = e.servo_count >= 1 && e.servo_count <= 7 && e.action_count >= 1 && e.start >= data_at() &&
                      end_of(e) <= end_;
    if (e.group != no_group && !sane) {
      e.group = no_group;
      queue(at, no_group);
    }
  }
  format_left_ = 0;
  if (!formatted) {
    // Every entry freed, then the header: written by service() ahead of the queue (a
    // directory of 255 entries would not fit it).
    format_left_ = static_cast<uint16_t>(entries_ + 3);
    return;
  }
  // A reset between a commit and the freeing of the old entry: keep the newer one.
  for (uint8_t i = 0; i < entries_; ++i) {
    for (uint8_t j = 0; j < entries_; ++j) {
      if (i == j || dir_[i].group == no_group || dir_[i].group != dir_[j].group) continue;
      const uint8_t older = newer(dir_[i].seq, dir_[j].seq) ? j : i;
      dir_[older].group = no_group;
      queue(entry_at(older), no_group);
    }
  }
}

bool GroupStore::find(uint8_t group, GroupInfo* info) const {
  if (group == no_group) return false;
  for (uint8_t i = 0; i < entries_; ++i) {
    if (dir_[i].group != group) continue;
    *info = GroupInfo{group, dir_[i].servo_count, dir_[i].action_count, dir_[i].start};
    return true;
  }
  return false;
}

uint32_t GroupStore::capacity_bytes() const {
  return memory_ == nullptr ? 0 : end_ - data_at();
}

bool GroupStore::allocate(uint32_t bytes, uint32_t* start) const {
  bool free_entry = false;
  for (uint8_t i = 0; i < entries_; ++i) free_entry = free_entry || dir_[i].group == no_group;
  if (!free_entry || memory_ == nullptr || bytes == 0) return false;
  // First fit: try the data start and the end of every stored group.
  for (int16_t candidate = -1; candidate < int16_t(entries_); ++candidate) {
    uint32_t from = data_at();
    if (candidate >= 0) {
      if (dir_[candidate].group == no_group) continue;
      from = end_of(dir_[candidate]);
    }
    if (from + bytes > end_) continue;
    bool overlaps = false;
    for (uint8_t i = 0; i < entries_ && !overlaps; ++i) {
      if (dir_[i].group == no_group) continue;
      overlaps = from < end_of(dir_[i]) && dir_[i].start < from + bytes;
    }
    if (!overlaps) {
      *start = from;
      return true;
    }
  }
  return false;
}

bool GroupStore::queue(uint32_t address, uint8_t value) {
  if (count_ == queue_capacity) return false;
  queue_[(head_ + count_) % queue_capacity] = Pending{address, value};
  ++count_;
  return true;
}

bool GroupStore::write(uint32_t address, const uint8_t* bytes, uint8_t n) {
  if (n > queue_room() || memory_ == nullptr || address + n > memory_->size()) return false;
  for (uint8_t i = 0; i < n; ++i) queue(address + i, bytes[i]);
  return true;
}

bool GroupStore::commit(const GroupInfo& g) {
  int16_t slot = -1, old = -1;
  for (uint8_t i = 0; i < entries_; ++i) {
    if (dir_[i].group == no_group && slot < 0) slot = int16_t(i);
    if (dir_[i].group == g.group) old = int16_t(i);
  }
  if (slot < 0 || queue_room() < 9 || g.group == no_group) return false;
  const uint8_t seq = old >= 0 ? static_cast<uint8_t>(dir_[old].seq + 1) : 0;
  const uint32_t at = entry_at(uint8_t(slot));
  const uint8_t fields[7] = {g.servo_count,
                             static_cast<uint8_t>(g.action_count & 0xFFu),
                             static_cast<uint8_t>(g.action_count >> 8),
                             static_cast<uint8_t>(g.start & 0xFFu),
                             static_cast<uint8_t>(g.start >> 8),
                             seq,
                             static_cast<uint8_t>(g.start >> 16)};
  for (uint8_t i = 0; i < 7; ++i) queue(at + 1 + i, fields[i]);
  queue(at, g.group);  // the commit
  if (old >= 0) {
    queue(entry_at(uint8_t(old)), no_group);
    dir_[old].group = no_group;
  }
  dir_[slot] = Entry{g.group, g.servo_count, g.action_count, g.start, seq};
  return true;
}

bool GroupStore::erase(uint8_t group) {
  uint8_t needed = 0;
  for (uint8_t i = 0; i < entries_; ++i)
    if (dir_[i].group != no_group && (group == no_group || dir_[i].group == group)) ++needed;
  if (needed > queue_room()) return false;
  for (uint8_t i = 0; i < entries_; ++i) {
    if (dir_[i].group == no_group || (group != no_group && dir_[i].group != group)) continue;
    queue(entry_at(i), no_group);
    dir_[i].group = no_group;
  }
  return true;
}

void GroupStore::service() {
  if (format_left_ > 0) {
    if (!memory_->ready()) return;
    const uint16_t i = static_cast<uint16_t>(entries_ + 3 - format_left_);
    if (i < entries_) memory_->write(entry_at(static_cast<uint8_t>(i)), no_group);
    else memory_->write(i - entries_, header[i - entries_]);
    --format_left_;
    return;
  }
  if (count_ == 0 || !memory_->ready()) return;
  const Pending p = queue_[head_];
  memory_->write(p.address, p.value);
  head_ = static_cast<uint8_t>((head_ + 1) % queue_capacity);
  --count_;
}

bool GroupStore::read_action(const GroupInfo& g, uint16_t index, uint16_t* ms, uint8_t* servos,
                             uint16_t* positions) {
  if (index >= g.action_count) return false;
  uint32_t at = g.start + uint32_t(index) * action_bytes(g.servo_count);
  *ms = read_u16(memory_, at);
  at += 2;
  for (uint8_t k = 0; k < g.servo_count; ++k) {
    servos[k] = memory_->read(at);
    positions[k] = read_u16(memory_, at + 1);
    at += 3;
  }
  return true;
}

}  // namespace controller
}  // namespace armctl
