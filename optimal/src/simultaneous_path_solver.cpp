#include "simultaneous_path_solver.hpp"

#include <IpIpoptApplication.hpp>
#include <IpTNLP.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <utility>
#include <vector>

#include "ipopt_lock.hpp"
#include "ipopt_status.hpp"
#include "station_derivatives.hpp"
#include "steering_rows.hpp"
#include "talus/core/error.hpp"
#include "talus/dynamics/admissible_set.hpp"
#include "talus/optimal/hessian_probes.hpp"

namespace talus::detail {
namespace {

using Ipopt::Index;
using Ipopt::Number;

/// Ipopt's "infinite" bound.
constexpr double kIpoptInfinity = 1e19;

class SimultaneousNlp : public Ipopt::TNLP {
 public:
  explicit SimultaneousNlp(const SimultaneousProblem& problem)
      : problem_(problem),
        terrain_(*problem.terrain),
        set_(problem.vehicle),
        steering_(problem.initial->knots()),
        max_curvature_(problem.vehicle.max_curvature()),
        control_(problem.initial->control_points()),
        points_(control_.size()),
        stations_(problem.stations) {
    const std::size_t m = points_;
    if (m < 4 || stations_ < 2) throw InputError("the simultaneous stage needs M >= 4, N >= 2");
    dims_ = problem.lateral_offsets ? 1 : 2;
    free_ = dims_ * (m - 2);
    origin_ = control_;
    // Each point's lateral direction: normal to the chord of its neighbours
    // in the initial control polygon.
    normal_.assign(m, Vec2::Zero());
    for (std::size_t i = 1; i + 1 < m; ++i) {
      const Vec2 chord = control_[i + 1] - control_[i - 1];
      normal_[i] = chord.norm() > 0.0 ? Vec2(-chord.y(), chord.x()) / chord.norm() : Vec2(0, 1);
    }
    for (const ForceCondition& c : set_.conditions()) conditions_.push_back(c);
    wheel_row_ = set_.wheels() != nullptr;
    cone_rows_ = set_.friction_coupling() > 0.0 ? 2 : 1;
    rows_per_end_ = cone_rows_ + conditions_.size() + (wheel_row_ ? 1 : 0);
    const KnotVector& knots = problem.initial->knots();
    first_basis_.resize(stations_);
    basis_.resize(stations_);
    Eigen::MatrixXd values(3, 4);
    for (std::size_t k = 0; k < stations_; ++k) {
      const double sigma =
          (k + 1 == stations_) ? 1.0 : static_cast<double>(k) / static_cast<double>(stations_ - 1);
      const std::size_t span = knots.find_span(sigma);
      knots.basis_derivatives(span, sigma, values);
      first_basis_[k] = span - 3;
      basis_[k] = values;
    }
    h_ = 1.0 / static_cast<double>(stations_ - 1);
    // Jacobian columns of each step: the free coordinates of the control
    // points that move either end, then b_j and b_{j+1}.
    step_columns_.resize(stations_ - 1);
    for (std::size_t j = 0; j + 1 < stations_; ++j) {
      auto& columns = step_columns_[j];
      for (std::size_t i = first_basis_[j]; i <= first_basis_[j + 1] + 3; ++i) {
        for (std::size_t d = 0; d < dims_; ++d) {
          columns.push_back(i == 0 || i + 1 == m ? -1 : static_cast<Index>(dims_ * (i - 1) + d));
        }
      }
      columns.push_back(static_cast<Index>(free_ + j));
      columns.push_back(static_cast<Index>(free_ + j + 1));
      for (Index c : columns) nonzeros_ += c >= 0 ? static_cast<Index>(2 * rows_per_end_) : 0;
    }
    // The steering rows (a finite limit only): each sample's entries in the
    // free columns (a lateral offset moves its point along the normal).
    steering_rows_ = std::isfinite(max_curvature_) ? steering_.size() : 0;
    if (steering_rows_ > 0) {
      for (const SteeringRows::Entry& e : steering_.pattern()) {
        const Index column = static_cast<Index>(dims_ * (e.point - 1) + (dims_ == 2 ? e.axis : 0));
        const auto key = std::make_pair(static_cast<Index>(e.row), column);
        if (steering_entries_.empty() || steering_entries_.back() != key)
          steering_entries_.push_back(key);
      }
      steering_jacobian_.resize(steering_.pattern().size());
      steering_values_.resize(steering_rows_);
    }
    // The Lagrangian's Hessian couples two variables iff they share a step
    // or a steering sample: the lower triangle of every clique.
    std::set<std::pair<Index, Index>> entries;
    const auto clique = [&](const std::vector<Index>& columns) {
      for (Index a : columns) {
        for (Index b : columns) {
          if (a >= 0 && b >= 0 && a >= b) entries.insert({a, b});
        }
      }
    };
    for (const auto& columns : step_columns_) clique(columns);
    for (std::size_t r = 0; r < steering_rows_; ++r) {
      std::vector<Index> columns;
      for (const auto& [row, column] : steering_entries_)
        if (row == static_cast<Index>(r)) columns.push_back(column);
      clique(columns);
    }
    hessian_entries_.assign(entries.begin(), entries.end());
    groups_ = probe_groups(hessian_entries_, free_, free_ + stations_);
    colour_.assign(free_, 0);
    for (std::size_t g = 0; g < groups_.size(); ++g) {
      for (std::size_t c : groups_[g]) colour_[c] = g;
    }
    const long n = static_cast<long>(free_ + stations_);
    group_columns_.assign(groups_.size(), Eigen::VectorXd::Zero(n));
    for (auto& b : b_columns_) b = Eigen::VectorXd::Zero(n);
    value_.resize(stations_);
    derivative_.resize(stations_);
    step_length_.resize(stations_ - 1);
  }

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag,
                    IndexStyleEnum& index_style) override {
    n = static_cast<Index>(free_ + stations_);
    m = static_cast<Index>((stations_ - 1) * 2 * rows_per_end_ + steering_rows_);
    nnz_jac_g = nonzeros_ + static_cast<Index>(steering_entries_.size());
    nnz_h_lag = static_cast<Index>(hessian_entries_.size());
    index_style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Index, Number* x_l, Number* x_u, Index m, Number* g_l,
                       Number* g_u) override {
    for (std::size_t i = 1; i + 1 < points_; ++i) {
      const long a = 2 * static_cast<long>(i) - 2;
      const Vec2 lo(problem_.lower[a], problem_.lower[a + 1]);
      const Vec2 hi(problem_.upper[a], problem_.upper[a + 1]);
      if (dims_ == 2) {
        for (int axis = 0; axis < 2; ++axis) {
          x_l[2 * (i - 1) + axis] = lo[axis] - origin_[i][axis];
          x_u[2 * (i - 1) + axis] = hi[axis] - origin_[i][axis];
        }
        continue;
      }
      // The offsets that keep the point in the box.
      double lower = -kIpoptInfinity, upper = kIpoptInfinity;
      for (int axis = 0; axis < 2; ++axis) {
        const double nu = normal_[i][axis];
        if (std::abs(nu) < 1e-12) continue;
        double a0 = (lo[axis] - origin_[i][axis]) / nu, a1 = (hi[axis] - origin_[i][axis]) / nu;
        if (a0 > a1) std::swap(a0, a1);
        lower = std::max(lower, a0);
        upper = std::min(upper, a1);
      }
      x_l[i - 1] = std::min(lower, 0.0);
      x_u[i - 1] = std::max(upper, 0.0);
    }
    const double v_max = set_.max_speed();
    const double b_max = std::isfinite(v_max) ? v_max * v_max : kIpoptInfinity;
    for (std::size_t k = 0; k < stations_; ++k) {
      x_l[free_ + k] = kMinSquaredSpeed;
      x_u[free_ + k] = b_max;
    }
    const double b0 = end_value(problem_.speeds.start_speed);
    const double b1 = end_value(problem_.speeds.end_speed);
    x_l[free_] = x_u[free_] = b0;
    x_l[free_ + stations_ - 1] = x_u[free_ + stations_ - 1] = b1;
    const Index speed_rows = m - static_cast<Index>(steering_rows_);
    for (Index r = 0; r < speed_rows; ++r) {
      g_l[r] = 0.0;
      g_u[r] = kIpoptInfinity;
    }
    const double kappa = (1.0 - SteeringRows::kMargin) * max_curvature_;
    for (Index r = speed_rows; r < m; ++r) {
      g_l[r] = -kappa;
      g_u[r] = kappa;
    }
    return true;
  }

