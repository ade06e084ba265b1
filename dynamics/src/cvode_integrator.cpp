#include "cvode_integrator.hpp"

#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <cstdlib>
#include <sstream>
#include <type_traits>

#include "talus/core/error.hpp"

namespace talus::detail {
namespace {

// RAII owners for the SUNDIALS C objects (destroyed in reverse order of declaration).
struct ContextDeleter {
  void operator()(SUNContext ctx) const { SUNContext_Free(&ctx); }
};
struct VectorDeleter {
  void operator()(N_Vector v) const { N_VDestroy(v); }
};
struct MatrixDeleter {
  void operator()(SUNMatrix a) const { SUNMatDestroy(a); }
};
struct LinearSolverDeleter {
  void operator()(SUNLinearSolver ls) const { SUNLinSolFree(ls); }
};
struct CvodeDeleter {
  void operator()(void* mem) const { CVodeFree(&mem); }
};

void error_callback(int error_code, const char* module, const char* function, char* msg,
                    void* user_data) {
  auto* text = static_cast<std::string*>(user_data);
  std::ostringstream s;
  s << (module ? module : "CVODE") << " " << (function ? function : "") << " (flag " << error_code
    << "): " << (msg ? msg : "");
  *text = s.str();
}

}  // namespace

struct CvodeIntegrator::Sundials {
  std::unique_ptr<std::remove_pointer_t<SUNContext>, ContextDeleter> context;
  std::unique_ptr<std::remove_pointer_t<N_Vector>, VectorDeleter> y, scratch;
  std::unique_ptr<std::remove_pointer_t<SUNMatrix>, MatrixDeleter> jacobian;
  std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, LinearSolverDeleter> solver;
  std::unique_ptr<void, CvodeDeleter> memory;
};

CvodeIntegrator::CvodeIntegrator(int states, const double* initial, CVRhsFn rhs, int roots,
                                 CVRootFn root, void* user_data, const CvodeSettings& settings)
    : sundials_(std::make_unique<Sundials>()) {
  Sundials& s = *sundials_;
  SUNContext raw = nullptr;
  if (SUNContext_Create(nullptr, &raw) != 0) throw SolverError("SUNContext_Create failed");
  s.context.reset(raw);
  s.y.reset(N_VNew_Serial(states, s.context.get()));
  s.scratch.reset(N_VNew_Serial(states, s.context.get()));
  s.jacobian.reset(SUNDenseMatrix(states, states, s.context.get()));
  if (!s.y || !s.scratch || !s.jacobian)
    throw SolverError("SUNDIALS could not allocate its vectors");
  s.solver.reset(SUNLinSol_Dense(s.y.get(), s.jacobian.get(), s.context.get()));
  s.memory.reset(CVodeCreate(CV_BDF, s.context.get()));
  if (!s.solver || !s.memory) throw SolverError("CVODE could not be created");
  double* y = N_VGetArrayPointer(s.y.get());
  for (int i = 0; i < states; ++i) y[i] = initial[i];

  void* mem = s.memory.get();
  const auto check = [](int flag, const char* what) {
    if (flag < 0) throw SolverError(std::string("CVODE setup failed in ") + what);
  };
  check(CVodeSetErrHandlerFn(mem, error_callback, &error_message_), "ErrHandler");
  check(CVodeInit(mem, rhs, 0.0, s.y.get()), "CVodeInit");
  check(CVodeSStolerances(mem, settings.relative_tolerance, settings.absolute_tolerance),
        "CVodeSStolerances");
  check(CVodeSetUserData(mem, user_data), "CVodeSetUserData");
  check(CVodeSetLinearSolver(mem, s.solver.get(), s.jacobian.get()), "CVodeSetLinearSolver");
  check(CVodeSetMaxNumSteps(mem, -1), "CVodeSetMaxNumSteps");  // the caller counts steps
  if (settings.max_step > 0.0) check(CVodeSetMaxStep(mem, settings.max_step), "hmax");
  check(CVodeRootInit(mem, roots, root), "CVodeRootInit");
  std::vector<int> directions(static_cast<std::size_t>(roots), -1);
  check(CVodeSetRootDirection(mem, directions.data()), "CVodeSetRootDirection");
  check(CVodeSetNoInactiveRootWarn(mem), "CVodeSetNoInactiveRootWarn");
}

CvodeIntegrator::~CvodeIntegrator() = default;

double* CvodeIntegrator::state() {
  return N_VGetArrayPointer(sundials_->y.get());
}

void CvodeIntegrator::set_stop_time(double t_stop) {
  CVodeSetStopTime(sundials_->memory.get(), t_stop);
}

int CvodeIntegrator::step(double t_stop, double& t) {
  return CVode(sundials_->memory.get(), t_stop, sundials_->y.get(), &t, CV_ONE_STEP);
}

void CvodeIntegrator::roots_found(int* found) const {
  CVodeGetRootInfo(sundials_->memory.get(), found);
}

const double* CvodeIntegrator::interpolate(double t) {
  if (CVodeGetDky(sundials_->memory.get(), t, 0, sundials_->scratch.get()) != CV_SUCCESS)
    return nullptr;
  return N_VGetArrayPointer(sundials_->scratch.get());
}

void CvodeIntegrator::restart(double t) {
  add_counters(before_restarts_);
  if (CVodeReInit(sundials_->memory.get(), t, sundials_->y.get()) != CV_SUCCESS)
    throw SolverError("CVodeReInit failed at a control tick");
}

void CvodeIntegrator::add_counters(CvodeCounters& to) const {
  void* mem = sundials_->memory.get();
  long value = 0;
  if (CVodeGetNumRhsEvals(mem, &value) == CV_SUCCESS) to.rhs_evaluations += value;
  if (CVodeGetNumLinRhsEvals(mem, &value) == CV_SUCCESS) to.rhs_evaluations += value;
  if (CVodeGetNumJacEvals(mem, &value) == CV_SUCCESS) to.jacobian_evaluations += value;
  if (CVodeGetNumGEvals(mem, &value) == CV_SUCCESS) to.root_evaluations += value;
  if (CVodeGetNumErrTestFails(mem, &value) == CV_SUCCESS) to.error_test_failures += value;
  if (CVodeGetNumNonlinSolvConvFails(mem, &value) == CV_SUCCESS) to.nonlinear_failures += value;
}

CvodeCounters CvodeIntegrator::counters() const {
  CvodeCounters out = before_restarts_;
  add_counters(out);
  return out;
}

std::string CvodeIntegrator::failure(int flag) const {
  std::ostringstream msg;
  // CVodeGetReturnFlagName returns a malloc'ed string the caller frees.
  char* name = CVodeGetReturnFlagName(flag);
  msg << "flag " << flag << ", " << (name ? name : "?") << ")";
  std::free(name);
  if (!error_message_.empty()) msg << ": " << error_message_;
  return msg.str();
}

}  // namespace talus::detail
