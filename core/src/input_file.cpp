#include "talus/core/input_file.hpp"

#include <sys/stat.h>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

#include "talus/core/error.hpp"

namespace talus {
namespace {

std::string bytes_text(std::size_t bytes) {
  char buffer[32];
  if (bytes >= (std::size_t{1} << 30)) {
    std::snprintf(buffer, sizeof buffer, "%.1f GiB", static_cast<double>(bytes) / (1 << 30));
  } else if (bytes >= (std::size_t{1} << 20)) {
    std::snprintf(buffer, sizeof buffer, "%.1f MiB", static_cast<double>(bytes) / (1 << 20));
  } else {
    std::snprintf(buffer, sizeof buffer, "%zu bytes", bytes);
  }
  return buffer;
}

}  // namespace

void require_file_name(const std::string& path) {
  if (path.find('\0') != std::string::npos)
    throw InputError(printable(path, 200) + ": a file name cannot contain a NUL byte");
}

std::string read_input_file(const std::string& path, std::size_t max_bytes) {
  require_file_name(path);
  const std::string name = printable(path, 200);
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) {
    throw InputError(name + ": cannot open file for reading (" + std::strerror(errno) + ")");
  }
  if (S_ISDIR(info.st_mode)) throw InputError(name + ": is a folder, not a file");
  if (!S_ISREG(info.st_mode)) {
    throw InputError(name +
                     ": is not a regular file (a device, FIFO or socket); give a file's path");
  }
  const auto size = static_cast<std::size_t>(info.st_size);
  if (size > max_bytes) {
    throw InputError(name + ": is " + bytes_text(size) + ", larger than the limit of " +
                     bytes_text(max_bytes) + " for this kind of input");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(name + ": cannot open file for reading");
  // Read at most max_bytes + 1 whatever stat said: the file may grow meanwhile.
  std::string text(size, '\0');
  in.read(text.data(), static_cast<std::streamsize>(size));
  text.resize(static_cast<std::size_t>(in.gcount()));
  if (in.bad()) throw InputError(name + ": read error");
  if (in.peek() != std::char_traits<char>::eof()) {
    throw InputError(name + ": grew while being read; it must not change meanwhile");
  }
  return text;
}

std::string read_input_stream(std::istream& in, const std::string& source, std::size_t max_bytes) {
  std::string text;
  char chunk[1 << 16];
  while (in.read(chunk, sizeof chunk) || in.gcount() > 0) {
    text.append(chunk, static_cast<std::size_t>(in.gcount()));
    if (text.size() > max_bytes) {
      throw InputError(printable(source, 200) + ": more than " + bytes_text(max_bytes) +
                       ", the limit for this kind of input");
    }
  }
  if (in.bad()) throw InputError(printable(source, 200) + ": read error");
  return text;
}

std::string printable(const std::string& text, std::size_t max_chars) {
  std::string out;
  std::size_t k = 0;
  for (; k < text.size() && out.size() < max_chars; ++k) {
    const auto c = static_cast<unsigned char>(text[k]);
    if (c == '\n') {
      out += "\\n";
    } else if (c == '\t') {
      out += "\\t";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c < 0x20 || c >= 0x7f) {
      char escape[8];
      std::snprintf(escape, sizeof escape, "\\x%02X", c);
      out += escape;
    } else {
      out += static_cast<char>(c);
    }
  }
  if (k < text.size()) out += "... (" + std::to_string(text.size()) + " bytes)";
  return out;
}

}  // namespace talus
