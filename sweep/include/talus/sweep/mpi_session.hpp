#pragma once
/// @file
/// MPI for `talus sweep` under mpirun, and nothing otherwise: a process
/// started by mpirun (OMPI_COMM_WORLD_SIZE in its environment) initialises
/// MPI; a plain `talus` never does.
///
/// Open MPI (Debian's libopenmpi3, libmpi.so.40) is loaded at run time with
/// dlopen(RTLD_LOCAL | RTLD_DEEPBIND) rather than linked, because the
/// sequential MUMPS inside Debian's Ipopt defines its own stub MPI_Init and
/// MPI_Comm_rank: linked normally, the process mixes the stubs with the real
/// library ("MPI_Comm_size called before MPI_INIT"), and linked first, Ipopt
/// would call the real MPI_Init inside every worker process. Loaded locally,
/// only this class sees Open MPI.
#include <memory>
#include <string>
#include <vector>

#include "talus/sweep/case_dealer.hpp"

namespace talus {

class MpiSession {
 public:
  /// InputError under mpirun when Open MPI cannot be loaded.
  MpiSession();
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  /// True on every rank iff `mine` is true on every rank (a collective call).
  bool all(bool mine) const;
  void barrier() const;
  /// `values` (the same length on every rank) replaced by their element-wise
  /// maximum over the ranks (a collective call; unchanged without mpirun).
  void max_all(std::vector<double>& values) const;
  /// Hands the sweep's cases out one at a time from rank 0 (case_dealer.hpp);
  /// null without mpirun or with one rank. Lives no longer than this session.
  std::unique_ptr<CaseDealer> case_dealer() const;
  /// Ends every rank at once (a rank failed after the others started waiting).
  [[noreturn]] void abort(int code) const;
  /// Whether this build can run under mpirun here: mpirun is on the PATH and
  /// the build is not under AddressSanitizer, whose runtime refuses the
  /// RTLD_DEEPBIND Open MPI is loaded with (google/sanitizers#611).
  static bool mpirun_available();

  /// Open MPI's entry points; defined (and used) in mpi_session.cpp only.
  struct Api;

 private:
  Api* api_ = nullptr;  ///< null without mpirun
  int rank_ = 0, size_ = 1;
};

}  // namespace talus
