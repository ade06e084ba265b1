#include "talus/kinematic/hait/chassis_placement.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <sstream>

#include "slice_stencil.hpp"
#include "talus/core/error.hpp"

namespace talus {
namespace {

constexpr double kPi = std::numbers::pi;
/// Secant steps are kept inside (-kAngleCap, kAngleCap): beyond it cos → 0
/// and the wheel positions fold back on the axle centre.
constexpr double kAngleCap = 1.45;

using Set = ChassisPlacementTable::Set;

PlacementStatus elevation(const RuledTerrain& t, const Vec2& p, double& z) {
  if (!t.contains(p)) return PlacementStatus::kOffMap;
  if (!t.has_data(p)) return PlacementStatus::kNoData;
  z = t.elevation(p);
  return PlacementStatus::kConverged;
}

/// The worse of two statuses: an unusable one wins, then kIterationLimit.
PlacementStatus worse(PlacementStatus a, PlacementStatus b) {
  if (!usable(a)) return a;
  if (!usable(b)) return b;
  return a == PlacementStatus::kIterationLimit ? a : b;
}

/// F(φ) of eq. 2 with the wheel elevations it used.
struct AxleEval {
  PlacementStatus status = PlacementStatus::kConverged;
  double f = 0.0, zl = 0.0, zr = 0.0;
};

AxlePlacement place_axle_impl(const RuledTerrain& left, const RuledTerrain& right, double l,
                              double x, double y, double theta, const AxlePlacementOptions& opt) {
  const Vec2 c(x, y);
  const Vec2 g(-std::sin(theta), std::cos(theta));  // left of the heading
  const auto eval = [&](double phi) {
    AxleEval e;
    const Vec2 off = l * std::cos(phi) * g;
    e.status = elevation(left, c + off, e.zl);
    if (!usable(e.status)) return e;
    e.status = elevation(right, c - off, e.zr);
    e.f = 2.0 * l * std::sin(phi) - (e.zl - e.zr);
    return e;
  };
  AxlePlacement out;
  double phi = 0.0;
  AxleEval e = eval(phi);
  out.status = e.status;
  int i = 0;
  while (usable(e.status) && std::abs(e.f) > opt.tolerance) {
    if (i == opt.max_iterations) {
      out.status = PlacementStatus::kIterationLimit;
      break;
    }
    ++i;
    // The slope a plane through both wheels would have (eq. 3): its root.
    const double alpha = std::atan((e.zl - e.zr) / (2.0 * l * std::cos(phi)));
    const AxleEval ea = eval(alpha);
    if (!usable(ea.status)) {
      e = ea;
      break;
    }
    if (std::abs(ea.f) <= opt.tolerance) {  // the secant step would land on α itself
      phi = alpha;
      e = ea;
      break;
    }
    const double denom = ea.f - e.f;
    double next = std::abs(denom) > 1e-15 ? phi - e.f * (alpha - phi) / denom : alpha;
    next = std::clamp(next, -kAngleCap, kAngleCap);
    e = eval(next);
    phi = next;
  }
  if (!usable(e.status)) {
    out.status = e.status;
    return out;
  }
  out.roll = phi;
  out.z = 0.5 * (e.zl + e.zr);
  out.iterations = i;
  return out;
}

/// Place_axle on the terrains a surface set names.
struct DirectSource {
  const RuledTerrain* nominal;
  const RuledTerrain* lower;
  const RuledTerrain* upper;
  double half_width;
  AxlePlacementOptions opt;

