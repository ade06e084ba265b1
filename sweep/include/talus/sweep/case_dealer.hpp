#pragma once
/// @file
/// CaseDealer: hands a sweep's cases to its ranks one at a time, so a rank
/// that drew quick cases takes more (dynamic load balancing across MPI ranks).
///
/// Rank 0 deals: it holds the list of cases still to run and answers the
/// other ranks' requests between its own cases (serve(), called whenever the
/// sweep's loop wakes). The others ask (next()) each time a worker slot is
/// free. Which rank runs a case never changes its result: every case is
/// computed by a single-threaded worker from its own parameters.
///
/// A request carries the asking rank's finished and failed counts, so rank
/// 0's progress line covers the whole sweep.
#include <cstddef>
#include <optional>
#include <vector>

namespace talus {

class CaseDealer {
 public:
  virtual ~CaseDealer() = default;
  /// True on the rank that deals (rank 0).
  virtual bool deals() const = 0;
  /// The dealer: the design indices still to run, in the order to hand them
  /// out; called once before next(). Ignored elsewhere.
  virtual void deal(std::vector<std::size_t> pending) = 0;
  /// The next case for this rank, or nullopt when none are left (then
  /// never again). Off the dealer it waits for the dealer's answer.
  virtual std::optional<std::size_t> next(std::size_t finished_here, std::size_t failed_here) = 0;
  /// The dealer: answers every request that has arrived; elsewhere a no-op.
  virtual void serve() = 0;
  /// The dealer: true once every other rank has been told that none are
  /// left (it may then stop serving). Elsewhere true.
  virtual bool served_all() const = 0;
  /// The dealer: finished and failed cases last reported by the other ranks.
  virtual std::size_t finished_elsewhere() const = 0;
  virtual std::size_t failed_elsewhere() const = 0;
};

}  // namespace talus
