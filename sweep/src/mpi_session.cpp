#include "talus/sweep/mpi_session.hpp"

#include <dlfcn.h>
#include <sys/prctl.h>

#include <csignal>

#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include "talus/core/error.hpp"

namespace talus {

/// The few Open MPI entry points the sweep needs. In Open MPI every handle
/// (communicator, datatype, operation) is a pointer to a global object, so
/// they are passed as void* and found by their symbol names.
struct MpiSession::Api {
  /// Open MPI's MPI_Status (ompi_status_public_t, stable in libmpi.so.40).
  struct Status {
    int source = 0, tag = 0, error = 0, cancelled = 0;
    std::size_t ucount = 0;
  };
  static constexpr int kAnySource = -1;  ///< Open MPI's MPI_ANY_SOURCE
  void* library = nullptr;
  int (*init)(int*, char***) = nullptr;
  int (*finalize)() = nullptr;
  int (*comm_rank)(void*, int*) = nullptr;
  int (*comm_size)(void*, int*) = nullptr;
  int (*barrier)(void*) = nullptr;
  int (*allreduce)(const void*, void*, int, void*, void*, void*) = nullptr;
  int (*abort)(void*, int) = nullptr;
  int (*send)(const void*, int, void*, int, int, void*) = nullptr;
  int (*recv)(void*, int, void*, int, int, void*, Status*) = nullptr;
  int (*iprobe)(int, int, void*, int*, Status*) = nullptr;
  int (*irecv)(void*, int, void*, int, int, void*, void**) = nullptr;
  int (*wait)(void**, Status*) = nullptr;
  void* world = nullptr;
  void* type_int = nullptr;
  void* op_min = nullptr;
  void* type_double = nullptr;
  void* op_max = nullptr;
};

namespace {

// AddressSanitizer's runtime refuses RTLD_DEEPBIND (google/sanitizers#611);
// the sanitizer build's tests skip MPI (test_sweep.cpp).
#if defined(__SANITIZE_ADDRESS__)
constexpr int kDeepBind = 0;
#else
constexpr int kDeepBind = RTLD_DEEPBIND;
#endif

template <typename Function>
void bind(void* library, const char* name, Function& f) {
  f = reinterpret_cast<Function>(dlsym(library, name));
  if (f == nullptr) throw InputError(std::string("Open MPI: libmpi has no ") + name);
}

void* object(void* library, const char* name) {
  void* p = dlsym(library, name);
  if (p == nullptr) throw InputError(std::string("Open MPI: libmpi has no ") + name);
  return p;
}

}  // namespace

MpiSession::MpiSession() {
  const char* announced = std::getenv("OMPI_COMM_WORLD_SIZE");
  if (announced == nullptr) {
    if (std::getenv("PMI_SIZE") != nullptr && std::atoi(std::getenv("PMI_SIZE")) > 1) {
      throw InputError(
          "talus supports Open MPI's mpirun only (PMI_SIZE is set, "
          "OMPI_COMM_WORLD_SIZE is not)");
    }
    return;
  }
  // A rank whose mpirun is killed (SIGKILL reaches no one else) ends too,
  // instead of running on and holding the sweep's lock.
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  // A sweep's ranks exchange a few integers per case, so the plain
  // point-to-point layer (ob1 over shared memory or TCP) is all it needs.
  // Left to choose, MPI_Init probes UCX, PSM and OFI first: 0.27 s per rank
  // against 0.05 s on the development machine. A user's --mca pml (mpirun
  // passes it as OMPI_MCA_pml) still wins.
  setenv("OMPI_MCA_pml", "ob1", /*overwrite=*/0);
  void* library = nullptr;
  for (const char* name : {"libmpi.so.40", "libmpi.so"}) {
    library = dlopen(name, RTLD_NOW | RTLD_LOCAL | kDeepBind);
    if (library != nullptr) break;
  }
  if (library == nullptr) {
    throw InputError(std::string("talus under mpirun needs Open MPI's libmpi.so.40 "
                                 "(Debian: libopenmpi3): ") +
                     dlerror());
  }
  auto* api = new Api;
  api->library = library;
  try {
    bind(library, "MPI_Init", api->init);
    bind(library, "MPI_Finalize", api->finalize);
    bind(library, "MPI_Comm_rank", api->comm_rank);
    bind(library, "MPI_Comm_size", api->comm_size);
    bind(library, "MPI_Barrier", api->barrier);
    bind(library, "MPI_Allreduce", api->allreduce);
    bind(library, "MPI_Abort", api->abort);
    bind(library, "MPI_Send", api->send);
    bind(library, "MPI_Recv", api->recv);
    bind(library, "MPI_Iprobe", api->iprobe);
    bind(library, "MPI_Irecv", api->irecv);
    bind(library, "MPI_Wait", api->wait);
    api->world = object(library, "ompi_mpi_comm_world");
    api->type_int = object(library, "ompi_mpi_int");
    api->op_min = object(library, "ompi_mpi_op_min");
    api->type_double = object(library, "ompi_mpi_double");
    api->op_max = object(library, "ompi_mpi_op_max");
  } catch (...) {
    delete api;
    throw;
  }
  api_ = api;
  api_->init(nullptr, nullptr);
  api_->comm_rank(api_->world, &rank_);
  api_->comm_size(api_->world, &size_);
}

MpiSession::~MpiSession() {
  if (api_ == nullptr) return;
  api_->finalize();
  delete api_;  // the library stays loaded: Open MPI cannot be initialised twice anyway
}

bool MpiSession::all(bool mine) const {
  if (api_ == nullptr) return mine;
  int local = mine ? 1 : 0, global = 0;
  api_->allreduce(&local, &global, 1, api_->type_int, api_->op_min, api_->world);
  return global == 1;
}

void MpiSession::max_all(std::vector<double>& values) const {
  if (api_ == nullptr || values.empty()) return;
  std::vector<double> out(values.size());
  api_->allreduce(values.data(), out.data(), static_cast<int>(values.size()), api_->type_double,
                  api_->op_max, api_->world);
  values = std::move(out);
}

void MpiSession::barrier() const {
  if (api_ != nullptr) api_->barrier(api_->world);
}

namespace {

/// Rank 0 keeps the list; a request is {finished, failed} of the asking
/// rank, the answer a design index or -1 for "none left".
class MpiCaseDealer final : public CaseDealer {
 public:
  using Api = MpiSession::Api;
  MpiCaseDealer(const Api& api, int rank, int size)
      : api_(api), rank_(rank), reported_(static_cast<std::size_t>(size), {0, 0}) {
    if (rank_ == 0) waiting_ = size - 1;
  }
  bool deals() const override { return rank_ == 0; }
  void deal(std::vector<std::size_t> pending) override {
    if (rank_ == 0) pending_ = std::move(pending);
  }
  std::optional<std::size_t> next(std::size_t finished_here, std::size_t failed_here) override {
    if (rank_ == 0) return take();
    if (!asked_) ask(finished_here, failed_here);
    Api::Status status;
    api_.wait(&request_, &status);
    asked_ = false;
    if (answer_ < 0) return std::nullopt;
    const auto index = static_cast<std::size_t>(answer_);
    // Ask for the one after at once: the dealer answers while this case
    // runs, so the next is in hand when a slot frees up.
    ask(finished_here, failed_here);
    return index;
  }
  void serve() override {
    if (rank_ != 0) return;
    for (;;) {
      int arrived = 0;
      Api::Status status;
      api_.iprobe(Api::kAnySource, kRequestTag, api_.world, &arrived, &status);
      if (arrived == 0) return;
      int request[2] = {0, 0};
      api_.recv(request, 2, api_.type_int, status.source, kRequestTag, api_.world, &status);
      reported_[static_cast<std::size_t>(status.source)] = {static_cast<std::size_t>(request[0]),
                                                            static_cast<std::size_t>(request[1])};
      const std::optional<std::size_t> index = take();
      const int answer = index ? static_cast<int>(*index) : -1;
      if (!index) --waiting_;
      api_.send(&answer, 1, api_.type_int, status.source, kAnswerTag, api_.world);
    }
  }
  bool served_all() const override { return waiting_ == 0; }
  std::size_t finished_elsewhere() const override { return sum(0); }
  std::size_t failed_elsewhere() const override { return sum(1); }

