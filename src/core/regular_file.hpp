// Reading a file armctl was given (a group file, a config, an arm file, a URDF) safely: only
// a regular file, at most `max_bytes`, checked on the opened descriptor before a byte is read.
// A directory would read as empty ("no actions"), a FIFO would block for ever, a sparse
// 2 GB file would cost seconds and gigabytes: each is refused at once, naming the path.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "core/error.hpp"

namespace armctl {

// The whole text of `path`. Errors (io; invalid_config when too large) read
// "<what> <path> is not a regular file (a directory)" and name the path through printable().
Result<std::string> read_regular_file(const std::filesystem::path& path, std::string_view what,
                                      std::uintmax_t max_bytes);

}  // namespace armctl