  bool get_starting_point(Index, bool, Number* x, bool, Number*, Number*, Index, bool,
                          Number*) override {
    for (std::size_t i = 0; i < free_; ++i) x[i] = 0.0;
    const double v_max = set_.max_speed();
    // Without a profile to start from: slow (a tenth of the speed cap, at
    // most 1 m/s), where the constraints are nearly those of standing still.
    const double slow = std::min(1.0, std::isfinite(v_max) ? 0.01 * v_max * v_max : 1.0);
    for (std::size_t k = 0; k < stations_; ++k) {
      double b = problem_.initial_squared_speeds.size() == stations_
                     ? problem_.initial_squared_speeds[k]
                     : slow;
      if (std::isfinite(v_max)) b = std::min(b, v_max * v_max);
      x[free_ + k] = std::max(b, kMinSquaredSpeed);
    }
    x[free_] = end_value(problem_.speeds.start_speed);
    x[free_ + stations_ - 1] = end_value(problem_.speeds.end_speed);
    return true;
  }

  bool eval_f(Index, const Number* x, bool, Number& value) override {
    if (!update(x)) return false;
    value = 0.0;
    for (std::size_t j = 0; j + 1 < stations_; ++j) {
      value += 2.0 * step_length_[j] / (std::sqrt(x[free_ + j]) + std::sqrt(x[free_ + j + 1]));
    }
    return std::isfinite(value);
  }

