#pragma once
/// @file
/// Reading an input file with bounds: every reader of Talus (ESRI ASCII grids,
/// path CSVs, vehicle and robot YAML) goes through read_input_file(), so no
/// input can make Talus read without end (/dev/zero), block (a FIFO) or take
/// memory out of proportion to the file.
#include <cstddef>
#include <istream>
#include <string>

namespace talus {

/// Size limits per kind of input [bytes]. A 10 000 x 10 000 grid at 12
/// characters a value is about 1.2 GB of text, the largest DEM the default
/// memory budget (memory_budget.hpp) could hold anyway.
inline constexpr std::size_t kMaxGridFileBytes = std::size_t{2} << 30;    ///< 2 GiB
inline constexpr std::size_t kMaxPathFileBytes = std::size_t{256} << 20;  ///< 256 MiB
inline constexpr std::size_t kMaxConfigFileBytes = std::size_t{1} << 20;  ///< 1 MiB (YAML)

/// InputError when the file name `path` holds a NUL byte: the C library would
/// read or write the file named by its part before the NUL (Python strings,
/// and C++ ones, can carry NUL; argv cannot).
void require_file_name(const std::string& path);

/// The whole content of the regular file `path`, at most `max_bytes` long.
/// Throws InputError, naming the file, for a file that does not exist or
/// cannot be opened, a directory, anything that is not a regular file (FIFO,
/// socket, device: they are refused before opening, so nothing blocks), a
/// file larger than `max_bytes`, a read error, or a NUL in its name.
std::string read_input_file(const std::string& path, std::size_t max_bytes);

/// The rest of `in`, at most `max_bytes`; InputError naming `source` beyond
/// that (a stream without end must not fill the memory).
std::string read_input_stream(std::istream& in, const std::string& source, std::size_t max_bytes);

/// `text` made safe to print in a one-line message: control and non-ASCII
/// bytes become \xNN escapes (\n, \t, \r as such), and a text longer than
/// `max_chars` is cut with "... (N bytes)".
std::string printable(const std::string& text, std::size_t max_chars = 64);

}  // namespace talus
