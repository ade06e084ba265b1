#include "talus/core/path_csv.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string_view>

#include "talus/core/error.hpp"
#include "talus/core/input_file.hpp"

namespace talus {
namespace {

[[noreturn]] void fail(const std::string& source, std::size_t line, const std::string& what) {
  throw InputError(source + ":" + std::to_string(line) + ": " + what);
}

bool is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && is_blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_blank(s.back())) s.remove_suffix(1);
  return s;
}

/// The text quoted for an error message, shortened if it is long.
std::string quoted(std::string_view s) {
  std::string out = "'";
  out += printable(std::string(s), 40);
  out += "'";
  return out;
}

/// Splits a line at every comma into trimmed fields.
std::vector<std::string_view> split_fields(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    if (comma == std::string_view::npos) {
      fields.push_back(trim(line.substr(start)));
      return fields;
    }
    fields.push_back(trim(line.substr(start, comma - start)));
    start = comma + 1;
  }
}

double parse_coordinate(std::string_view field, const char* name, const std::string& source,
                        std::size_t line) {
  if (field.empty()) fail(source, line, std::string(name) + " value is empty");
  const char* first = field.data();
  const char* last = field.data() + field.size();
  if (*first == '+' && last - first > 1 && first[1] != '-') ++first;  // from_chars rejects '+'
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(first, last, value);
  if (ec == std::errc::result_out_of_range) {
    fail(source, line, std::string(name) + " value " + quoted(field) + " is out of range");
  }
  if (ec != std::errc() || ptr != last) {
    fail(source, line, std::string(name) + " value " + quoted(field) + " is not a number");
  }
  if (!std::isfinite(value)) {
    fail(
        source, line,
        std::string(name) + " value " + quoted(field) + " is not finite (NaN/Inf are not allowed)");
  }
  return value;
}

std::vector<Vec2> parse_path_csv(std::string_view rest, const std::string& source_name) {
  constexpr std::string_view kBom = "\xEF\xBB\xBF";
  if (rest.substr(0, kBom.size()) == kBom) rest.remove_prefix(kBom.size());

  std::vector<Vec2> points;
  std::size_t line = 0;
  std::size_t first_blank = 0;    // line of the first blank line after the header, 0 = none
  std::size_t last_nonblank = 1;  // line of the last point (or the header)
  bool header_seen = false;
  while (!rest.empty()) {
    const std::size_t newline = rest.find('\n');
    const std::string_view raw = rest.substr(0, newline);
    rest.remove_prefix(newline == std::string_view::npos ? rest.size() : newline + 1);
    ++line;
    const std::string_view content = trim(raw);

    if (!header_seen) {
      const std::vector<std::string_view> names = split_fields(content);
      if (names.size() != 2 || names[0] != "x" || names[1] != "y") {
        fail(source_name, line,
             "the first line must be the header 'x,y', got " + quoted(content) +
                 ": not a path CSV file?");
      }
      header_seen = true;
      continue;
    }
    if (content.empty()) {
      if (!first_blank) first_blank = line;
      continue;
    }
    if (first_blank) {
      fail(source_name, line,
           "data after the blank line " + std::to_string(first_blank) +
               " (blank lines are allowed only at the end of the file)");
    }
    const std::vector<std::string_view> fields = split_fields(content);
    if (fields.size() != 2) {
      fail(source_name, line,
           "expected 2 columns x,y, got " + std::to_string(fields.size()) + " in " +
               quoted(content));
    }
    const Vec2 p(parse_coordinate(fields[0], "x", source_name, line),
                 parse_coordinate(fields[1], "y", source_name, line));
    if (!points.empty() && p == points.back()) {
      std::ostringstream msg;
      msg.precision(17);
      msg << "point " << points.size() << " (" << p.x() << ", " << p.y()
          << ") repeats the previous point: consecutive points must differ";
      fail(source_name, line, msg.str());
    }
    if (points.size() == kMaxPathPoints) {
      fail(source_name, line,
           "more than " + std::to_string(kMaxPathPoints) +
               " points: a path's way points feed an interpolating spline and its stations, "
               "whose memory and time grow with them; thin the path first");
    }
    points.push_back(p);
    last_nonblank = line;
  }
  if (!header_seen) fail(source_name, 1, "empty file: expected the header line 'x,y'");
  if (points.size() < 2) {
    fail(source_name, last_nonblank,
         "a path needs at least 2 points, got " + std::to_string(points.size()));
  }
  return points;
}

}  // namespace

std::vector<Vec2> read_path_csv(std::istream& in, const std::string& source_name) {
  return parse_path_csv(read_input_stream(in, source_name, kMaxPathFileBytes), source_name);
}

std::vector<Vec2> read_path_csv(const std::string& path) {
  return parse_path_csv(read_input_file(path, kMaxPathFileBytes), printable(path, 200));
}

}  // namespace talus