  bool eval_grad_f(Index n, const Number* x, bool, Number* gradient) override {
    if (!update(x)) return false;
    ++gradient_evaluations_;
    std::fill(gradient, gradient + n, 0.0);
    add_objective_gradient(x, 1.0, gradient);
    return true;
  }

  bool eval_h(Index n, const Number* x, bool, Number obj_factor, Index, const Number* lambda, bool,
              Index, Index* i_row, Index* j_col, Number* values) override {
    if (values == nullptr) {
      for (std::size_t e = 0; e < hessian_entries_.size(); ++e) {
        i_row[e] = hessian_entries_[e].first;
        j_col[e] = hessian_entries_[e].second;
      }
      return true;
    }
    // Forward differences of the Lagrangian's exact gradient: one probe per
    // group of control coordinates that share no row of the Hessian
    // (probe_groups(): about nine groups however many points; with a probe
    // per coordinate a 57-point polish on battery seed 5 took 3.3 s instead
    // of 1.3 s), and three interleaved groups of b (b_k and b_{k+3} never
    // share a step); the b-coordinate entries come from the coordinates'
    // columns (symmetry). Forward rather than central: half the geometry
    // evaluations, and Ipopt's Newton steps need no more than the O(h)
    // accuracy. A b probe leaves the geometry as it is (update() keys on the
    // control coordinates), so it costs only the rows.
    const long dimension = n;
    std::vector<double> probe(x, x + n);
    Eigen::VectorXd& base = base_gradient_;
    base.resize(dimension);
    Eigen::VectorXd plus(dimension);
    if (!lagrangian_gradient(x, obj_factor, lambda, base)) return false;
    const double control_step = 1e-4 * terrain_.cellsize();
    const auto column = [&](auto&& perturb, Eigen::VectorXd& out) {
      perturb();
      const bool ok = lagrangian_gradient(probe.data(), obj_factor, lambda, plus);
      std::copy(x, x + n, probe.begin());
      out = plus - base;
      return ok;
    };
    // The speed probes first, while the workspace still holds x's geometry.
    std::vector<double> b_step(stations_);
    for (std::size_t k = 0; k < stations_; ++k) b_step[k] = 1e-4 * x[free_ + k] + 1e-8;
    bool ok = true;
    for (std::size_t group = 0; group < 3 && ok; ++group) {
      ok = column(
          [&] {
            for (std::size_t k = group; k < stations_; k += 3)
              probe[free_ + k] = x[free_ + k] + b_step[k];
          },
          b_columns_[group]);
    }
    for (std::size_t group = 0; group < groups_.size() && ok; ++group) {
      ok = column(
          [&] {
            for (std::size_t c : groups_[group]) probe[c] = x[c] + control_step;
          },
          group_columns_[group]);
      group_columns_[group] /= control_step;
    }
    if (!ok) return false;
    for (std::size_t e = 0; e < hessian_entries_.size(); ++e) {
      const auto [r, c] = hessian_entries_[e];
      const std::size_t col = static_cast<std::size_t>(c);
      if (col < free_) {
        values[e] = group_columns_[colour_[col]][r];
      } else {
        const std::size_t k = col - free_;
        values[e] = b_columns_[k % 3][r] / b_step[k];
      }
    }
    return true;
  }

