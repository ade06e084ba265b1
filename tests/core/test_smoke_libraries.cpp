// Smoke tests for the five third-party libraries Talus builds on: each test proves the library
// links and computes a correct answer against a known analytic solution.
//   Ipopt 3.11 (MUMPS), NLopt 2.7 (C++ API), SUNDIALS 6.4 CVODE, CHOLMOD (SuiteSparse 5.12) via
//   Eigen 3.4.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <type_traits>
#include <vector>

#include <Eigen/CholmodSupport>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <IpIpoptApplication.hpp>
#include <IpTNLP.hpp>

#include <nlopt.hpp>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

namespace {

// ---------------------------------------------------------------------------------------------
// Ipopt
// ---------------------------------------------------------------------------------------------

using Ipopt::Index;
using Ipopt::Number;

// Beyond Ipopt's default nlp_{lower,upper}_bound_inf (+-1e19): treated as "no bound".
constexpr Number kIpoptInf = 2e19;

// What finalize_solution reports, kept for the assertions.
struct IpoptResult {
  Ipopt::SolverReturn status = Ipopt::UNASSIGNED;
  std::vector<Number> x;
  std::vector<Number> lambda;
  Number objective = 0.0;
};

// Common part of the test problems: records the final iterate.
class RecordingTnlp : public Ipopt::TNLP {
 public:
  const IpoptResult& result() const { return result_; }

  void finalize_solution(Ipopt::SolverReturn status, Index n, const Number* x,
                         const Number* /*z_L*/, const Number* /*z_U*/, Index m, const Number* /*g*/,
                         const Number* lambda, Number obj_value,
                         const Ipopt::IpoptData* /*ip_data*/,
                         Ipopt::IpoptCalculatedQuantities* /*ip_cq*/) override {
    result_.status = status;
    result_.x.assign(x, x + n);
    result_.lambda.assign(lambda, lambda + m);
    result_.objective = obj_value;
  }

 private:
  IpoptResult result_;
};

// min (x-1)^2 + (y-2)^2  s.t.  x + y <= 1.
// The optimum is the projection of (1,2) onto the half-plane: (0,1), objective 2, and the
// multiplier of the active constraint is 2 (grad f + lambda grad g = 0 at the optimum).
class ProjectionQp final : public RecordingTnlp {
 public:
  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag,
                    IndexStyleEnum& index_style) override {
    n = 2;
    m = 1;
    nnz_jac_g = 2;
    nnz_h_lag = 2;  // diagonal only
    index_style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Index /*n*/, Number* x_l, Number* x_u, Index /*m*/, Number* g_l,
                       Number* g_u) override {
    x_l[0] = x_l[1] = -kIpoptInf;
    x_u[0] = x_u[1] = kIpoptInf;
    g_l[0] = -kIpoptInf;
    g_u[0] = 1.0;
    return true;
  }

  bool get_starting_point(Index /*n*/, bool init_x, Number* x, bool init_z, Number* /*z_L*/,
                          Number* /*z_U*/, Index /*m*/, bool init_lambda,
                          Number* /*lambda*/) override {
    if (!init_x || init_z || init_lambda) return false;
    x[0] = 3.0;  // infeasible start on purpose
    x[1] = 3.0;
    return true;
  }

  bool eval_f(Index /*n*/, const Number* x, bool /*new_x*/, Number& obj_value) override {
    obj_value = (x[0] - 1.0) * (x[0] - 1.0) + (x[1] - 2.0) * (x[1] - 2.0);
    return true;
  }

  bool eval_grad_f(Index /*n*/, const Number* x, bool /*new_x*/, Number* grad_f) override {
    grad_f[0] = 2.0 * (x[0] - 1.0);
    grad_f[1] = 2.0 * (x[1] - 2.0);
    return true;
  }

  bool eval_g(Index /*n*/, const Number* x, bool /*new_x*/, Index /*m*/, Number* g) override {
    g[0] = x[0] + x[1];
    return true;
  }

  bool eval_jac_g(Index /*n*/, const Number* /*x*/, bool /*new_x*/, Index /*m*/, Index /*nele_jac*/,
                  Index* iRow, Index* jCol, Number* values) override {
    if (values == nullptr) {
      iRow[0] = 0;
      jCol[0] = 0;
      iRow[1] = 0;
      jCol[1] = 1;
    } else {
      values[0] = 1.0;
      values[1] = 1.0;
    }
    return true;
  }

