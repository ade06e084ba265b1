#pragma once
/// @file
/// The one way Talus writes a file a user named (`-o FILE`, a GeoTIFF, a grid,
/// a data file in an output folder): atomically, and never over anything that
/// is not a regular file.
///
/// Contract of write_file_atomically():
/// - the target, after following symbolic links, is either absent or a regular
///   file; a device (/dev/null, /dev/full), FIFO, socket or folder is refused
///   with an InputError before anything is written, and again just before the
///   rename (rename(2) would replace a device node with a regular file, which
///   as root breaks the machine);
/// - the content goes to a hidden temporary file in the target's own folder
///   (same file system, so the rename is atomic), is flushed to disk (fsync),
///   and is then renamed over the target: a reader sees the old file or the
///   whole new one, never a truncated one;
/// - on any failure (disk full, permissions, an exception from the writer) the
///   temporary file is removed and the previous target is left untouched.
/// A symbolic link as target is kept: the file it points to is replaced.
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace talus {

/// Throws InputError if `path` (after following symbolic links) exists and is
/// not a regular file, naming what it is, or is a protected input; `option` (e.g. "-o") prefixes
/// the message when given. Call it before expensive work so a bad target fails in a second;
/// write_file_atomically() checks again anyway.
void require_regular_output(const std::filesystem::path& path, std::string_view option = {});

/// Records `files` (those that exist) as inputs of this run: from now on
/// require_regular_output() and write_file_atomically() refuse a target that
/// is one of them (the same device and inode: a symbolic or hard link to an
/// input too). For commands (the CLI protects every file its terrain read
/// reached); process-wide, so a library user who means to overwrite an input
/// does not call it.
void protect_from_outputs(const std::vector<std::string>& files);

/// Calls `write(temporary)`, which must create and fill the file `temporary`,
/// then moves it over `path` as the contract above says. The target's folder
/// must exist. Throws InputError for a refused target or a missing folder and
/// talus::Error (or whatever `write` throws) for a failed write, after removing
/// the temporary.
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(const std::filesystem::path&)>& write);

/// Writes `text` to `path` with write_file_atomically(), creating the folders
/// on the way to it (figure and report data files).
void write_text_file(const std::filesystem::path& path, std::string_view text);

}  // namespace talus
