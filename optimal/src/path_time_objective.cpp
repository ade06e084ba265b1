#include "talus/optimal/path_time_objective.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string_view>

#include "profile_sensitivity.hpp"
#include "station_derivatives.hpp"
#include "steering_rows.hpp"
#include "talus/bspline/surface_path.hpp"
#include "talus/core/error.hpp"

namespace talus {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// Marks `profile` infeasible at `station` for `why` (its buffers kept for the next solve) and
/// returns the objective's value there: so that a rejected path says where and why.
double infeasible(TimeOptimalProfile& profile, std::size_t station, std::string_view why) {
  profile.status = ProfileStatus::kInfeasible;
  profile.infeasible_station = station;
  profile.infeasible_binding = Constraint::kNone;
  profile.message.assign(why);
  return kInfinity;
}

KnotVector uniform_clamped_knots(std::size_t control_points) {
  std::vector<double> breaks;
  const std::size_t spans = control_points - 3;
  for (std::size_t k = 0; k <= spans; ++k) breaks.push_back(static_cast<double>(k) / spans);
  return KnotVector::clamped(3, breaks);
}

}  // namespace

PathTimeObjective::PathTimeObjective(const BPatch& terrain, const Vehicle& vehicle,
                                     const Vec2& start, const Vec2& goal,
                                     std::size_t control_points, std::size_t stations,
                                     const ProfileOptions& speeds)
    : terrain_(terrain),
      vehicle_(vehicle),
      start_(start),
      goal_(goal),
      control_points_(control_points),
      speeds_(speeds),
      knots_(uniform_clamped_knots(std::max<std::size_t>(control_points, 4))),
      max_curvature_(vehicle.max_curvature()),
      limits_(vehicle) {
  if (control_points < 4) throw InputError("a path needs at least 4 control points");
  if (stations < 2) throw InputError("a path needs at least 2 stations");
  speeds.validate();
  sigma_.resize(stations);
  first_basis_.resize(stations);
  basis_.resize(stations);
  Eigen::MatrixXd values(3, 4);
  for (std::size_t k = 0; k < stations; ++k) {
    sigma_[k] = (k + 1 == stations) ? 1.0 : static_cast<double>(k) / (stations - 1);
    const std::size_t span = knots_.find_span(sigma_[k]);
    knots_.basis_derivatives(span, sigma_[k], values);
    first_basis_[k] = span - 3;
    basis_[k] = values;
  }
  steering_ = std::make_shared<const detail::SteeringRows>(knots_);
  for (const detail::SteeringRows::Entry& e : steering_->pattern())
    pattern_.emplace_back(static_cast<long>(e.row), 2 * static_cast<long>(e.point) - 2 + e.axis);
  control_.resize(control_points);
  control_.front() = start;
  control_.back() = goal;
}

Eigen::VectorXd PathTimeObjective::variables(const std::vector<Vec2>& control_points) const {
  if (control_points.size() != control_points_)
    throw InputError("wrong number of control points for this objective");
  Eigen::VectorXd z(static_cast<long>(dimension()));
  for (std::size_t i = 1; i + 1 < control_points_; ++i) {
    z[2 * static_cast<long>(i) - 2] = control_points[i].x();
    z[2 * static_cast<long>(i) - 1] = control_points[i].y();
  }
  return z;
}

std::vector<Vec2> PathTimeObjective::control_points(const Eigen::VectorXd& z) const {
  std::vector<Vec2> out(control_points_);
  out.front() = start_;
  out.back() = goal_;
  for (std::size_t i = 1; i + 1 < control_points_; ++i)
    out[i] = Vec2(z[2 * static_cast<long>(i) - 2], z[2 * static_cast<long>(i) - 1]);
  return out;
}

Curve2 PathTimeObjective::curve(const Eigen::VectorXd& z) const {
  return Curve2(knots_, control_points(z));
}

std::size_t PathTimeObjective::curvature_samples() const {
  return steering_->size();
}

bool PathTimeObjective::curvatures(const Eigen::VectorXd& z, double* values,
                                   double* jacobian) const {
  if (z.size() != static_cast<long>(dimension()) || !z.allFinite()) return false;
  return steering_->evaluate(control_points(z), values, jacobian);
}

