#include "profile_sensitivity.hpp"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <unsupported/Eigen/AutoDiff>

#include "step_controls.hpp"

namespace talus::detail {
namespace {

// Variables of one equation: x_j, x_{j+1}, Δs_j, then the 6 geometry values
// of the station where the constraint is evaluated.
constexpr int kGeometry = 6;
constexpr int kVariables = 3 + kGeometry;
using Ad = Eigen::AutoDiffScalar<Eigen::Matrix<double, kVariables, 1>>;

enum class Kind {
  kLateralPlus,     // λ R − Q >= 0 (λ: the vehicle's lateral envelope): a speed condition
  kLateralMinus,    // λ R + Q >= 0
  kSpeedCondition,  // a speed condition of the vehicle the envelope does not imply
  kMaxSpeed,        // v_max² − x >= 0
  kWheelContact,    // g k_r + κ_w x >= 0: contact at the wheels (rigid body)
  kFriction,        // μ² R² − f_t² − 2 c f_t f_q − f_q² >= 0 (c: 0, or ± the lighter
                    // axle's beta, AdmissibleSet::friction_coupling)
  kTractionZero,    // f_t = 0: friction on a station whose lateral friction is exhausted
  kTraction,        // a traction condition of the vehicle (pitch-over, drive, brake)
  // u = the double root where the step's line x = y0 + β u touches the
  // friction ellipse of the far station: the discrete limit curve (the
  // largest state from which some control is admissible at both ends).
  kTangentControl,
};

/// Constraint value at a station with state x, step control u and geometry
/// (κ_n, κ_g, k_t, k_q, k_r, κ_w) = G; `condition` for kSpeedCondition and
/// kTraction, `coupling` for kFriction. One source for double and AutoDiff.
template <typename S>
S constraint(Kind kind, const ForceCondition* condition, double coupling, const AdmissibleSet& c,
             double max_speed_squared, const S& x, const S& u, const S* G) {
  const double g = c.gravity();
  const S R = g * G[4] + G[0] * x;
  const S Q = g * G[3] + G[1] * x;
  const S F = u + g * G[2];
  switch (kind) {
    case Kind::kLateralPlus:
      return c.lateral_ratio() * R - Q;
    case Kind::kLateralMinus:
      return c.lateral_ratio() * R + Q;
    case Kind::kMaxSpeed:
      return max_speed_squared - x;
    case Kind::kWheelContact:
      return g * G[4] - c.contact_reserve() + G[5] * x;
    case Kind::kFriction:
      return c.friction() * c.friction() * R * R - F * F - 2.0 * coupling * F * Q - Q * Q;
    case Kind::kTractionZero:
      return F;
    case Kind::kSpeedCondition:
    case Kind::kTraction:
      return condition->r * R + condition->q * Q + condition->t * F + condition->c;
    case Kind::kTangentControl:
      break;  // needs the line: tangent_control()
  }
  return S(0.0);
}

/// The friction ellipse (with the coupling 2 `coupling` f_t f_q) of a station along the
/// step's line x = y0 + β u, as A u² + B u + K <= 0 (as in AdmissibleSet::accelerations_along):
/// its A and B.
template <typename S>
std::pair<S, S> ellipse_along_line(const AdmissibleSet& c, double coupling, const S& y0,
                                   const S& beta, const S* G) {
  const double g = c.gravity();
  const S R0 = g * G[4] + G[0] * y0, R1 = G[0] * beta;
  const S Q0 = g * G[3] + G[1] * y0, Q1 = G[1] * beta;
  const S T0 = g * G[2];
  const double m2 = c.friction() * c.friction();
  return {1.0 + 2.0 * coupling * Q1 + Q1 * Q1 - m2 * R1 * R1,
          2.0 * (T0 + coupling * (Q0 + Q1 * T0) + Q0 * Q1 - m2 * R0 * R1)};
}

/// u + B / (2 A) of ellipse_along_line: zero at the double root.
template <typename S>
S tangent_control(const AdmissibleSet& c, double coupling, const S& y0, const S& beta, const S& u,
                  const S* G) {
  const auto [A, B] = ellipse_along_line(c, coupling, y0, beta, G);
  return u + B / (2.0 * A);
}

// Normalised residual below which a constraint counts as touched: the
// profile solver widens its bounds by 1e-10 relative for rounding.
constexpr double kActiveTolerance = 1e-8;
// Relative nudge the profile solver may give a state to keep it admissible.
constexpr double kStateNudge = 1e-9;

// Relative along-line slope below which a touched friction ellipse counts as
// tangent: the solver finds such states by bisection to 1e-13 relative, which
// leaves the two roots about sqrt(1e-13) apart.
constexpr double kTangentTolerance = 1e-5;

struct Equation {
  Kind kind = Kind::kMaxSpeed;
  std::size_t station = 0;  // where the constraint is evaluated
  std::size_t step = 0;     // for control conditions: the step j (states j, j + 1)
  bool speed_only = true;   // a speed condition pins `station` alone
  double residual = std::numeric_limits<double>::infinity();
  const ForceCondition* condition = nullptr;  // kSpeedCondition, kTraction
  double coupling = 0.0;                      // kFriction, kTangentControl: the cone's
};

class Problem {
 public:
  Problem(const Vehicle& vehicle, const std::vector<StationGeometry>& geometry,
          const std::vector<double>& s, const std::vector<double>& speeds)
      : c_(vehicle), vmax2_(c_.max_speed() * c_.max_speed()), geometry_(geometry), s_(s) {
    x_.resize(speeds.size());
    for (std::size_t k = 0; k < speeds.size(); ++k) x_[k] = speeds[k] * speeds[k];
  }