 private:
  /// ∇(factor f + λᵀ g) at x (updates the workspace there).
  bool lagrangian_gradient(const Number* x, double factor, const Number* lambda,
                           Eigen::VectorXd& out) {
    if (!update(x)) return false;
    out.setZero();
    add_objective_gradient(x, factor, out.data());
    std::vector<double>& rows = rows_;
    rows.resize(2 * rows_per_end_);
    for (std::size_t j = 0; j + 1 < stations_; ++j) {
      step_rows(j, x, rows.data(), &jacobian_);
      const auto& columns = step_columns_[j];
      const Number* l = lambda + row_offset(j);
      for (std::size_t c = 0; c < columns.size(); ++c) {
        if (columns[c] < 0) continue;
        double sum = 0.0;
        for (std::size_t r = 0; r < 2 * rows_per_end_; ++r)
          sum += l[r] * jacobian_(static_cast<long>(r), static_cast<long>(c));
        out[columns[c]] += sum;
      }
    }
    if (steering_rows_ > 0) {
      if (!steering_jacobian_at(x)) return false;
      const Number* l = lambda + row_offset(stations_ - 1);
      for (std::size_t e = 0; e < steering_entries_.size(); ++e)
        out[steering_entries_[e].second] += l[steering_entries_[e].first] * steering_sparse_[e];
    }
    return true;
  }

  /// gradient += factor ∇T at x (workspace up to date).
  void add_objective_gradient(const Number* x, double factor, Number* gradient) {
    Eigen::VectorXd& local = local_;
    for (std::size_t j = 0; j + 1 < stations_; ++j) {
      const double r0 = std::sqrt(x[free_ + j]), r1 = std::sqrt(x[free_ + j + 1]);
      const double sum = r0 + r1;
      const double dt_ds = 2.0 / sum;
      const double dt_dsum = -2.0 * step_length_[j] / (sum * sum);
      step_length_gradient(j, local);
      const auto& columns = step_columns_[j];
      const std::size_t controls = columns.size() - 2;
      for (std::size_t c = 0; c < controls; ++c) {
        if (columns[c] >= 0) gradient[columns[c]] += factor * dt_ds * local[static_cast<long>(c)];
      }
      gradient[free_ + j] += factor * dt_dsum * 0.5 / r0;
      gradient[free_ + j + 1] += factor * dt_dsum * 0.5 / r1;
    }
  }

 public:
  bool eval_g(Index, const Number* x, bool, Index, Number* g) override {
    if (!update(x)) return false;
    for (std::size_t j = 0; j + 1 < stations_; ++j) step_rows(j, x, g + row_offset(j), nullptr);
    if (steering_rows_ > 0)
      return steering_.evaluate(control_, g + row_offset(stations_ - 1), nullptr);
    return true;
  }

  bool eval_jac_g(Index, const Number* x, bool, Index, Index, Index* i_row, Index* j_col,
                  Number* values) override {
    if (values == nullptr) {
      Index e = 0;
      for (std::size_t j = 0; j + 1 < stations_; ++j) {
        for (std::size_t r = 0; r < 2 * rows_per_end_; ++r) {
          for (Index c : step_columns_[j]) {
            if (c < 0) continue;
            i_row[e] = static_cast<Index>(row_offset(j) + r);
            j_col[e] = c;
            ++e;
          }
        }
      }
      for (const auto& [row, column] : steering_entries_) {
        i_row[e] = static_cast<Index>(row_offset(stations_ - 1)) + row;
        j_col[e] = column;
        ++e;
      }
      return true;
    }
    if (!update(x)) return false;
    Index e = 0;
    std::vector<double> rows(2 * rows_per_end_);
    for (std::size_t j = 0; j + 1 < stations_; ++j) {
      step_rows(j, x, rows.data(), &jacobian_);
      const auto& columns = step_columns_[j];
      for (std::size_t r = 0; r < 2 * rows_per_end_; ++r) {
        for (std::size_t c = 0; c < columns.size(); ++c) {
          if (columns[c] < 0) continue;
          values[e++] = jacobian_(static_cast<long>(r), static_cast<long>(c));
        }
      }
    }
    if (steering_rows_ > 0) {
      if (!steering_jacobian_at(x)) return false;
      std::copy(steering_sparse_.begin(), steering_sparse_.end(), values + e);
    }
    return true;
  }