 private:
  static constexpr int kRequestTag = 7101, kAnswerTag = 7102;
  void ask(std::size_t finished_here, std::size_t failed_here) {
    counts_[0] = static_cast<int>(finished_here);
    counts_[1] = static_cast<int>(failed_here);
    api_.send(counts_, 2, api_.type_int, 0, kRequestTag, api_.world);
    api_.irecv(&answer_, 1, api_.type_int, 0, kAnswerTag, api_.world, &request_);
    asked_ = true;
  }
  std::optional<std::size_t> take() {
    if (taken_ == pending_.size()) return std::nullopt;
    return pending_[taken_++];
  }
  std::size_t sum(int which) const {
    std::size_t total = 0;
    for (const auto& counts : reported_) total += which == 0 ? counts.first : counts.second;
    return total;
  }
  const Api& api_;
  int rank_;
  std::vector<std::size_t> pending_;
  std::size_t taken_ = 0;
  int waiting_ = 0;  ///< other ranks not yet told "none left"
  // Off the dealer: the request in flight and its answer's buffer.
  int counts_[2] = {0, 0};
  int answer_ = -1;
  void* request_ = nullptr;  ///< Open MPI's MPI_Request
  bool asked_ = false;
  std::vector<std::pair<std::size_t, std::size_t>> reported_;
};

}  // namespace

std::unique_ptr<CaseDealer> MpiSession::case_dealer() const {
  if (api_ == nullptr || size_ < 2) return nullptr;
  return std::make_unique<MpiCaseDealer>(*api_, rank_, size_);
}

bool MpiSession::mpirun_available() {
#if defined(__SANITIZE_ADDRESS__)
  return false;
#else
  return std::system("command -v mpirun >/dev/null 2>&1") == 0;
#endif
}

void MpiSession::abort(int code) const {
  if (api_ != nullptr) api_->abort(api_->world, code);
  std::exit(code);
}

}  // namespace talus