  bool eval_h(Index /*n*/, const Number* /*x*/, bool /*new_x*/, Number obj_factor, Index /*m*/,
              const Number* /*lambda*/, bool /*new_lambda*/, Index /*nele_hess*/, Index* iRow,
              Index* jCol, Number* values) override {
    if (values == nullptr) {
      iRow[0] = jCol[0] = 0;
      iRow[1] = jCol[1] = 1;
    } else {
      // The constraint is linear: only the objective contributes.
      values[0] = 2.0 * obj_factor;
      values[1] = 2.0 * obj_factor;
    }
    return true;
  }
};

// Hock & Schittkowski problem 71 (the Ipopt tutorial problem):
//   min x0 x3 (x0 + x1 + x2) + x2
//   s.t. x0 x1 x2 x3 >= 25,  x0^2 + x1^2 + x2^2 + x3^2 = 40,  1 <= x <= 5,  x_start = (1,5,5,1).
// Optimum x* = (1, 4.74299963, 3.82114998, 1.37940829), f* = 17.014017145 (quoted as 17.0140173).
class Hs071 final : public RecordingTnlp {
 public:
  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag,
                    IndexStyleEnum& index_style) override {
    n = 4;
    m = 2;
    nnz_jac_g = 8;   // both constraints are dense
    nnz_h_lag = 10;  // dense lower triangle of a 4x4 matrix
    index_style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Index n, Number* x_l, Number* x_u, Index /*m*/, Number* g_l,
                       Number* g_u) override {
    for (Index i = 0; i < n; ++i) {
      x_l[i] = 1.0;
      x_u[i] = 5.0;
    }
    g_l[0] = 25.0;
    g_u[0] = kIpoptInf;
    g_l[1] = g_u[1] = 40.0;
    return true;
  }

  bool get_starting_point(Index /*n*/, bool init_x, Number* x, bool init_z, Number* /*z_L*/,
                          Number* /*z_U*/, Index /*m*/, bool init_lambda,
                          Number* /*lambda*/) override {
    if (!init_x || init_z || init_lambda) return false;
    x[0] = 1.0;
    x[1] = 5.0;
    x[2] = 5.0;
    x[3] = 1.0;
    return true;
  }

  bool eval_f(Index /*n*/, const Number* x, bool /*new_x*/, Number& obj_value) override {
    obj_value = x[0] * x[3] * (x[0] + x[1] + x[2]) + x[2];
    return true;
  }

  bool eval_grad_f(Index /*n*/, const Number* x, bool /*new_x*/, Number* grad_f) override {
    grad_f[0] = x[3] * (2.0 * x[0] + x[1] + x[2]);
    grad_f[1] = x[0] * x[3];
    grad_f[2] = x[0] * x[3] + 1.0;
    grad_f[3] = x[0] * (x[0] + x[1] + x[2]);
    return true;
  }

  bool eval_g(Index /*n*/, const Number* x, bool /*new_x*/, Index /*m*/, Number* g) override {
    g[0] = x[0] * x[1] * x[2] * x[3];
    g[1] = x[0] * x[0] + x[1] * x[1] + x[2] * x[2] + x[3] * x[3];
    return true;
  }

  bool eval_jac_g(Index /*n*/, const Number* x, bool /*new_x*/, Index /*m*/, Index /*nele_jac*/,
                  Index* iRow, Index* jCol, Number* values) override {
    if (values == nullptr) {
      Index k = 0;
      for (Index row = 0; row < 2; ++row) {
        for (Index col = 0; col < 4; ++col) {
          iRow[k] = row;
          jCol[k] = col;
          ++k;
        }
      }
    } else {
      values[0] = x[1] * x[2] * x[3];
      values[1] = x[0] * x[2] * x[3];
      values[2] = x[0] * x[1] * x[3];
      values[3] = x[0] * x[1] * x[2];
      for (Index i = 0; i < 4; ++i) values[4 + i] = 2.0 * x[i];
    }
    return true;
  }

  // Entries in row-major order of the lower triangle: (0,0) (1,0) (1,1) (2,0) (2,1) (2,2) ...
  bool eval_h(Index /*n*/, const Number* x, bool /*new_x*/, Number obj_factor, Index /*m*/,
              const Number* lambda, bool /*new_lambda*/, Index /*nele_hess*/, Index* iRow,
              Index* jCol, Number* values) override {
    if (values == nullptr) {
      Index k = 0;
      for (Index row = 0; row < 4; ++row) {
        for (Index col = 0; col <= row; ++col) {
          iRow[k] = row;
          jCol[k] = col;
          ++k;
        }
      }
      return true;
    }
    const Number s = obj_factor;
    const Number l0 = lambda[0];
    const Number l1 = lambda[1];
    values[0] = s * 2.0 * x[3] + l1 * 2.0;                          // (0,0)
    values[1] = s * x[3] + l0 * x[2] * x[3];                        // (1,0)
    values[2] = l1 * 2.0;                                           // (1,1)
    values[3] = s * x[3] + l0 * x[1] * x[3];                        // (2,0)
    values[4] = l0 * x[0] * x[3];                                   // (2,1)
    values[5] = l1 * 2.0;                                           // (2,2)
    values[6] = s * (2.0 * x[0] + x[1] + x[2]) + l0 * x[1] * x[2];  // (3,0)
    values[7] = s * x[0] + l0 * x[0] * x[2];                        // (3,1)
    values[8] = s * x[0] + l0 * x[0] * x[1];                        // (3,2)
    values[9] = l1 * 2.0;                                           // (3,3)
    return true;
  }
};

