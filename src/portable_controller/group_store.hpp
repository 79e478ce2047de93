// Action groups in a small byte-addressed persistent memory (the Mega's 4 KiB EEPROM; RAM
// in tests), written one byte at a time without ever blocking the main loop.
//
// Layout: bytes 0..2 "AG" + format 1; a directory of 16 entries of 8 bytes at 4; group data
// from 132 to `end` (begin(); the bytes after it are the owner's, e.g. the servo settings). Entry: group (0xFF = free), servo count, action count u16, start
// u16, sequence, spare. An action is stored as received: ms u16, then {servo u8, position
// u16} x servo count (2 + 3n bytes; little-endian).
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
  virtual uint16_t size() const = 0;
  virtual uint8_t read(uint16_t address) = 0;
  virtual bool ready() = 0;                               // a byte write may start
  virtual void write(uint16_t address, uint8_t value) = 0;  // starts one (only when ready)
 protected:
  ~GroupMemory() {}
};

struct GroupInfo {
  uint8_t group;
  uint8_t servo_count;
  uint16_t action_count;
  uint16_t start;
};

class GroupStore {
 public:
  static const uint8_t entries = 16;
  static const uint16_t directory_at = 4;
  static const uint16_t data_at = directory_at + 8 * entries;
  static const uint8_t queue_capacity = 48;
  static const uint8_t no_group = 0xFF;

  static uint16_t action_bytes(uint8_t servo_count) { return static_cast<uint16_t>(2 + 3 * servo_count); }

  // Reads the directory; a memory without the header is formatted (queued writes). Groups
  // live below `end` (0: the whole memory); a stored group reaching past it is dropped.
  // write() may also queue bytes above it (the owner's own records share the queue, so
  // all writes land in the order asked).
  void begin(GroupMemory* memory, uint16_t end = 0);

  bool find(uint8_t group, GroupInfo* info) const;
  // Start of `bytes` of space that no stored group uses, and a free directory entry for
  // it: false if either is missing (the download does not fit).
  bool allocate(uint16_t bytes, uint16_t* start) const;
  // Bytes of group data the memory can hold in all.
  uint16_t capacity_bytes() const;

  // Queued writes; false (nothing queued) if the queue has no room for all of them.
  bool write(uint16_t address, const uint8_t* bytes, uint8_t count);
  bool commit(const GroupInfo& group);
  bool erase(uint8_t group);  // 255 = every group
  bool idle() const { return count_ == 0; }
  uint8_t queue_room() const { return static_cast<uint8_t>(queue_capacity - count_); }
  // Starts the next queued write if the memory is ready: call from the main loop.
  void service();

  // One stored action: its time and up to 7 {servo, position}; false if out of range.
  bool read_action(const GroupInfo& group, uint16_t index, uint16_t* ms, uint8_t* servos, uint16_t* positions);

 private:
  struct Entry {
    uint8_t group;
    uint8_t servo_count;
    uint16_t action_count;
    uint16_t start;
    uint8_t seq;
  };
  struct Pending {
    uint16_t address;
    uint8_t value;
  };
  bool queue(uint16_t address, uint8_t value);
  uint16_t end_of(const Entry& e) const {
    return static_cast<uint16_t>(e.start + e.action_count * action_bytes(e.servo_count));
  }
  static uint16_t entry_at(uint8_t i) { return static_cast<uint16_t>(directory_at + 8 * i); }

  GroupMemory* memory_ = nullptr;
  uint16_t end_ = 0;
  Entry dir_[entries];
  Pending queue_[queue_capacity];
  uint8_t head_ = 0;
  uint8_t count_ = 0;
};

}  // namespace controller
}  // namespace armctl