  bool intermediate_callback(Ipopt::AlgorithmMode, Index iteration, Number, Number, Number, Number,
                             Number, Number, Number, Number, Index, const Ipopt::IpoptData*,
                             Ipopt::IpoptCalculatedQuantities*) override {
    iterations_ = static_cast<std::size_t>(iteration);
    if (problem_.termination.should_stop()) {
      timed_out_ = true;
      return false;
    }
    return true;
  }
  bool timed_out() const { return timed_out_; }

  void finalize_solution(Ipopt::SolverReturn status, Index, const Number* x, const Number*,
                         const Number*, Index, const Number*, const Number*, Number objective,
                         const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
    status_ = status;
    set_control(x);
    result_z_.resize(2 * static_cast<long>(points_ - 2));
    for (std::size_t i = 1; i + 1 < points_; ++i) {
      result_z_[2 * static_cast<long>(i) - 2] = control_[i].x();
      result_z_[2 * static_cast<long>(i) - 1] = control_[i].y();
    }
    result_b_.assign(x + free_, x + free_ + stations_);
    objective_ = objective;
  }

  Ipopt::SolverReturn status() const { return status_; }
  std::size_t iterations() const { return iterations_; }
  std::size_t evaluations() const { return evaluations_; }
  std::size_t gradient_evaluations() const { return gradient_evaluations_; }
  const Eigen::VectorXd& result_variables() const { return result_z_; }
  const std::vector<double>& result_squared_speeds() const { return result_b_; }
  double objective() const { return objective_; }

 private:
  static double end_value(double speed) { return std::max(speed * speed, kMinSquaredSpeed); }
  std::size_t row_offset(std::size_t step) const { return step * 2 * rows_per_end_; }

  void set_control(const Number* x) {
    for (std::size_t i = 1; i + 1 < points_; ++i) {
      const std::size_t a = dims_ * (i - 1);
      control_[i] = dims_ == 2 ? Vec2(origin_[i].x() + x[a], origin_[i].y() + x[a + 1])
                               : Vec2(origin_[i] + x[a] * normal_[i]);
    }
  }

  /// The steering rows' Jacobian at x into steering_sparse_ (steering_entries_
  /// order): dκ/dP chained to the free columns. False at a cusp.
  bool steering_jacobian_at(const Number* x) {
    set_control(x);
    if (!steering_.evaluate(control_, nullptr, steering_jacobian_.data())) return false;
    steering_sparse_.assign(steering_entries_.size(), 0.0);
    std::size_t e = 0;
    const auto& pattern = steering_.pattern();
    for (std::size_t p = 0; p < pattern.size(); ++p) {
      const Index column =
          static_cast<Index>(dims_ * (pattern[p].point - 1) + (dims_ == 2 ? pattern[p].axis : 0));
      const auto key = std::make_pair(static_cast<Index>(pattern[p].row), column);
      while (steering_entries_[e] != key) ++e;
      const double along = dims_ == 2 ? 1.0 : normal_[pattern[p].point][pattern[p].axis];
      steering_sparse_[e] += along * steering_jacobian_[p];
    }
    return true;
  }