// Runs Ipopt (default linear solver: MUMPS) quietly on `nlp`.
Ipopt::ApplicationReturnStatus SolveQuietly(const Ipopt::SmartPtr<Ipopt::TNLP>& nlp) {
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
  app->Options()->SetIntegerValue("print_level", 0);
  app->Options()->SetStringValue("sb", "yes");  // no banner
  app->Options()->SetNumericValue("tol", 1e-10);
  // Never set linear_solver=ma97 here: Debian's Ipopt 3.11 calls exit(1) for it.
  const Ipopt::ApplicationReturnStatus init = app->Initialize();
  if (init != Ipopt::Solve_Succeeded) return init;
  return app->OptimizeTNLP(nlp);
}

TEST(SmokeIpopt, SolvesProjectionQp) {
  Ipopt::SmartPtr<ProjectionQp> nlp = new ProjectionQp();
  ASSERT_EQ(SolveQuietly(Ipopt::GetRawPtr(nlp)), Ipopt::Solve_Succeeded);

  const IpoptResult& r = nlp->result();
  EXPECT_EQ(r.status, Ipopt::SUCCESS);
  ASSERT_EQ(r.x.size(), 2u);
  EXPECT_NEAR(r.x[0], 0.0, 1e-7);
  EXPECT_NEAR(r.x[1], 1.0, 1e-7);
  EXPECT_NEAR(r.objective, 2.0, 1e-7);
  ASSERT_EQ(r.lambda.size(), 1u);
  EXPECT_NEAR(r.lambda[0], 2.0, 1e-6);
}

TEST(SmokeIpopt, SolvesHs071) {
  Ipopt::SmartPtr<Hs071> nlp = new Hs071();
  ASSERT_EQ(SolveQuietly(Ipopt::GetRawPtr(nlp)), Ipopt::Solve_Succeeded);

  const IpoptResult& r = nlp->result();
  EXPECT_EQ(r.status, Ipopt::SUCCESS);
  EXPECT_NEAR(r.objective, 17.014017145, 1e-7);
  const std::array<double, 4> expected{1.0, 4.74299963, 3.82114998, 1.37940829};
  ASSERT_EQ(r.x.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_NEAR(r.x[i], expected[i], 1e-6) << "x[" << i << "]";
  }
  // Both constraints are active at the optimum.
  const double product = r.x[0] * r.x[1] * r.x[2] * r.x[3];
  const double sum_sq = r.x[0] * r.x[0] + r.x[1] * r.x[1] + r.x[2] * r.x[2] + r.x[3] * r.x[3];
  EXPECT_NEAR(product, 25.0, 1e-7);
  EXPECT_NEAR(sum_sq, 40.0, 1e-7);
  // Multipliers from the Ipopt documentation for this problem.
  ASSERT_EQ(r.lambda.size(), 2u);
  EXPECT_NEAR(r.lambda[0], -0.552293650, 1e-6);
  EXPECT_NEAR(r.lambda[1], 0.161468556, 1e-6);
}

// ---------------------------------------------------------------------------------------------
// NLopt
// ---------------------------------------------------------------------------------------------

struct RosenbrockCounter {
  int evaluations = 0;
};

// f(x,y) = (1-x)^2 + 100 (y - x^2)^2, global minimum f(1,1) = 0.
double Rosenbrock(const std::vector<double>& x, std::vector<double>& grad, void* data) {
  ++static_cast<RosenbrockCounter*>(data)->evaluations;
  const double a = 1.0 - x[0];
  const double b = x[1] - x[0] * x[0];
  if (!grad.empty()) {
    grad[0] = -2.0 * a - 400.0 * x[0] * b;
    grad[1] = 200.0 * b;
  }
  return a * a + 100.0 * b * b;
}