  std::size_t stations() const { return x_.size(); }
  double x(std::size_t k) const { return x_[k]; }
  double length(std::size_t j) const { return s_[j + 1] - s_[j]; }
  double control(std::size_t j) const { return (x_[j + 1] - x_[j]) / (2.0 * length(j)); }

  std::array<double, kGeometry> g(std::size_t k) const {
    const StationGeometry& s = geometry_[k];
    return {s.kappa_n, s.kappa_g, s.k_t, s.k_q, s.k_r, s.kappa_wheels};
  }

  /// Lateral friction exhausted at station k (|f_q| = μ R): there the
  /// friction ellipse admits only f_t = 0, and its quadratic form has a zero
  /// derivative, so the equation used is f_t = 0 itself.
  bool friction_exhausted(std::size_t k) const {
    const auto G = g(k);
    const double R = c_.gravity() * G[4] + G[0] * x_[k], Q = c_.gravity() * G[3] + G[1] * x_[k];
    return std::abs(c_.friction() * R - std::abs(Q)) <= 1e-8 * scale(k, 0.0);
  }

  double scale(std::size_t k, double u) const {
    const auto G = g(k);
    return c_.gravity() + std::abs(G[0] * x_[k]) + std::abs(G[1] * x_[k]) + std::abs(u) +
           std::abs(c_.gravity() * G[2]);
  }

  /// Normalised |value| of a constraint as an equation.
  double residual(const Equation& e) const {
    const auto G = g(e.station);
    const double u = e.speed_only ? 0.0 : control(e.step);
    const double value =
        constraint<double>(e.kind, e.condition, e.coupling, c_, vmax2_, x_[e.station], u, G.data());
    const double sc = scale(e.station, u);
    if (e.kind == Kind::kMaxSpeed) return std::abs(value) / std::max(vmax2_, 1e-300);
    return std::abs(value) / (e.kind == Kind::kFriction ? sc * sc : sc);
  }

  /// The best speed condition pinning station k.
  Equation best_speed_equation(std::size_t k) const {
    Equation best;
    const auto consider = [&](Equation e) {
      e.residual = residual(e);
      if (e.residual < best.residual) best = e;
    };
    consider({Kind::kLateralPlus, k, 0, true});
    consider({Kind::kLateralMinus, k, 0, true});
    for (const ForceCondition& c : c_.extra_speed_conditions())
      consider({Kind::kSpeedCondition, k, 0, true, 0.0, &c});
    if (std::isfinite(vmax2_)) consider({Kind::kMaxSpeed, k, 0, true});
    if (c_.wheels() != nullptr) consider({Kind::kWheelContact, k, 0, true});
    return best;
  }

