#include "talus/core/memory_budget.hpp"

#include <sys/resource.h>
#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "talus/core/error.hpp"
#include "talus/core/input_file.hpp"

namespace talus {
namespace {
/// The largest budget the variable may give [MiB]: 1e12 MiB is about 2^60
/// bytes, below std::size_t's 2^64 (1e30 wrapped to a budget of 0).
constexpr double kMaxLimitMiB = 1e12;
}  // namespace

std::size_t memory_budget() {
  if (const char* limit = std::getenv("TALUS_MEMORY_LIMIT_MB")) {
    char* end = nullptr;
    const double mb = std::strtod(limit, &end);
    if (!(end != limit && *end == '\0' && std::isfinite(mb) && mb > 0.0 && mb <= kMaxLimitMiB)) {
      throw InputError("TALUS_MEMORY_LIMIT_MB must be a number of MiB in (0, 1e12], got '" +
                       printable(limit, 40) + "'");
    }
    return static_cast<std::size_t>(mb * 1024.0 * 1024.0);
  }
  double available = 1e18;
  const long pages = ::sysconf(_SC_PHYS_PAGES), page_size = ::sysconf(_SC_PAGE_SIZE);
  if (pages > 0 && page_size > 0) available = static_cast<double>(pages) * page_size;
  struct rlimit limit {};
  if (::getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
    available = std::min(available, static_cast<double>(limit.rlim_cur));
  }
  return static_cast<std::size_t>(0.75 * available);
}

void require_memory(double bytes, const std::string& what, const std::string& advice) {
  const std::size_t budget = memory_budget();
  if (bytes <= static_cast<double>(budget)) return;
  char text[160];
  std::snprintf(text, sizeof text, " needs about %.0f MiB, more than the memory budget of %.0f MiB",
                bytes / (1024.0 * 1024.0), static_cast<double>(budget) / (1024.0 * 1024.0));
  throw InputError(what + text + "; " + advice);
}

}  // namespace talus
