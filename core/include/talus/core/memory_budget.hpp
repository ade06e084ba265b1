#pragma once
/// @file
/// The memory budget: before a large allocation (a grid, a lattice, a station
/// table, an uncertainty table) Talus estimates what it needs and refuses with
/// one line naming the option to change, instead of dying of std::bad_alloc or
/// swapping the machine to a halt.
#include <cstddef>
#include <string>

namespace talus {

/// The budget [bytes]: 3/4 of the smaller of the physical memory and the
/// process's address-space limit (RLIMIT_AS, e.g. `prlimit --as`). The
/// environment variable TALUS_MEMORY_LIMIT_MB, if set to a positive number,
/// replaces it.
std::size_t memory_budget();

/// Throws InputError "<what> needs about N MiB, more than the memory budget of
/// M MiB; <advice>" when `bytes` exceeds memory_budget(). `advice` names the
/// option or input to change.
void require_memory(double bytes, const std::string& what, const std::string& advice);

}  // namespace talus