  /// The station geometry and its derivatives at x; false where a station
  /// leaves the data, the curve has a cusp or a step has no length. Keyed on
  /// the control coordinates the workspace holds (the speeds do not enter
  /// the geometry), not on Ipopt's new_x: eval_h's probes move the workspace
  /// away from Ipopt's current point.
  bool update(const Number* x) {
    if (cached_ && std::equal(x, x + free_, cached_controls_.begin())) return valid_;
    cached_ = true;
    cached_controls_.assign(x, x + free_);
    valid_ = false;
    ++evaluations_;
    set_control(x);
    for (std::size_t k = 0; k < stations_; ++k) {
      Eigen::Matrix<double, 2, 3> p = Eigen::Matrix<double, 2, 3>::Zero();
      for (int b = 0; b < 4; ++b) {
        const Vec2& c = control_[first_basis_[k] + static_cast<std::size_t>(b)];
        for (int d = 0; d < 3; ++d) p.col(d) += basis_[k](d, b) * c;
      }
      const Vec2 position = p.col(0);
      if (!p.allFinite() || !terrain_.contains(position) || !terrain_.on_data(position))
        return false;
      if (!(p.col(1).norm() > 0.0)) return false;
      const StationDerivatives sd = station_derivatives(terrain_, p, set_.wheels());
      if (!sd.value.allFinite() || !sd.jacobian.allFinite()) return false;
      value_[k] = sd.value;
      // Chain to the station's four control points: column dims b + d.
      derivative_[k].setZero();
      for (int b = 0; b < 4; ++b) {
        const std::size_t i = first_basis_[k] + static_cast<std::size_t>(b);
        for (int axis = 0; axis < 2; ++axis) {
          const Eigen::Matrix<double, StationDerivatives::kRows, 1> along =
              sd.jacobian.col(axis) * basis_[k](0, b) +
              sd.jacobian.col(2 + axis) * basis_[k](1, b) +
              sd.jacobian.col(4 + axis) * basis_[k](2, b);
          if (dims_ == 2) {
            derivative_[k].col(2 * b + axis) = along;
          } else {
            derivative_[k].col(b) += normal_[i][axis] * along;
          }
        }
      }
    }
    for (std::size_t j = 0; j + 1 < stations_; ++j) {
      step_length_[j] = 0.5 * h_ * (value_[j][5] + value_[j + 1][5]) +
                        h_ * h_ / 12.0 * (value_[j][6] - value_[j + 1][6]);
      if (!(step_length_[j] > 0.0)) return false;
    }
    valid_ = true;
    return true;
  }

  /// dΔs_j over the step's columns (step_columns_ order, b entries zero).
  void step_length_gradient(std::size_t j, Eigen::VectorXd& out) const {
    out.setZero(static_cast<long>(step_columns_[j].size()));
    const double a = 0.5 * h_, c = h_ * h_ / 12.0;
    for (int end = 0; end < 2; ++end) {
      const std::size_t k = j + static_cast<std::size_t>(end);
      const long offset = static_cast<long>(dims_ * (first_basis_[k] - first_basis_[j]));
      const long w = static_cast<long>(4 * dims_);
      const double sign = end == 0 ? 1.0 : -1.0;
      out.segment(offset, w) +=
          (a * derivative_[k].row(5) + sign * c * derivative_[k].row(6)).head(w).transpose();
    }
  }

