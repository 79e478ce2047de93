// Crash-safe file replacement (group store, settings, points files, recordings, .rob files): after a kill -9 or power cut at any instant, `path` holds
// either its old content or the new content, never a mix.
//
// How: write a temporary file beside it, fsync it, rename it over `path` (rename is atomic
// within a file system), then fsync the directory so the rename itself is durable. A kill
// before the rename leaves only a stray temporary file (`is_temporary_name`), which loaders
// delete; the target is untouched.
//
// Whose file it is stays the user's to say: a symlink is written through (its target is
// replaced, the link stays a link), the file keeps its mode (and owner where allowed), and a
// read-only file is refused, not replaced. Every writer (points files, recordings, group
// files, .rob files, the board's store and settings) goes through here, so all behave alike.
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

// Whether write_file_atomically(path, ...) would be allowed, asked before work that cannot
// be redone is spent on its content (a recording made by hand): the directory exists and
// may be written, the file (through symlinks) is a regular file that is not read-only, or
// does not exist yet. The error names the path and why, as write_file_atomically's would.
Status check_writable(const std::filesystem::path& path);

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
