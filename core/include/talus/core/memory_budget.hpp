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
/// environment variable TALUS_MEMORY_LIMIT_MB, when set, replaces it: a number
/// of MiB in (0, 1e12] (1e12 MiB keeps the byte count within std::size_t);
/// anything else (text, a sign, NaN, 0, 1e30) is an InputError naming the
/// variable, not ignored or wrapped.
std::size_t memory_budget();

/// Throws InputError "<what> needs about N MiB, more than the memory budget of
/// M MiB; <advice>" when `bytes` exceeds memory_budget(). `advice` names the
/// option or input to change.
void require_memory(double bytes, const std::string& what, const std::string& advice);

}  // namespace talus