  /// The 2 (cones + C [+ 1]) constraint values of step j (the friction cone, or the lighter
  /// axle's two coupled cones, each ForceCondition, and with wheels contact at the wheels,
  /// g k_r + κ_w ṡ² >= 0, at its first end and then at its second) and, when
  /// `jacobian` is given, their derivatives over the step's columns.
  void step_rows(std::size_t j, const Number* x, double* rows, Eigen::MatrixXd* jacobian) {
    const double g = set_.gravity(), mu = set_.friction();
    const double b0 = x[free_ + j], b1 = x[free_ + j + 1];
    const double ds = step_length_[j];
    const double u = (b1 - b0) / (2.0 * ds);
    const long width = static_cast<long>(step_columns_[j].size());
    const long col_b0 = width - 2, col_b1 = width - 1;
    Eigen::VectorXd &du = du_, &dft = dft_, &dfq = dfq_, &dr = dr_;
    if (jacobian != nullptr) {
      jacobian->setZero(static_cast<long>(2 * rows_per_end_), width);
      step_length_gradient(j, du);
      du *= -u / ds;
      du[col_b0] = -1.0 / (2.0 * ds);
      du[col_b1] = 1.0 / (2.0 * ds);
    }
    for (int end = 0; end < 2; ++end) {
      const std::size_t k = j + static_cast<std::size_t>(end);
      const double b = end == 0 ? b0 : b1;
      const auto& v = value_[k];
      const double ft = u + g * v[2];
      const double fq = g * v[3] + v[1] * b;
      const double rn = g * v[4] + v[0] * b;
      double* out = rows + static_cast<std::size_t>(end) * rows_per_end_;
      for (std::size_t c = 0; c < cone_rows_; ++c) {
        const double coupling = cone_coupling(c);
        out[c] = (mu * mu * rn * rn - ft * ft - 2.0 * coupling * ft * fq - fq * fq) / (2.0 * g);
      }
      for (std::size_t c = 0; c < conditions_.size(); ++c) {
        const ForceCondition& f = conditions_[c];
        out[cone_rows_ + c] = f.t * ft + f.q * fq + f.r * rn + f.c;
      }
      if (wheel_row_)
        out[cone_rows_ + conditions_.size()] = g * v[4] - set_.contact_reserve() + v[7] * b;
      if (jacobian == nullptr) continue;
      // d(f_t, f_q, R) over the step's columns.
      const long offset = static_cast<long>(dims_ * (first_basis_[k] - first_basis_[j]));
      const long w = static_cast<long>(4 * dims_);
      const auto& d = derivative_[k];
      dft = du;
      dft.segment(offset, w) += g * d.row(2).head(w).transpose();
      dfq.setZero(width);
      dfq.segment(offset, w) = (g * d.row(3) + b * d.row(1)).head(w).transpose();
      dr.setZero(width);
      dr.segment(offset, w) = (g * d.row(4) + b * d.row(0)).head(w).transpose();
      const long col_b = end == 0 ? col_b0 : col_b1;
      dfq[col_b] += v[1];
      dr[col_b] += v[0];
      const long row = static_cast<long>(static_cast<std::size_t>(end) * rows_per_end_);
      for (std::size_t c = 0; c < cone_rows_; ++c) {
        const double coupling = cone_coupling(c);
        jacobian->row(row + static_cast<long>(c)) =
            ((mu * mu * rn) * dr - (ft + coupling * fq) * dft - (fq + coupling * ft) * dfq)
                .transpose() /
            g;
      }
      for (std::size_t c = 0; c < conditions_.size(); ++c) {
        const ForceCondition& f = conditions_[c];
        jacobian->row(row + static_cast<long>(cone_rows_ + c)) =
            (f.t * dft + f.q * dfq + f.r * dr).transpose();
      }
      if (wheel_row_) {
        Eigen::VectorXd& dw = dw_;
        dw.setZero(width);
        dw.segment(offset, w) = (g * d.row(4) + b * d.row(7)).head(w).transpose();
        dw[col_b] += v[7];
        jacobian->row(row + static_cast<long>(cone_rows_ + conditions_.size())) = dw.transpose();
      }
    }
  }