  AxlePlacement operator()(Set set, double x, double y, double theta) const {
    const RuledTerrain* l = nominal;
    const RuledTerrain* r = nominal;
    switch (set) {
      case Set::kNominal:
        break;
      case Set::kBothLower:
        l = r = lower;
        break;
      case Set::kBothUpper:
        l = r = upper;
        break;
      case Set::kLeftLowerRightUpper:
        l = lower;
        r = upper;
        break;
      case Set::kLeftUpperRightLower:
        l = upper;
        r = lower;
        break;
    }
    return place_axle_impl(*l, *r, half_width, x, y, theta, opt);
  }
};

struct TableSource {
  const ChassisPlacementTable* table;
  AxlePlacement operator()(Set set, double x, double y, double theta) const {
    return table->axle(set, x, y, theta);
  }
};

template <class Source>
OtherAxlePlacement other_axle(const Source& src, Set set, const ArticulatedChassis& chassis,
                              double xm, double ym, double zm, double theta, int direction,
                              const AxlePlacementOptions& opt) {
  const double d = chassis.axle_spacing;
  const Vec2 m(xm, ym);
  const Vec2 f = direction * Vec2(std::cos(theta), std::sin(theta));
  OtherAxlePlacement out;
  struct Eval {
    AxlePlacement axle;
    Vec2 center;
    double g = 0.0;
  };
  const auto eval = [&](double psi) {
    Eval e;
    e.center = m + d * std::cos(psi) * f;
    e.axle = src(set, e.center.x(), e.center.y(), theta);
    ++out.axle_placements;
    e.g = zm + d * std::sin(psi) - e.axle.z;
    return e;
  };
  double psi = 0.0;
  Eval e = eval(psi);
  PlacementStatus status = e.axle.status;
  int i = 0;
  while (usable(e.axle.status) && std::abs(e.g) > opt.tolerance) {
    if (i == opt.max_iterations) {
      status = PlacementStatus::kIterationLimit;
      break;
    }
    ++i;
    // The pitch that would reach the axle's elevation without the link.
    const double beta = std::atan2(e.axle.z - zm, d * std::cos(psi));
    const Eval eb = eval(beta);
    if (!usable(eb.axle.status)) {
      e = eb;
      break;
    }
    if (std::abs(eb.g) <= opt.tolerance) {
      psi = beta;
      e = eb;
      break;
    }
    const double denom = eb.g - e.g;
    double next = std::abs(denom) > 1e-15 ? psi - e.g * (beta - psi) / denom : beta;
    next = std::clamp(next, -kAngleCap, kAngleCap);
    e = eval(next);
    psi = next;
  }
  out.status = usable(e.axle.status) ? worse(status, e.axle.status) : e.axle.status;
  out.pitch = psi;
  out.axle = e.axle;
  out.center = e.center;
  out.iterations = i;
  return out;
}

template <class Source>
ChassisPlacement chassis_on(const Source& src, Set set, const ArticulatedChassis& chassis, double x,
                            double y, double theta, const AxlePlacementOptions& opt) {
  ChassisPlacement p;
  p.x = x;
  p.y = y;
  p.theta = theta;
  const AxlePlacement mid = src(set, x, y, theta);
  p.axle_placements = 1;
  p.status = mid.status;
  if (!usable(mid.status)) return p;
  p.z = mid.z;
  p.roll_middle = mid.roll;
  const OtherAxlePlacement front = other_axle(src, set, chassis, x, y, mid.z, theta, +1, opt);
  p.axle_placements += front.axle_placements;
  p.status = worse(p.status, front.status);
  if (!usable(p.status)) return p;
  const OtherAxlePlacement rear = other_axle(src, set, chassis, x, y, mid.z, theta, -1, opt);
  p.axle_placements += rear.axle_placements;
  p.status = worse(p.status, rear.status);
  p.roll_front = front.axle.roll;
  p.pitch_front = front.pitch;
  p.roll_rear = rear.axle.roll;
  p.pitch_rear = rear.pitch;
  return p;
}

}  // namespace

ChassisPlacementInterval ChassisPlacementInterval::around(const ChassisPlacement& nominal) {
  const auto point = [](double v) { return Interval{v, v}; };
  ChassisPlacementInterval out;
  out.axle_placements = nominal.axle_placements;
  out.status = nominal.status;
  out.z = point(nominal.z);
  out.roll_middle = point(nominal.roll_middle);
  out.roll_front = point(nominal.roll_front);
  out.roll_rear = point(nominal.roll_rear);
  out.pitch_front = point(nominal.pitch_front);
  out.pitch_rear = point(nominal.pitch_rear);
  return out;
}

namespace {

template <class Source>
ChassisPlacementInterval chassis_interval(const Source& src, const ArticulatedChassis& chassis,
                                          double x, double y, double theta,
                                          const AxlePlacementOptions& opt) {
  const ChassisPlacement nom = chassis_on(src, Set::kNominal, chassis, x, y, theta, opt);
  ChassisPlacementInterval out = ChassisPlacementInterval::around(nom);
  if (!usable(nom.status)) return out;

  // Middle axle: z from both wheels on T_min / T_max, φ from crossed wheels.
  const auto axle_at = [&](Set set, const Vec2& c) {
    const AxlePlacement a = src(set, c.x(), c.y(), theta);
    ++out.axle_placements;
    out.status = worse(out.status, a.status);
    return a;
  };
  const Vec2 m(x, y);
  const AxlePlacement zlo = axle_at(Set::kBothLower, m);
  const AxlePlacement zhi = axle_at(Set::kBothUpper, m);
  const AxlePlacement rlo = axle_at(Set::kLeftLowerRightUpper, m);
  const AxlePlacement rhi = axle_at(Set::kLeftUpperRightLower, m);
  if (!usable(out.status)) return out;
  out.z.include(zlo.z);
  out.z.include(zhi.z);
  out.roll_middle.include(rlo.roll);
  out.roll_middle.include(rhi.roll);

  for (int direction : {+1, -1}) {
    Interval& pitch = direction > 0 ? out.pitch_front : out.pitch_rear;
    Interval& roll = direction > 0 ? out.roll_front : out.roll_rear;
    // Lowest ψ: middle axle at its highest, this axle on T_min (and conversely).
    const OtherAxlePlacement lo =
        other_axle(src, Set::kBothLower, chassis, x, y, out.z.hi, theta, direction, opt);
    const OtherAxlePlacement hi =
        other_axle(src, Set::kBothUpper, chassis, x, y, out.z.lo, theta, direction, opt);
    out.axle_placements += lo.axle_placements + hi.axle_placements;
    out.status = worse(out.status, worse(lo.status, hi.status));
    if (!usable(out.status)) return out;
    pitch.include(lo.pitch);
    pitch.include(hi.pitch);
    const Vec2 f = direction * Vec2(std::cos(theta), std::sin(theta));
    const double d = chassis.axle_spacing;
    for (double psi : {lo.pitch, hi.pitch, direction > 0 ? nom.pitch_front : nom.pitch_rear}) {
      const Vec2 c = m + d * std::cos(psi) * f;
      const AxlePlacement a = axle_at(Set::kLeftLowerRightUpper, c);
      const AxlePlacement b = axle_at(Set::kLeftUpperRightLower, c);
      if (!usable(out.status)) return out;
      roll.include(a.roll);
      roll.include(b.roll);
    }
  }
  return out;
}

void require_chassis(const ArticulatedChassis& chassis) {
  chassis.validate();
}

void require_finite_configuration(double x, double y, double theta, const char* who) {
  if (!(std::isfinite(x) && std::isfinite(y) && std::isfinite(theta))) {
    std::ostringstream msg;
    msg << who << ": configuration (" << x << ", " << y << ", " << theta << ") must be finite";
    throw InputError(msg.str());
  }
}

}  // namespace

void AxlePlacementOptions::validate() const {
  if (!(tolerance > 0 && std::isfinite(tolerance))) {
    std::ostringstream msg;
    msg << "AxlePlacementOptions.tolerance must be positive and finite, got " << tolerance;
    throw InputError(msg.str());
  }
  if (max_iterations <= 0)
    throw InputError("AxlePlacementOptions.max_iterations must be > 0, got " +
                     std::to_string(max_iterations));
}

void ChassisTableOptions::validate() const {
  if (theta_slices < 4)
    throw InputError("ChassisTableOptions.theta_slices must be >= 4, got " +
                     std::to_string(theta_slices));
  if (!(terrain_uncertainty >= 0 && std::isfinite(terrain_uncertainty))) {
    std::ostringstream msg;
    msg << "ChassisTableOptions.terrain_uncertainty must be finite and >= 0, got "
        << terrain_uncertainty;
    throw InputError(msg.str());
  }
  if (terrain_uncertainty_map && terrain_uncertainty > 0.0) {
    throw InputError(
        "ChassisTableOptions: terrain_uncertainty and terrain_uncertainty_map are both set; "
        "set one");
  }
  axle.validate();
}

double ChassisPlacement::body_angle() const {
  return kPi + pitch_front + pitch_rear;
}

AxlePlacement place_axle(const RuledTerrain& left, const RuledTerrain& right,
                         double half_axle_width, double x, double y, double theta,
                         const AxlePlacementOptions& options) {
  require_finite_configuration(x, y, theta, "place_axle");
  if (!(half_axle_width > 0 && std::isfinite(half_axle_width))) {
    std::ostringstream msg;
    msg << "place_axle: half_axle_width must be positive and finite, got " << half_axle_width;
    throw InputError(msg.str());
  }
  options.validate();
  return place_axle_impl(left, right, half_axle_width, x, y, theta, options);
}

AxlePlacement place_axle(const RuledTerrain& terrain, double half_axle_width, double x, double y,
                         double theta, const AxlePlacementOptions& options) {
  return place_axle(terrain, terrain, half_axle_width, x, y, theta, options);
}

OtherAxlePlacement place_other_axle(const RuledTerrain& terrain, const ArticulatedChassis& chassis,
                                    double x_m, double y_m, double z_m, double theta, int direction,
                                    const AxlePlacementOptions& options) {
  require_finite_configuration(x_m, y_m, theta, "place_other_axle");
  options.validate();
  if (direction != 1 && direction != -1)
    throw InputError("place_other_axle: direction must be +1 (front) or -1 (rear), got " +
                     std::to_string(direction));
  const DirectSource src{&terrain, &terrain, &terrain, chassis.half_axle_width, options};
  return other_axle(src, Set::kNominal, chassis, x_m, y_m, z_m, theta, direction, options);
}

OtherAxlePlacement place_other_axle(const AxlePlacer& axle, const ArticulatedChassis& chassis,
                                    double x_m, double y_m, double z_m, double theta, int direction,
                                    const AxlePlacementOptions& options) {
  require_finite_configuration(x_m, y_m, theta, "place_other_axle");
  options.validate();
  if (!axle) throw InputError("place_other_axle: no axle placement function");
  if (direction != 1 && direction != -1)
    throw InputError("place_other_axle: direction must be +1 (front) or -1 (rear), got " +
                     std::to_string(direction));
  const auto src = [&axle](Set, double x, double y, double th) { return axle(x, y, th); };
  return other_axle(src, Set::kNominal, chassis, x_m, y_m, z_m, theta, direction, options);
}

ChassisPlacement place_chassis(const ArticulatedChassis& chassis, const RuledTerrain& terrain,
                               double x, double y, double theta,
                               const AxlePlacementOptions& options) {
  require_finite_configuration(x, y, theta, "place_chassis");
  options.validate();
  const DirectSource src{&terrain, &terrain, &terrain, chassis.half_axle_width, options};
  return chassis_on(src, Set::kNominal, chassis, x, y, theta, options);
}

std::vector<Vec2> swept_body_outline(double length, double half_width, double rho, double dtheta) {
  if (!(length > 0 && std::isfinite(length)) || !(half_width > 0 && std::isfinite(half_width)) ||
      !(rho >= 0 && std::isfinite(rho)) || !(dtheta >= 0 && dtheta < 0.5 * kPi)) {
    std::ostringstream msg;
    msg << "swept_body_outline: need length > 0, half_width > 0, rho >= 0, dtheta in [0, pi/2); "
           "got "
        << length << ", " << half_width << ", " << rho << ", " << dtheta;
    throw InputError(msg.str());
  }
  const double L = length, w = half_width;
  if (dtheta == 0.0) return {{0, -w - rho}, {L, -w - rho}, {L, w + rho}, {0, w + rho}};
  const double sd = std::sin(dtheta), cd = std::cos(dtheta);
  // The far corners (L, ±w) turned by ±Δθ reach polar angles up to ±β at radius r.
  const double r = std::hypot(L, w);
  const double beta = std::atan2(L * sd + w * cd, L * cd - w * sd);
  constexpr int kSegments = 5;  // odd: no vertex on the axis, so ±ρ shifts every vertex
  const double step = 2.0 * beta / kSegments;
  const double outer = r / std::cos(0.5 * step);  // vertices of the tangent segments
  const auto shifted = [rho](Vec2 v) {
    v.y() += v.y() > 0 ? rho : -rho;
    return v;
  };
  std::vector<Vec2> out{shifted({-w * sd, -w * cd})};  // near edge, right end
  for (int i = 0; i <= kSegments; ++i) {
    const double a = -beta + step * i;
    out.push_back(shifted({outer * std::cos(a), outer * std::sin(a)}));
  }
  out.push_back(shifted({-w * sd, w * cd}));  // near edge, left end
  return out;
}

ChassisPlacementInterval place_chassis_interval(const ArticulatedChassis& chassis,
                                                const RuledTerrain& terrain,
                                                const RuledTerrain& lower,
                                                const RuledTerrain& upper, double x, double y,
                                                double theta, const AxlePlacementOptions& options) {
  require_finite_configuration(x, y, theta, "place_chassis_interval");
  options.validate();
  const DirectSource src{&terrain, &lower, &upper, chassis.half_axle_width, options};
  return chassis_interval(src, chassis, x, y, theta, options);
}

ChassisPlacementTable::ChassisPlacementTable(const ArticulatedChassis& chassis,
                                             const RuledTerrain& terrain,
                                             const ChassisTableOptions& options)
    : chassis_(chassis), axle_options_(options.axle), terrain_(terrain) {
  require_chassis(chassis);
  options.validate();
  const auto start = std::chrono::steady_clock::now();
  slices_ = options.theta_slices;
  const ElevationGrid* dz_map = options.terrain_uncertainty_map.get();
  const bool uncertain = options.terrain_uncertainty > 0.0 || dz_map != nullptr;
  const RuledTerrain lower = dz_map      ? terrain.lower_envelope(*dz_map)
                             : uncertain ? terrain.lower_envelope(options.terrain_uncertainty)
                                         : terrain;
  const RuledTerrain upper = dz_map      ? terrain.upper_envelope(*dz_map)
                             : uncertain ? terrain.upper_envelope(options.terrain_uncertainty)
                                         : terrain;
  const DirectSource src{&terrain, &lower, &upper, chassis.half_axle_width, options.axle};
  const ElevationGrid& grid = terrain.grid();
  const std::size_t nodes = grid.ncols() * grid.nrows();
  const int nsets = uncertain ? 5 : 1;
  sets_.resize(nsets);
  for (int s = 0; s < nsets; ++s) {
    Surfaces& surf = sets_[s];
    surf.z.assign(nodes * slices_, 0.0);
    surf.roll.assign(nodes * slices_, 0.0);
    surf.status.assign(nodes * slices_, static_cast<std::uint8_t>(PlacementStatus::kOffMap));
    for (int k = 0; k < slices_; ++k) {
      const double theta = slice_angle(k);
      for (std::size_t j = 0; j < grid.nrows(); ++j)
        for (std::size_t i = 0; i < grid.ncols(); ++i) {
          const Vec2 p = grid.node_position(i, j);
          const AxlePlacement a = src(static_cast<Set>(s), p.x(), p.y(), theta);
          const std::size_t idx = (k * grid.nrows() + j) * grid.ncols() + i;
          surf.status[idx] = static_cast<std::uint8_t>(a.status);
          if (usable(a.status)) {
            surf.z[idx] = a.z;
            surf.roll[idx] = a.roll;
          }
          ++diagnostics_.placements;
        }
    }
  }
  diagnostics_.slices = slices_;
  diagnostics_.surface_sets = nsets;
  diagnostics_.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double ChassisPlacementTable::slice_angle(int k) const {
  return 2.0 * kPi * k / slices_;
}

AxlePlacement ChassisPlacementTable::axle(double x, double y, double theta) const {
  return axle(Set::kNominal, x, y, theta);
}

AxlePlacement ChassisPlacementTable::axle(Set set, double x, double y, double theta) const {
  AxlePlacement out;
  const Vec2 p(x, y);
  if (!terrain_.contains(p) || !std::isfinite(theta)) return out;  // kOffMap
  const auto si = static_cast<std::size_t>(set);
  if (si >= sets_.size())
    throw InputError("ChassisPlacementTable: surface set " + std::to_string(si) +
                     " needs a table built with terrain_uncertainty > 0");
  const Surfaces& surf = sets_[si];
  const detail::SliceStencil st = detail::slice_stencil(terrain_, slices_, p, theta);
  out.status = PlacementStatus::kConverged;
  double z[2] = {0, 0}, r[2] = {0, 0};
  for (int q = 0; q < st.slices; ++q) {
    for (const std::size_t i : st.index[q])
      out.status = worse(out.status, static_cast<PlacementStatus>(surf.status[i]));
    z[q] = st.blend(surf.z, q);
    r[q] = st.blend(surf.roll, q);
  }
  if (!usable(out.status)) return out;
  out.z = st.in_theta(z);
  out.roll = st.in_theta(r);
  return out;
}

ChassisPlacementTable::NodeValues ChassisPlacementTable::nodes(Set set, int k) const {
  const auto si = static_cast<std::size_t>(set);
  if (si >= sets_.size())
    throw InputError("ChassisPlacementTable::nodes: surface set " + std::to_string(si) +
                     " needs a table built with terrain_uncertainty > 0");
  if (k < 0 || k >= slices_)
    throw InputError("ChassisPlacementTable::nodes: slice " + std::to_string(k) + " outside [0, " +
                     std::to_string(slices_) + ")");
  const Surfaces& s = sets_[si];
  const std::size_t n = terrain_.grid().ncols() * terrain_.grid().nrows();
  const std::size_t off = static_cast<std::size_t>(k) * n;
  return {std::span<const double>(s.z).subspan(off, n),
          std::span<const double>(s.roll).subspan(off, n),
          std::span<const std::uint8_t>(s.status).subspan(off, n)};
}

ChassisPlacement ChassisPlacementTable::place(double x, double y, double theta) const {
  return chassis_on(TableSource{this}, Set::kNominal, chassis_, x, y, theta, axle_options_);
}

ChassisPlacementInterval ChassisPlacementTable::place_interval(double x, double y,
                                                               double theta) const {
  if (!has_uncertainty())
    throw InputError(
        "ChassisPlacementTable::place_interval needs a table built with terrain_uncertainty > 0");
  return chassis_interval(TableSource{this}, chassis_, x, y, theta, axle_options_);
}

}  // namespace talus
