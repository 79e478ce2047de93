// Action groups in a byte-addressed persistent memory (the Mega's 4 KiB EEPROM; a file on
// Linux, CoreDevice; RAM in tests), written one byte at a time without ever blocking the
// main loop.
//
// Layout: bytes 0..2 "AG" + format 1; a directory of `entries` entries of 8 bytes at 4 (the
// owner's choice at begin(): 16 on the Mega, 255 on Linux); group data from data_at() to
// `end` (begin(); the bytes after it are the owner's, e.g. the servo settings). Entry: group
// (0xFF = free), servo count, action count u16, start bits 0..15, sequence, start bits
// 16..23 (0xFF there, as an image before it was used left it, reads as 0). An action is
// stored as received: ms u16, then {servo u8, position u16} x servo count (2 + 3n bytes;
// little-endian).
//
// Never half-stored: a download writes its actions into space no stored group uses; at
// the end the new entry is written with its group byte last (one byte write: the commit),
// then the old entry of that group (if any) is freed. A reset anywhere before the commit
// leaves the old group; a reset between commit and free leaves two entries, and begin()
// keeps the one with the newer sequence. Writes are queued in order, so the memory always
// holds a prefix of them.
#pragma once

#include <stdint.h>

namespace armctl {
namespace controller {

class GroupMemory {
 public:
  virtual uint32_t size() const = 0;  // at most 2^24 bytes: a start has 24 bits
  virtual uint8_t read(uint32_t address) = 0;
  virtual bool ready() = 0;                               // a byte write may start
  virtual void write(uint32_t address, uint8_t value) = 0;  // starts one (only when ready)
 protected:
  ~GroupMemory() {}
};

struct GroupInfo {
  uint8_t group;
  uint8_t servo_count;
  uint16_t action_count;
  uint32_t start;
};

class GroupStore {
 public:
  struct Entry {
    uint8_t group;
    uint8_t servo_count;
    uint16_t action_count;
    uint32_t start;
    uint8_t seq;
  };
  static const uint8_t mega_entries = 16;  // the directory the Mega keeps (4 KiB EEPROM)
  static const uint16_t directory_at = 4;
  static const uint8_t queue_capacity = 48;
  static const uint8_t no_group = 0xFF;

  static constexpr uint16_t action_bytes(uint8_t servo_count) { return static_cast<uint16_t>(2 + 3 * servo_count); }

  // Reads the directory into `directory` (`entries` of them, 1..255, owned by the caller and
  // alive as long as the store); a memory without the header is formatted (queued writes).
  // Groups live below `end` (0: the whole memory); a stored group reaching past it is
  // dropped. write() may also queue bytes above it (the owner's own records share the
  // queue, so all writes land in the order asked).
  void begin(GroupMemory* memory, uint32_t end, Entry* directory, uint8_t entries);

  uint8_t entries() const { return entries_; }
  uint32_t data_at() const { return directory_at + 8u * entries_; }
  bool find(uint8_t group, GroupInfo* info) const;
  // Start of `bytes` of space that no stored group uses, and a free directory entry for
  // it: false if either is missing (the download does not fit).
  bool allocate(uint32_t bytes, uint32_t* start) const;
  // Bytes of group data the memory can hold in all.
  uint32_t capacity_bytes() const;

  // Queued writes; false (nothing queued) if the queue has no room for all of them.
  bool write(uint32_t address, const uint8_t* bytes, uint8_t count);
  bool commit(const GroupInfo& group);
  bool erase(uint8_t group);  // 255 = every group
  bool idle() const { return count_ == 0 && format_left_ == 0; }
  uint8_t queue_room() const { return static_cast<uint8_t>(queue_capacity - count_); }
  // Starts the next queued write if the memory is ready: call from the main loop.
  void service();

  // One stored action: its time and up to 7 {servo, position}; false if out of range.
  bool read_action(const GroupInfo& group, uint16_t index, uint16_t* ms, uint8_t* servos, uint16_t* positions);

 private:
  struct Pending {
    uint32_t address;
    uint8_t value;
  };
  bool queue(uint32_t address, uint8_t value);
  uint32_t end_of(const Entry& e) const { return e.start + uint32_t(e.action_count) * action_bytes(e.servo_count); }
  static uint32_t entry_at(uint8_t i) { return directory_at + 8u * i; }

  GroupMemory* memory_ = nullptr;
  uint32_t end_ = 0;
  Entry* dir_ = nullptr;
  uint8_t entries_ = 0;
  Pending queue_[queue_capacity];
  uint8_t head_ = 0;
  uint8_t count_ = 0;
  uint16_t format_left_ = 0;  // writes left to format a blank memory (entries, then header)
};

}  // namespace controller
}  // namespace armctl