double PathTimeObjective::travel_time(const Eigen::VectorXd& z) {
  ++evaluations_;
  if (!z.allFinite()) return kInfinity;
  for (std::size_t i = 1; i + 1 < control_points_; ++i)
    control_[i] = Vec2(z[2 * static_cast<long>(i) - 2], z[2 * static_cast<long>(i) - 1]);
  const std::size_t n = sigma_.size();
  frames_.resize(n);
  planar_.resize(n);
  const double h = 1.0 / static_cast<double>(n - 1);  // station spacing in σ
  for (std::size_t k = 0; k < n; ++k) {
    Eigen::Matrix<double, 2, 3> p = Eigen::Matrix<double, 2, 3>::Zero();
    for (int b = 0; b < 4; ++b) {
      const Vec2& c = control_[first_basis_[k] + static_cast<std::size_t>(b)];
      for (int d = 0; d < 3; ++d) p.col(d) += basis_[k](d, b) * c;
    }
    planar_[k] = p;
    const Vec2 position = p.col(0);
    if (!terrain_.contains(position) || !terrain_.on_data(position))
      return infeasible(profile_, k, "it leaves the map's measured data");
    if (!(p.col(1).norm() > 0.0))  // a cusp: no frame
      return infeasible(profile_, k, "it has a cusp (its tangent vanishes)");
    PathFrame& f = frames_[k];
    f = lift_to_surface(position, terrain_.evaluate(position), p.col(1), p.col(2));
    f.parameter = sigma_[k];
    if (k == 0) {
      f.s = 0.0;
    } else {
      const PathFrame& prev = frames_[k - 1];
      f.s = prev.s + 0.5 * h * (prev.speed + f.speed) +
            h * h / 12.0 * (prev.speed_rate - f.speed_rate);
      if (!(f.s > prev.s))
        return infeasible(profile_, k, "its parametrisation is degenerate (no arc length)");
    }
  }
  const std::size_t beyond = std::isfinite(max_curvature_)
                                 ? steering_->first_beyond(control_, max_curvature_)
                                 : curvature_samples();
  if (beyond < curvature_samples()) {
    const double sigma = steering_->parameter(beyond);
    profile_ = TimeOptimalProfile{};
    profile_.status = ProfileStatus::kInfeasible;
    profile_.infeasible_binding = Constraint::kSteering;
    profile_.infeasible_station = static_cast<std::size_t>(std::lround(sigma * (n - 1)));
    profile_.message = "turns tighter than the steering limit between the stations";
    return kInfinity;
  }
  limits_.compute(frames_, terrain_);
  try {
    solver_.solve(limits_, speeds_, profile_);
  } catch (const InputError& e) {  // start or end speed above this path's limit there
    return infeasible(profile_, 0, e.what());
  }
  return profile_.status == ProfileStatus::kOk ? profile_.travel_time : kInfinity;
}

double PathTimeObjective::evaluate(const Eigen::VectorXd& z, Eigen::VectorXd* gradient) {
  if (z.size() != static_cast<long>(dimension()))
    throw InputError("PathTimeObjective: wrong number of variables");
  // Solvers ask for the value and then the gradient at the same point: the
  // workspace still holds that point's profile.
  const bool same_point = last_valid_ && z == last_z_;
  const double time = same_point ? last_time_ : travel_time(z);
  last_z_ = z;
  last_time_ = time;
  last_valid_ = true;
  if (gradient == nullptr || !std::isfinite(time)) return time;
  ++gradient_evaluations_;
  gradient->setZero(static_cast<long>(dimension()));
  if (!adjoint_gradient(*gradient)) {
    ++fallbacks_;
    finite_difference_gradient(z, *gradient);
    travel_time(z);  // restore the workspace to z
  }
  return time;
}

bool PathTimeObjective::adjoint_gradient(Eigen::VectorXd& gradient) {
  const std::size_t n = sigma_.size();
  if (profile_.merged_stations > 0) return false;
  geometry_.resize(n);
  arc_.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    geometry_[k] = limits_.geometry(k);
    arc_[k] = frames_[k].s;
  }
  detail::TravelTimeSensitivity sensitivity;
  if (!detail::travel_time_sensitivity(vehicle_, geometry_, arc_, profile_.v, sensitivity))
    return false;
  const double h = 1.0 / static_cast<double>(n - 1);
  for (std::size_t k = 0; k < n; ++k) {
    // dT/d(κ_n, κ_g, k_t, k_q, k_r, speed, speed_rate, κ_w) at station k; the
    // speed terms through the Hermite step lengths on either side.
    Eigen::Matrix<double, 1, detail::StationDerivatives::kRows> outer;
    for (int i = 0; i < 5; ++i) outer[i] = sensitivity.geometry[k][static_cast<std::size_t>(i)];
    const double before = k > 0 ? sensitivity.step_length[k - 1] : 0.0;
    const double after = k + 1 < n ? sensitivity.step_length[k] : 0.0;
    outer[5] = 0.5 * h * (before + after);
    outer[6] = h * h / 12.0 * (after - before);
    outer[7] = sensitivity.geometry[k][5];
    const Eigen::Matrix<double, 1, 6> local =
        outer * detail::station_derivatives(terrain_, planar_[k], limits_.wheels()).jacobian;
    for (int b = 0; b < 4; ++b) {
      const std::size_t i = first_basis_[k] + static_cast<std::size_t>(b);
      if (i == 0 || i + 1 == control_points_) continue;  // start and goal are fixed
      for (int axis = 0; axis < 2; ++axis) {
        gradient[2 * static_cast<long>(i) - 2 + axis] += basis_[k](0, b) * local[axis] +
                                                         basis_[k](1, b) * local[2 + axis] +
                                                         basis_[k](2, b) * local[4 + axis];
      }
    }
  }
  return gradient.allFinite();
}

void PathTimeObjective::finite_difference_gradient(const Eigen::VectorXd& z,
                                                   Eigen::VectorXd& gradient) {
  Eigen::VectorXd probe = z;
  const double center = travel_time(z);
  for (long i = 0; i < z.size(); ++i) {
    // Absolute, tied to the terrain: map coordinates can be 1e6 m (UTM).
    const double step = 1e-5 * terrain_.cellsize();
    probe[i] = z[i] + step;
    const double plus = travel_time(probe);
    probe[i] = z[i] - step;
    const double minus = travel_time(probe);
    probe[i] = z[i];
    // One-sided where the other side is infeasible.
    if (std::isfinite(plus) && std::isfinite(minus)) {
      gradient[i] = (plus - minus) / (2.0 * step);
    } else if (std::isfinite(plus)) {
      gradient[i] = (plus - center) / step;
    } else if (std::isfinite(minus)) {
      gradient[i] = (center - minus) / step;
    } else {
      gradient[i] = 0.0;
    }
  }
}

}  // namespace talus