// Minimises Rosenbrock from the classic start (-1.2, 1) with `algorithm`.
void ExpectRosenbrockMinimum(nlopt::algorithm algorithm, double tolerance) {
  RosenbrockCounter counter;
  nlopt::opt opt(algorithm, 2);
  opt.set_min_objective(Rosenbrock, &counter);
  opt.set_lower_bounds({-5.0, -5.0});
  opt.set_upper_bounds({5.0, 5.0});
  opt.set_xtol_rel(1e-12);
  opt.set_ftol_abs(1e-20);
  opt.set_maxeval(20000);

  std::vector<double> x{-1.2, 1.0};
  double f_min = 0.0;
  nlopt::result result = nlopt::FAILURE;
  try {
    result = opt.optimize(x, f_min);
  } catch (const nlopt::roundoff_limited&) {
    // Tight tolerances may end in round-off; the iterate is still checked below.
    result = nlopt::ROUNDOFF_LIMITED;
    f_min = opt.last_optimum_value();
  }
  EXPECT_GT(result, 0) << "nlopt result " << result;
  EXPECT_NE(result, nlopt::MAXEVAL_REACHED);
  EXPECT_NEAR(x[0], 1.0, tolerance);
  EXPECT_NEAR(x[1], 1.0, tolerance);
  EXPECT_LT(f_min, tolerance * tolerance);
  EXPECT_GT(counter.evaluations, 0);
  EXPECT_EQ(counter.evaluations, opt.get_numevals());
}

TEST(SmokeNlopt, LbfgsMinimisesRosenbrock) {
  ExpectRosenbrockMinimum(nlopt::LD_LBFGS, 1e-6);
}

TEST(SmokeNlopt, BobyqaMinimisesRosenbrock) {
  ExpectRosenbrockMinimum(nlopt::LN_BOBYQA, 1e-6);
}

// ---------------------------------------------------------------------------------------------
// SUNDIALS CVODE
// ---------------------------------------------------------------------------------------------

// RAII owners for the SUNDIALS C objects.
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
using ContextPtr = std::unique_ptr<std::remove_pointer_t<SUNContext>, ContextDeleter>;
using VectorPtr = std::unique_ptr<std::remove_pointer_t<N_Vector>, VectorDeleter>;
using MatrixPtr = std::unique_ptr<std::remove_pointer_t<SUNMatrix>, MatrixDeleter>;
using LinearSolverPtr =
    std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, LinearSolverDeleter>;
using CvodePtr = std::unique_ptr<void, CvodeDeleter>;

ContextPtr MakeContext() {
  SUNContext ctx = nullptr;
  if (SUNContext_Create(nullptr, &ctx) != 0) return nullptr;
  return ContextPtr(ctx);
}

// Everything one dense-Newton CVODE integration owns. Members are destroyed in reverse order:
// the integrator first, the context last.
struct CvodeSystem {
  ContextPtr ctx;
  VectorPtr y;
  MatrixPtr jac;
  LinearSolverPtr solver;
  CvodePtr mem;
};

// Sets up CVODE with method `lmm` (CV_ADAMS / CV_BDF), a dense Newton solver and the analytic
// Jacobian. Fails the current test (and leaves `sys.mem` empty) on any error.
void SetUpCvode(CvodeSystem& sys, int lmm, const std::vector<sunrealtype>& y0, CVRhsFn rhs,
                CVLsJacFn jac, void* user_data) {
  const auto n = static_cast<sunindextype>(y0.size());
  sys.ctx = MakeContext();
  ASSERT_NE(sys.ctx, nullptr);
  sys.y.reset(N_VNew_Serial(n, sys.ctx.get()));
  ASSERT_NE(sys.y, nullptr);
  for (sunindextype i = 0; i < n; ++i) NV_Ith_S(sys.y.get(), i) = y0[static_cast<std::size_t>(i)];
  sys.jac.reset(SUNDenseMatrix(n, n, sys.ctx.get()));
  ASSERT_NE(sys.jac, nullptr);
  sys.solver.reset(SUNLinSol_Dense(sys.y.get(), sys.jac.get(), sys.ctx.get()));
  ASSERT_NE(sys.solver, nullptr);
  CvodePtr mem(CVodeCreate(lmm, sys.ctx.get()));
  ASSERT_NE(mem, nullptr);
  ASSERT_EQ(CVodeInit(mem.get(), rhs, 0.0, sys.y.get()), CV_SUCCESS);
  ASSERT_EQ(CVodeSStolerances(mem.get(), 1e-11, 1e-14), CV_SUCCESS);
  ASSERT_EQ(CVodeSetUserData(mem.get(), user_data), CV_SUCCESS);
  ASSERT_EQ(CVodeSetMaxNumSteps(mem.get(), 100000), CV_SUCCESS);
  ASSERT_EQ(CVodeSetLinearSolver(mem.get(), sys.solver.get(), sys.jac.get()), CVLS_SUCCESS);
  ASSERT_EQ(CVodeSetJacFn(mem.get(), jac), CVLS_SUCCESS);
  sys.mem = std::move(mem);
}