  /// Appends the control conditions step j touches, at either end: the
  /// friction ellipse (plus the tangent condition where the step's line
  /// touches it), else f_t = 0 where lateral friction is exhausted, then the
  /// vehicle's traction conditions. The ellipse comes first even near
  /// exhaustion: a state a few 1e-9 below the tip of a sliding limit leaves
  /// f_t a range about sqrt(1e-9) of the force scale wide, and a step whose
  /// control ends on that range's edge pins the state by the ellipse (taking
  /// f_t = 0 there left such states without an equation on the battery).
  void active_step_equations(std::size_t j, std::vector<Equation>& out) const {
    for (std::size_t station : {j, j + 1}) {
      const auto add = [&](Equation e) {
        e.residual = residual(e);
        if (e.residual > control_tolerance(j, station)) return false;
        out.push_back(e);
        if (e.kind == Kind::kFriction && tangent(j, station, e.coupling)) {
          e.kind = Kind::kTangentControl;
          out.push_back(e);
        }
        return true;
      };
      // The friction cone, or the lighter axle's two coupled cones (one is touched at most,
      // unless f_t f_q = 0, where both meet and the first stands for them).
      const double beta = c_.friction_coupling();
      bool friction = false;
      for (const double coupling : {beta, -beta}) {
        Equation e{Kind::kFriction, station, j, false};
        e.coupling = coupling;
        friction = friction || add(e);
        if (friction || beta == 0.0) break;
      }
      if (!friction && friction_exhausted(station)) add({Kind::kTractionZero, station, j, false});
      for (const ForceCondition& c : c_.traction_conditions())
        add({Kind::kTraction, station, j, false, 0.0, &c});
    }
  }

  /// Residual below which a control condition of step j counts as touched:
  /// kActiveTolerance plus what the solver's relative nudges of the states
  /// (up to 1e-9 of x, time_optimal_profile.cpp) make of the control
  /// u = Δx / (2 Δs), in units of the station's force scale.
  double control_tolerance(std::size_t j, std::size_t station) const {
    const double u_nudge = kStateNudge * (x_[j] + x_[j + 1]) / (2.0 * length(j));
    return kActiveTolerance + 2.0 * u_nudge / scale(station, control(j));
  }

  /// Whether step j's line touches the friction ellipse of `station` (one
  /// of its ends) at the step's control: there the friction equation fixes
  /// only the near state, and the double root fixes the control.
  bool tangent(std::size_t j, std::size_t station, double coupling) const {
    const auto G = g(station);
    const double u = control(j);
    const bool far_end = station == j + 1;
    const double y0 = far_end ? x_[j] : x_[j + 1];
    const double beta = (far_end ? 2.0 : -2.0) * length(j);
    const auto [A, B] = ellipse_along_line<double>(c_, coupling, y0, beta, G.data());
    const double slope = 2.0 * A * u + B;  // d/du of the ellipse along the line
    return std::abs(slope) <=
           kTangentTolerance * (std::abs(B) + std::abs(2.0 * A * u) + scale(station, u));
  }

  /// Value and derivatives of an equation in (x_j, x_{j+1}, Δs_j, G).
  Ad differentiate(const Equation& e) const {
    const auto G = g(e.station);
    Ad vars[kVariables];
    const double values[kVariables] = {e.speed_only ? x_[e.station] : x_[e.step],
                                       e.speed_only ? 0.0 : x_[e.step + 1],
                                       e.speed_only ? 1.0 : length(e.step),
                                       G[0],
                                       G[1],
                                       G[2],
                                       G[3],
                                       G[4],
                                       G[5]};
    for (int i = 0; i < kVariables; ++i) vars[i] = Ad(values[i], kVariables, i);
    const Ad u = e.speed_only ? Ad(0.0) : (vars[1] - vars[0]) / (2.0 * vars[2]);
    const Ad& x = e.speed_only ? vars[0] : (e.station == e.step ? vars[0] : vars[1]);
    if (e.kind == Kind::kTangentControl) {
      const bool far_end = e.station == e.step + 1;
      const Ad beta = (far_end ? 2.0 : -2.0) * vars[2];
      return tangent_control<Ad>(c_, e.coupling, far_end ? vars[0] : vars[1], beta, u, vars + 3);
    }
    return constraint<Ad>(e.kind, e.condition, e.coupling, c_, vmax2_, x, u, vars + 3);
  }

