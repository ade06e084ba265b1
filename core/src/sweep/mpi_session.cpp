#include "talus/core/sweep/mpi_session.hpp"

#include <dlfcn.h>
#include <sys/prctl.h>

#include <csignal>

#include <cstdlib>
#include <string>

#include "talus/core/error.hpp"

namespace talus {

/// The few Open MPI entry points the sweep needs. In Open MPI every handle
/// (communicator, datatype, operation) is a pointer to a global object, so
/// they are passed as void* and found by their symbol names.
struct MpiSession::Api {
  void* library = nullptr;
  int (*init)(int*, char***) = nullptr;
  int (*finalize)() = nullptr;
  int (*comm_rank)(void*, int*) = nullptr;
  int (*comm_size)(void*, int*) = nullptr;
  int (*barrier)(void*) = nullptr;
  int (*allreduce)(const void*, void*, int, void*, void*, void*) = nullptr;
  int (*abort)(void*, int) = nullptr;
  void* world = nullptr;
  void* type_int = nullptr;
  void* op_min = nullptr;
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
          "talus sweep supports Open MPI's mpirun only (PMI_SIZE is set, "
          "OMPI_COMM_WORLD_SIZE is not)");
    }
    return;
  }
  // A rank whose mpirun is killed (SIGKILL reaches no one else) ends too,
  // instead of running on and holding the sweep's lock.
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  void* library = nullptr;
  for (const char* name : {"libmpi.so.40", "libmpi.so"}) {
    library = dlopen(name, RTLD_NOW | RTLD_LOCAL | kDeepBind);
    if (library != nullptr) break;
  }
  if (library == nullptr) {
    throw InputError(std::string("talus sweep under mpirun needs Open MPI's libmpi.so.40 "
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
    api->world = object(library, "ompi_mpi_comm_world");
    api->type_int = object(library, "ompi_mpi_int");
    api->op_min = object(library, "ompi_mpi_op_min");
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

void MpiSession::barrier() const {
  if (api_ != nullptr) api_->barrier(api_->world);
}

void MpiSession::abort(int code) const {
  if (api_ != nullptr) api_->abort(api_->world, code);
  std::exit(code);
}

}  // namespace talus
