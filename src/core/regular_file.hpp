// Reading a file armctl was given (a group file, a config, an arm file, a URDF) safely: only
// a regular file, at most `max_bytes`, checked on the opened descriptor before a byte is read.
// A directory would read as empty ("no actions"), a FIFO would block for ever, a sparse
// 2 GB file would cost seconds and gigabytes: each is refused at once, naming the path.
#pragma once

#include <sys/types.h>

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

// The UTF-8 byte-order mark (EF BB BF) some editors put at the start of a text file.
inline constexpr std::string_view kUtf8Bom = "\xEF\xBB\xBF";

// A text file armctl parses (program, path, points, recording, group file, JSON config):
// read_regular_file, then a leading UTF-8 byte-order mark dropped, so that it is not read as
// part of the first word and line/column numbers in errors count from the first character.
// Binary files (.rob) and writers that keep the file's bytes use read_regular_file.
Result<std::string> read_text_file(const std::filesystem::path& path, std::string_view what,
                                   std::uintmax_t max_bytes);

// "a directory", "a FIFO", ... for messages about a file of the wrong type (st_mode).
const char* file_type_name(mode_t mode);

}  // namespace armctl