 private:
  AdmissibleSet c_;
  double vmax2_;
  const std::vector<StationGeometry>& geometry_;
  const std::vector<double>& s_;
  std::vector<double> x_;
};

}  // namespace

bool travel_time_sensitivity(const Vehicle& vehicle, const std::vector<StationGeometry>& geometry,
                             const std::vector<double>& s, const std::vector<double>& speeds,
                             TravelTimeSensitivity& out) {
  const std::size_t m = speeds.size();
  if (m < 2 || geometry.size() != m || s.size() != m) return false;
  for (std::size_t j = 0; j + 1 < m; ++j) {
    if (!(s[j + 1] > s[j])) return false;
  }
  const Problem problem(vehicle, geometry, s, speeds);
  out.geometry.assign(m, {0.0, 0.0, 0.0, 0.0, 0.0, 0.0});
  out.step_length.assign(m - 1, 0.0);

  // Direct partials of T.
  std::vector<double> dT_dx(m, 0.0);
  for (std::size_t j = 0; j + 1 < m; ++j) {
    const double a = std::sqrt(problem.x(j)), b = std::sqrt(problem.x(j + 1));
    const double sum = a + b;
    if (!(sum > 0.0)) return false;
    // A standstill inside the path makes dT/dx infinite there.
    if ((a == 0.0 && j > 0) || (b == 0.0 && j + 2 < m)) return false;
    out.step_length[j] = 2.0 / sum;
    const double common = -problem.length(j) / (sum * sum);
    if (a > 0.0) dT_dx[j] += common / a;
    if (b > 0.0) dT_dx[j + 1] += common / b;
  }
  if (m == 2) return true;  // no interior state

  // Every constraint the profile touches is an equation: speed conditions
  // pin single stations; control conditions tie the two states of a step (a
  // step can touch two, where the profile rides the boundary of the
  // admissible set between stations). Consistent and, off degenerate
  // profiles, of full column rank: solved in the least-squares sense, which
  // is exact for a consistent system.
  std::vector<Equation> equations;
  for (std::size_t k = 1; k + 1 < m; ++k) {
    const Equation e = problem.best_speed_equation(k);
    if (e.residual <= kActiveTolerance) equations.push_back(e);
  }
  for (std::size_t j = 0; j + 1 < m; ++j) problem.active_step_equations(j, equations);
  const std::size_t n = m - 2;  // interior states x_1 .. x_{m-2} are the unknowns
  if (equations.size() < n) return false;

  std::vector<Eigen::Triplet<double>> entries;
  std::vector<Ad> derivatives;
  derivatives.reserve(equations.size());
  const auto column = [m](std::size_t station) -> long {
    return (station == 0 || station + 1 == m) ? -1 : static_cast<long>(station) - 1;
  };
  for (std::size_t r = 0; r < equations.size(); ++r) {
    const Equation& e = equations[r];
    derivatives.push_back(problem.differentiate(e));
    const auto& d = derivatives.back().derivatives();
    const std::size_t first = e.speed_only ? e.station : e.step;
    if (const long col = column(first); col >= 0)
      entries.emplace_back(static_cast<long>(r), col, d[0]);
    if (!e.speed_only) {
      if (const long col = column(e.step + 1); col >= 0)
        entries.emplace_back(static_cast<long>(r), col, d[1]);
    }
  }
  const auto rows = static_cast<long>(equations.size());
  Eigen::SparseMatrix<double> jacobian(rows, static_cast<long>(n));
  jacobian.setFromTriplets(entries.begin(), entries.end());
  // λ = J (JᵀJ)⁻¹ ∂T/∂xᵀ: the multipliers of the least-squares solution.
  const Eigen::SparseMatrix<double> normal = jacobian.transpose() * jacobian;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(normal);
  if (ldlt.info() != Eigen::Success) return false;
  const Eigen::VectorXd pivots = ldlt.vectorD();
  if (!(pivots.minCoeff() > 1e-14 * pivots.cwiseAbs().maxCoeff())) return false;  // rank-deficient
  Eigen::VectorXd rhs(static_cast<long>(n));
  for (std::size_t k = 1; k + 1 < m; ++k) rhs[static_cast<long>(k) - 1] = dT_dx[k];
  const Eigen::VectorXd lambda = jacobian * ldlt.solve(rhs);
  if (!lambda.allFinite()) return false;

  for (std::size_t r = 0; r < equations.size(); ++r) {
    const Equation& e = equations[r];
    const auto& d = derivatives[r].derivatives();
    const double l = lambda[static_cast<long>(r)];
    if (!e.speed_only) out.step_length[e.step] -= l * d[2];
    for (int i = 0; i < kGeometry; ++i)
      out.geometry[e.station][static_cast<std::size_t>(i)] -= l * d[3 + i];
  }
  return true;
}

}  // namespace talus::detail
