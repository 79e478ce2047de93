// The board's storage uses core's crash-safe files (core/atomic_file.hpp).
#pragma once

#include "core/atomic_file.hpp"

namespace armctl::rc_board {
using armctl::is_temporary_name;
using armctl::read_whole_file;
using armctl::remove_file_durably;
using armctl::write_file_atomically;
}  // namespace armctl::rc_board