// y' = -k y, y(0) = 1  =>  y(t) = exp(-k t).
int DecayRhs(sunrealtype /*t*/, N_Vector y, N_Vector ydot, void* user_data) {
  const sunrealtype k = *static_cast<const sunrealtype*>(user_data);
  NV_Ith_S(ydot, 0) = -k * NV_Ith_S(y, 0);
  return 0;
}

int DecayJac(sunrealtype /*t*/, N_Vector /*y*/, N_Vector /*fy*/, SUNMatrix jac, void* user_data,
             N_Vector /*tmp1*/, N_Vector /*tmp2*/, N_Vector /*tmp3*/) {
  SM_ELEMENT_D(jac, 0, 0) = -*static_cast<const sunrealtype*>(user_data);
  return 0;
}

// x'' = -w^2 x as (x, v)' = (v, -w^2 x), x(0) = 1, v(0) = 0  =>  x = cos(w t), v = -w sin(w t).
int OscillatorRhs(sunrealtype /*t*/, N_Vector y, N_Vector ydot, void* user_data) {
  const sunrealtype w = *static_cast<const sunrealtype*>(user_data);
  NV_Ith_S(ydot, 0) = NV_Ith_S(y, 1);
  NV_Ith_S(ydot, 1) = -w * w * NV_Ith_S(y, 0);
  return 0;
}

int OscillatorJac(sunrealtype /*t*/, N_Vector /*y*/, N_Vector /*fy*/, SUNMatrix jac,
                  void* user_data, N_Vector /*tmp1*/, N_Vector /*tmp2*/, N_Vector /*tmp3*/) {
  const sunrealtype w = *static_cast<const sunrealtype*>(user_data);
  SM_ELEMENT_D(jac, 0, 0) = 0.0;
  SM_ELEMENT_D(jac, 0, 1) = 1.0;
  SM_ELEMENT_D(jac, 1, 0) = -w * w;
  SM_ELEMENT_D(jac, 1, 1) = 0.0;
  return 0;
}

TEST(SmokeCvode, BdfMatchesExponentialDecay) {
  sunrealtype k = 0.7;
  CvodeSystem sys;
  SetUpCvode(sys, CV_BDF, {1.0}, DecayRhs, DecayJac, &k);
  ASSERT_NE(sys.mem, nullptr);

  for (const sunrealtype t_out : {1.0, 4.0, 10.0}) {
    sunrealtype t = 0.0;
    ASSERT_EQ(CVode(sys.mem.get(), t_out, sys.y.get(), &t, CV_NORMAL), CV_SUCCESS);
    EXPECT_DOUBLE_EQ(t, t_out);
    const double exact = std::exp(-k * t_out);
    EXPECT_NEAR(NV_Ith_S(sys.y.get(), 0), exact, 1e-6 * exact) << "t = " << t_out;
  }
  long steps = 0;
  ASSERT_EQ(CVodeGetNumSteps(sys.mem.get(), &steps), CV_SUCCESS);
  EXPECT_GT(steps, 0);
}

