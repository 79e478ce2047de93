// Crash-safe file replacement (group store, settings, points files, recordings, .rob files): after a kill -9 or power cut at any instant, `path` holds
// either its old content or the new content, never a mix.
//
// How: write a temporary file beside it, fsync it, rename it over `path` (rename is atomic
// within a file system), then fsync the directory so the rename itself is durable. A kill
// before the rename leaves only a stray temporary file (`is_temporary_name`), which loaders
// delete; the target is untouched.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "core/error.hpp"

namespace armctl {

Status write_file_atomically(const std::filesystem::path& path,
                             std::span<const std::uint8_t> bytes);

// Removes `path` durably (unlink + fsync of the directory). Missing file: Ok.
Status remove_file_durably(const std::filesystem::path& path);

// Whole file, or nullopt if it does not exist; other failures are errors. Only a regular
// file of at most `max_bytes` is read: a directory, a FIFO (opened without waiting for a
// writer) or a larger file (a sparse 2 GB one included) is an error at once, checked on the
// opened descriptor before any byte is read.
Result<std::optional<std::vector<std::uint8_t>>> read_whole_file(const std::filesystem::path& path,
                                                                 std::uintmax_t max_bytes);

// Temporary files are named "<final name>.tmp-<pid>".
bool is_temporary_name(std::string_view file_name);

}  // namespace armctl
