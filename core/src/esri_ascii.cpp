#include "talus/core/esri_ascii.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <optional>
#include <sstream>
#include <string_view>

#include "talus/core/error.hpp"
#include "talus/core/input_file.hpp"
#include "talus/core/output_file.hpp"

namespace talus {
namespace {

/// std::isspace in the "C" locale, inline: the library call (locale lookup
/// per character) was a quarter of reading a 3601² grid.
constexpr bool is_space(char c) {
  return c == ' ' || c == '\n' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/// Splits text into whitespace-separated tokens, remembering each one's line.
class Tokenizer {
 public:
  explicit Tokenizer(std::string_view text) : text_(text) {}

  /// Next token, or nullopt at the end of the text.
  std::optional<std::string_view> next() {
    while (pos_ < text_.size() && is_space(text_[pos_])) {
      if (text_[pos_] == '\n') ++line_;
      ++pos_;
    }
    if (pos_ >= text_.size()) return std::nullopt;
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !is_space(text_[pos_])) ++pos_;
    token_line_ = line_;
    return text_.substr(start, pos_ - start);
  }
  std::size_t line() const { return token_line_; }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  std::size_t line_ = 1;
  std::size_t token_line_ = 1;
};

[[noreturn]] void fail(const std::string& source, std::size_t line, const std::string& what) {
  throw InputError(source + ":" + std::to_string(line) + ": " + what);
}

std::optional<double> parse_number(std::string_view token) {
  double value = 0.0;
  const char* first = token.data();
  const char* last = token.data() + token.size();
  if (first != last && *first == '+') ++first;  // from_chars rejects a leading '+'
  const auto [ptr, ec] = std::from_chars(first, last, value);
  if (ec != std::errc() || ptr != last) return std::nullopt;
  return value;
}

/// Why `token` is no number: out of a double's range (1e-400, 1e400) or not
/// a number at all.
std::string not_a_number(std::string_view token) {
  double value = 0.0;
  const char* first = token.data();
  const char* last = token.data() + token.size();
  if (first != last && *first == '+') ++first;
  const auto [ptr, ec] = std::from_chars(first, last, value);
  std::string quoted = "'";
  quoted += printable(std::string(token));
  quoted += "'";
  if (ec == std::errc::result_out_of_range && ptr == last) {
    return quoted + " is out of the range of a double (about 1e-308 to 1e308 in magnitude)";
  }
  return quoted + " is not a number";
}

bool starts_like_number(std::string_view token) {
  const char c = token.front();
  if (std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.') return true;
  // inf and nan parse as numbers: data (refused as non-finite), not a header key.
  return parse_number(token).has_value();
}

std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

struct Header {
  std::map<std::string, double> values;
  std::map<std::string, std::size_t> lines;
};

Header read_header(Tokenizer& tokens, const std::string& source,
                   std::optional<std::string_view>& first_data) {
  static const char* const kKnown[] = {"ncols",     "nrows",     "xllcorner", "xllcenter",
                                       "yllcorner", "yllcenter", "cellsize",  "nodata_value"};
  Header header;
  while (true) {
    auto token = tokens.next();
    if (!token) {
      if (header.values.empty()) fail(source, tokens.line(), "empty file: not an ESRI ASCII grid");
      fail(source, tokens.line(), "file ends inside the header: no elevation values");
    }
    if (starts_like_number(*token)) {
      if (header.values.empty()) {
        fail(source, tokens.line(),
             "the header is missing: the file starts with the value '" +
                 printable(std::string(*token)) +
                 "' (an ESRI ASCII grid starts with ncols, nrows, xllcorner, yllcorner, "
                 "cellsize)");
      }
      first_data = token;
      return header;
    }
    const std::string key = lower(*token);
    const std::size_t line = tokens.line();
    if (std::find(std::begin(kKnown), std::end(kKnown), key) == std::end(kKnown)) {
      fail(source, line,
           "unknown header key '" + printable(std::string(*token)) +
               "' (expected ncols, nrows, xllcorner|xllcenter, yllcorner|yllcenter, cellsize, "
               "NODATA_value): not an ESRI ASCII grid?");
    }
    if (header.values.count(key)) fail(source, line, "header key '" + key + "' appears twice");
    auto value_token = tokens.next();
    if (!value_token || tokens.line() != line)
      fail(source, line, "header key '" + key + "' has no value");
    const auto value = parse_number(*value_token);
    if (!value || !std::isfinite(*value)) {
      fail(source, line,
           "header key '" + key + "' has value '" + printable(std::string(*value_token)) +
               "', expected a finite number");
    }
    header.values[key] = *value;
    header.lines[key] = line;
    // One value per header line: "ncols 4 4" is a typo, not the first datum.
    Tokenizer peek = tokens;
    if (const auto extra = peek.next(); extra && peek.line() == line) {
      fail(source, line,
           "header key '" + key + "' has more than one value ('" + printable(std::string(*extra)) +
               "' follows)");
    }
  }
}

std::size_t positive_count(const Header& header, const std::string& key,
                           const std::string& source) {
  const double v = header.values.at(key);
  if (v < 2 || v != std::floor(v) || v > 1e8) {
    fail(source, header.lines.at(key),
         key + " must be an integer in [2, 1e8], got " + std::to_string(v));
  }
  return static_cast<std::size_t>(v);
}

double corner_or_centre(const Header& header, const std::string& axis, double cellsize,
                        const std::string& source) {
  const std::string corner = axis + "llcorner", centre = axis + "llcenter";
  const bool has_corner = header.values.count(corner) != 0;
  const bool has_centre = header.values.count(centre) != 0;
  if (has_corner && has_centre) {
    fail(source, header.lines.at(centre), "both " + corner + " and " + centre + " are given");
  }
  if (has_corner) return header.values.at(corner) + 0.5 * cellsize;
  if (has_centre) return header.values.at(centre);
  fail(source, 1, "missing header key " + corner + " (or " + centre + ")");
}

/// Values left after the header's first datum (included), and the line of the last.
std::pair<std::size_t, std::size_t> count_values(Tokenizer tokens) {
  std::size_t n = 1;
  while (tokens.next()) ++n;
  return {n, tokens.line()};
}

[[noreturn]] void fail_short(const std::string& source, std::size_t values, std::size_t line,
                             std::size_t ncols, std::size_t nrows) {
  fail(source, line,
       "file ends after " + std::to_string(values) +
           " values, expected ncols x nrows = " + std::to_string(ncols) + " x " +
           std::to_string(nrows) + " = " + std::to_string(ncols * nrows));
}

ElevationGrid parse_esri_ascii(std::string_view text, const std::string& source_name) {
  constexpr std::string_view kBom = "\xEF\xBB\xBF";  // some editors start UTF-8 with it
  if (text.substr(0, kBom.size()) == kBom) text.remove_prefix(kBom.size());
  Tokenizer tokens(text);
  std::optional<std::string_view> token;
  const Header header = read_header(tokens, source_name, token);

  for (const char* key : {"ncols", "nrows", "cellsize"}) {
    if (!header.values.count(key)) fail(source_name, 1, std::string("missing header key ") + key);
  }
  const std::size_t ncols = positive_count(header, "ncols", source_name);
  const std::size_t nrows = positive_count(header, "nrows", source_name);
  const double cellsize = header.values.at("cellsize");
  if (!(cellsize > 0.0)) {
    fail(source_name, header.lines.at("cellsize"),
         "cellsize must be positive, got " + std::to_string(cellsize));
  }
  const double x_min = corner_or_centre(header, "x", cellsize, source_name);
  const double y_min = corner_or_centre(header, "y", cellsize, source_name);
  const bool has_nodata = header.values.count("nodata_value") != 0;
  const double nodata = has_nodata ? header.values.at("nodata_value") : 0.0;

  // A 100-byte file must not claim 20000 x 20000: every value takes at least two bytes
  // (a digit and a separator), so a header claiming more values than half the text has
  // room for is short; only then are the values counted (a second pass), for the message.
  const std::size_t expected = ncols * nrows;
  if (expected > text.size() / 2 + 1) {
    const auto [values, last_line] = count_values(tokens);
    if (values < expected) fail_short(source_name, values, last_line, ncols, nrows);
  }
  ElevationGrid grid(ncols, nrows, cellsize, x_min, y_min);
  std::size_t count = 0;
  // Rows are expected one per line; a file that wraps rows over several lines
  // is accepted as long as the total count is right. The values come in line order, so
  // each line's count is checked when the next line starts (a map per value was a fifth
  // of reading a 3601² grid).
  std::size_t lines_with_values = 0, current_line = 0, on_line = 0;
  std::size_t first_ragged_line = 0, first_ragged_count = 0;
  const auto close_line = [&] {
    if (on_line == 0) return;
    ++lines_with_values;
    if (on_line != ncols && first_ragged_line == 0) {
      first_ragged_line = current_line;
      first_ragged_count = on_line;
    }
  };
  std::size_t last_line = tokens.line();
  for (; token; token = tokens.next()) {
    const std::size_t line = tokens.line();
    if (count == expected) {
      fail(source_name, line,
           "more values than ncols x nrows = " + std::to_string(expected) + " (extra token '" +
               printable(std::string(*token)) + "')");
    }
    const auto value = parse_number(*token);
    if (!value) fail(source_name, line, "value " + not_a_number(*token));
    if (!std::isfinite(*value)) {
      fail(source_name, line,
           "value '" + printable(std::string(*token)) +
               "' is not finite (NaN/Inf are not "
               "allowed; use NODATA_value for voids)");
    }
    if (!(has_nodata && *value == nodata) && !(std::abs(*value) <= kMaxElevationMagnitude)) {
      fail(source_name, line,
           "value '" + printable(std::string(*token)) + "' is beyond the supported elevation " +
               "magnitude of 1e9 m (a void? declare it with NODATA_value)");
    }
    const std::size_t row_from_north = count / ncols;
    const std::size_t i = count % ncols;
    const std::size_t j = nrows - 1 - row_from_north;
    if (has_nodata && *value == nodata) {
      grid.set_void(i, j);
    } else {
      grid.at(i, j) = *value;
    }
    if (line != current_line) {
      close_line();
      current_line = line;
      on_line = 0;
    }
    ++on_line;
    ++count;
    last_line = line;
  }
  close_line();
  if (count < expected) fail_short(source_name, count, last_line, ncols, nrows);
  if (lines_with_values == nrows && first_ragged_line != 0) {
    fail(source_name, first_ragged_line,
         "row has " + std::to_string(first_ragged_count) +
             " values, expected ncols = " + std::to_string(ncols));
  }
  return grid;
}

}  // namespace

ElevationGrid read_esri_ascii(std::istream& in, const std::string& source_name) {
  const std::string text = read_input_stream(in, source_name, kMaxGridFileBytes);
  return parse_esri_ascii(text, source_name);
}

ElevationGrid read_esri_ascii(const std::string& path) {
  return parse_esri_ascii(read_input_file(path, kMaxGridFileBytes), printable(path, 200));
}

void write_esri_ascii(const ElevationGrid& grid, std::ostream& out, double nodata_value) {
  out << std::setprecision(17);
  out << "ncols " << grid.ncols() << "\nnrows " << grid.nrows() << "\nxllcorner "
      << grid.x_min() - 0.5 * grid.cellsize() << "\nyllcorner "
      << grid.y_min() - 0.5 * grid.cellsize() << "\ncellsize " << grid.cellsize()
      << "\nNODATA_value " << nodata_value << "\n";
  char buffer[64];
  for (std::size_t r = 0; r < grid.nrows(); ++r) {
    const std::size_t j = grid.nrows() - 1 - r;
    for (std::size_t i = 0; i < grid.ncols(); ++i) {
      const double z = grid.valid(i, j) ? grid.at(i, j) : nodata_value;
      if (grid.valid(i, j) && z == nodata_value) {
        throw InputError("cannot write grid: node (" + std::to_string(i) + ", " +
                         std::to_string(j) + ") has the NODATA value as its elevation");
      }
      // Shortest representation that round-trips exactly.
      const auto result = std::to_chars(buffer, buffer + sizeof buffer, z);
      if (i) out << ' ';
      out.write(buffer, result.ptr - buffer);
    }
    out << '\n';
  }
  if (!out) throw InputError("write failed while writing an ESRI ASCII grid");
}

void write_esri_ascii(const ElevationGrid& grid, const std::string& path, double nodata_value) {
  write_file_atomically(path, [&](const std::filesystem::path& temporary) {
    std::ofstream out(temporary, std::ios::binary);
    if (!out) throw InputError(printable(path, 200) + ": cannot open file for writing");
    write_esri_ascii(grid, out, nodata_value);
    out.close();
    if (!out) throw Error(printable(path, 200) + ": write failed (disk full?)");
  });
}

}  // namespace talus