  const SimultaneousProblem& problem_;
  const BPatch& terrain_;
  AdmissibleSet set_;
  SteeringRows steering_;
  double max_curvature_;  // the vehicle's steering limit [1/m]; +inf: no steering rows
  std::size_t steering_rows_ = 0;
  std::vector<std::pair<Index, Index>> steering_entries_;  // (sample, free column), sorted
  std::vector<double> steering_jacobian_, steering_sparse_, steering_values_;
  std::vector<ForceCondition> conditions_;
  std::vector<Vec2> control_;  // workspace: the current control points
  std::size_t points_, stations_, dims_ = 2, free_ = 0, rows_per_end_ = 0;
  bool wheel_row_ = false;     // contact at the wheels (rigid body): one more row per end
  std::size_t cone_rows_ = 1;  // the friction cone, or the lighter axle's two cones
  /// The coupling of cone row c: 0 for the friction cone, ± AdmissibleSet::friction_coupling().
  double cone_coupling(std::size_t c) const {
    return cone_rows_ == 1 ? 0.0 : (c == 0 ? 1.0 : -1.0) * set_.friction_coupling();
  }
  std::vector<Vec2> origin_, normal_;  // the initial control points, their lateral directions
  double h_ = 0.0;
  std::vector<std::size_t> first_basis_;
  std::vector<Eigen::Matrix<double, 3, 4>> basis_;
  std::vector<std::vector<Index>> step_columns_;
  Index nonzeros_ = 0;
  // Per-point cache.
  std::vector<Eigen::Matrix<double, StationDerivatives::kRows, 1>> value_;
  std::vector<Eigen::Matrix<double, StationDerivatives::kRows, 8>> derivative_;
  std::vector<double> step_length_;
  Eigen::MatrixXd jacobian_;
  std::vector<double> rows_;
  Eigen::VectorXd local_, du_, dft_, dfq_, dr_, dw_;
  std::vector<std::pair<Index, Index>> hessian_entries_;  // (row, column), row >= column
  std::vector<std::size_t> colour_;                       // each control coordinate's group
  std::vector<std::vector<std::size_t>> groups_;          // the coordinates probed together
  std::vector<Eigen::VectorXd> group_columns_;            // each group's difference quotient
  std::array<Eigen::VectorXd, 3> b_columns_;
  bool cached_ = false, valid_ = false;
  std::vector<double> cached_controls_;  // the control coordinates the workspace holds
  Eigen::VectorXd base_gradient_;
  // Outcome.
  Ipopt::SolverReturn status_ = Ipopt::UNASSIGNED;
  bool timed_out_ = false;
  std::size_t iterations_ = 0, evaluations_ = 0, gradient_evaluations_ = 0;
  Eigen::VectorXd result_z_;
  std::vector<double> result_b_;
  double objective_ = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace

SimultaneousRun run_simultaneous(const SimultaneousProblem& problem) {
  const auto ipopt_lock = detail::lock_ipopt();  // before the SmartPtrs: released after them
  Ipopt::SmartPtr<SimultaneousNlp> nlp = new SimultaneousNlp(problem);
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
  auto options = app->Options();
  options->SetIntegerValue("print_level", 0);
  options->SetStringValue("sb", "yes");
  if (problem.limited_memory_hessian)
    options->SetStringValue("hessian_approximation", "limited-memory");
  options->SetIntegerValue("max_iter", static_cast<int>(problem.max_iterations));
  options->SetNumericValue("tol", problem.tolerance);
  options->SetNumericValue("constr_viol_tol", 1e-7);
  options->SetNumericValue("acceptable_tol", 100.0 * problem.tolerance);
  options->SetNumericValue("acceptable_constr_viol_tol", 1e-6);
  // Monotone: on the smooth-hill and infeasible-start tests the adaptive
  // strategy took 2 to 4 times the iterations in the second phase.
  options->SetStringValue("mu_strategy", "monotone");
  if (problem.warm_start) {
    // The start is a local optimum's neighbourhood with a profile feasible
    // for this discretisation: a small barrier parameter and push keep
    // Ipopt near it instead of centring far inside (from the default 0.1 a
    // cold phase 1 on battery seed 2 first slowed the path from 12.4 s to
    // 17.9 s before coming back).
    options->SetNumericValue("mu_init", 1e-4);
    for (const char* push : {"bound_push", "bound_frac", "slack_bound_push", "slack_bound_frac"})
      options->SetNumericValue(push, 1e-6);
  }
  // Never set linear_solver=ma97: Debian's Ipopt 3.11 calls exit(1) for it.
  SimultaneousRun run;
  if (app->Initialize() != Ipopt::Solve_Succeeded) {
    run.status = "initialization_failed";
    run.failed = true;
    return run;
  }
  app->OptimizeTNLP(Ipopt::GetRawPtr(nlp));
  const Ipopt::SolverReturn s = nlp->status();
  run.status = ipopt_status_text(s);
  run.converged = s == Ipopt::SUCCESS || s == Ipopt::STOP_AT_ACCEPTABLE_POINT;
  run.failed = !(run.converged || s == Ipopt::MAXITER_EXCEEDED || s == Ipopt::CPUTIME_EXCEEDED ||
                 s == Ipopt::STOP_AT_TINY_STEP);
  if (s == Ipopt::USER_REQUESTED_STOP && nlp->timed_out()) {
    run.status = "time_limit";
    run.failed = false;
  }
  run.iterations = nlp->iterations();
  run.evaluations = nlp->evaluations();
  run.gradient_evaluations = nlp->gradient_evaluations();
  run.variables = nlp->result_variables();
  run.squared_speeds = nlp->result_squared_speeds();
  run.nlp_time = nlp->objective();
  return run;
}

}  // namespace talus::detail
