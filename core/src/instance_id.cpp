#include "talus/core/instance_id.hpp"

#include <atomic>

namespace talus {

std::uint64_t InstanceId::next() {
  static std::atomic<std::uint64_t> counter{0};
  return ++counter;
}

}  // namespace talus
