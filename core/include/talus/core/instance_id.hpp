#pragma once
/// @file
/// InstanceId: a number no other object of the program has had, so that a
/// cache can recognise the object it was built for without comparing
/// addresses (a new object may land at a destroyed one's address). A copy or
/// a move is a new object and gets a new number; assignment gives the target
/// a new one too (its value changed). Thread-safe.
#include <cstdint>

namespace talus {

class InstanceId {
 public:
  InstanceId() : value_(next()) {}
  InstanceId(const InstanceId&) : value_(next()) {}
  InstanceId& operator=(const InstanceId&) {
    value_ = next();
    return *this;
  }
  std::uint64_t value() const { return value_; }

 private:
  static std::uint64_t next();
  std::uint64_t value_;
};

}  // namespace talus