TEST(SmokeCvode, AdamsMatchesHarmonicOscillator) {
  sunrealtype w = 2.0;
  CvodeSystem sys;
  SetUpCvode(sys, CV_ADAMS, {1.0, 0.0}, OscillatorRhs, OscillatorJac, &w);
  ASSERT_NE(sys.mem, nullptr);

  // Output times where neither cos(w t) nor sin(w t) is near zero.
  for (const sunrealtype t_out : {0.5, 3.0, 10.0}) {
    sunrealtype t = 0.0;
    ASSERT_EQ(CVode(sys.mem.get(), t_out, sys.y.get(), &t, CV_NORMAL), CV_SUCCESS);
    EXPECT_DOUBLE_EQ(t, t_out);
    const double x_exact = std::cos(w * t_out);
    const double v_exact = -w * std::sin(w * t_out);
    EXPECT_NEAR(NV_Ith_S(sys.y.get(), 0), x_exact, 1e-6 * std::abs(x_exact)) << "t = " << t_out;
    EXPECT_NEAR(NV_Ith_S(sys.y.get(), 1), v_exact, 1e-6 * std::abs(v_exact)) << "t = " << t_out;
  }
  long jac_evals = 0;
  ASSERT_EQ(CVodeGetNumJacEvals(sys.mem.get(), &jac_evals), CVLS_SUCCESS);
  EXPECT_GT(jac_evals, 0);  // the analytic Jacobian was used
}

// ---------------------------------------------------------------------------------------------
// CHOLMOD (through Eigen)
// ---------------------------------------------------------------------------------------------

// A = I + L on an N x N grid, L the 5-point Dirichlet Laplacian (4 on the diagonal, -1 for each
// neighbour). Its eigenpairs are known in closed form:
//   lambda_ij = 5 - 2 cos(i pi / (N+1)) - 2 cos(j pi / (N+1)),
//   v_ij(p, q) = sin(i p pi / (N+1)) sin(j q pi / (N+1)),   i, j, p, q = 1..N.
TEST(SmokeCholmod, SupernodalLltSolvesShiftedLaplacian) {
  constexpr int kN = 30;
  constexpr int kSize = kN * kN;
  const auto index = [](int p, int q) { return p * kN + q; };  // p, q zero-based
  constexpr double kH = std::numbers::pi / (kN + 1);

  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(5 * kSize);
  for (int p = 0; p < kN; ++p) {
    for (int q = 0; q < kN; ++q) {
      const int row = index(p, q);
      triplets.emplace_back(row, row, 5.0);
      if (p > 0) triplets.emplace_back(row, index(p - 1, q), -1.0);
      if (p + 1 < kN) triplets.emplace_back(row, index(p + 1, q), -1.0);
      if (q > 0) triplets.emplace_back(row, index(p, q - 1), -1.0);
      if (q + 1 < kN) triplets.emplace_back(row, index(p, q + 1), -1.0);
    }
  }
  Eigen::SparseMatrix<double> a(kSize, kSize);
  a.setFromTriplets(triplets.begin(), triplets.end());
  ASSERT_EQ(a.nonZeros(), 5 * kSize - 4 * kN);

  // Right-hand side b = lambda v for one eigenpair: the exact solution is v.
  constexpr int kI = 3;
  constexpr int kJ = 5;
  const double lambda = 5.0 - 2.0 * std::cos(kI * kH) - 2.0 * std::cos(kJ * kH);
  Eigen::VectorXd v(kSize);
  for (int p = 0; p < kN; ++p) {
    for (int q = 0; q < kN; ++q) {
      v[index(p, q)] = std::sin(kI * (p + 1) * kH) * std::sin(kJ * (q + 1) * kH);
    }
  }
  const Eigen::VectorXd b = lambda * v;

  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>> cholmod(a);
  ASSERT_EQ(cholmod.info(), Eigen::Success);
  const Eigen::VectorXd x = cholmod.solve(b);
  ASSERT_EQ(cholmod.info(), Eigen::Success);

  EXPECT_LT((a * x - b).norm() / b.norm(), 1e-10);
  EXPECT_LT((x - v).norm() / v.norm(), 1e-10);

  // Same answer as Eigen's own sparse Cholesky.
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(a);
  ASSERT_EQ(ldlt.info(), Eigen::Success);
  const Eigen::VectorXd x_ldlt = ldlt.solve(b);
  EXPECT_LT((x - x_ldlt).norm() / x_ldlt.norm(), 1e-12);

  // log det A = sum of log lambda_ij over all eigenvalues.
  double log_det = 0.0;
  for (int i = 1; i <= kN; ++i) {
    for (int j = 1; j <= kN; ++j) {
      log_det += std::log(5.0 - 2.0 * std::cos(i * kH) - 2.0 * std::cos(j * kH));
    }
  }
  EXPECT_NEAR(cholmod.logDeterminant(), log_det, 1e-10 * std::abs(log_det));
  EXPECT_NEAR(ldlt.vectorD().array().log().sum(), log_det, 1e-10 * std::abs(log_det));
}

}  // namespace
