#include "talus/kinematic/hait/chassis_uncertainty_table.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "slice_stencil.hpp"
#include "talus/core/error.hpp"
#include "talus/kinematic/hait/chassis_placement.hpp"

namespace talus {
namespace {

constexpr double kPi = std::numbers::pi;
using Set = ChassisPlacementTable::Set;

/// The worse of two statuses: an unusable one wins, then kIterationLimit.
PlacementStatus worse(PlacementStatus a, PlacementStatus b) {
  if (!usable(a)) return a;
  if (!usable(b)) return b;
  return a == PlacementStatus::kIterationLimit ? a : b;
}

/// Lattice offsets (di, dj) of the nodes a window around a node must scan for
/// slice angle `theta`: the box of half extents (hx along the heading, hy
/// across) whose Minkowski sum with the square [−g, g]² holds the offset
/// (separating-axis test on the four axes of the box and the square).
std::vector<std::pair<int, int>> window_offsets(double theta, double hx, double hy, double g,
                                                double h) {
  const double c = std::cos(theta), s = std::sin(theta);
  const double ac = std::abs(c), as = std::abs(s);
  const double eps = 1e-9 * (1.0 + hx + hy + g);
  const double ext_x = g + hx * ac + hy * as;  // box ⊕ square projected on world x
  const double ext_y = g + hx * as + hy * ac;
  const double sq = g * (ac + as);  // square projected on the box axes
  const int ni = static_cast<int>(std::ceil(ext_x / h + 1e-9));
  const int nj = static_cast<int>(std::ceil(ext_y / h + 1e-9));
  std::vector<std::pair<int, int>> out;
  for (int dj = -nj; dj <= nj; ++dj) {
    for (int di = -ni; di <= ni; ++di) {
      const double ox = di * h, oy = dj * h;
      if (std::abs(ox) > ext_x + eps || std::abs(oy) > ext_y + eps) continue;
      if (std::abs(ox * c + oy * s) > hx + sq + eps) continue;
      if (std::abs(-ox * s + oy * c) > hy + sq + eps) continue;
      out.emplace_back(di, dj);
    }
  }
  return out;
}

/// The CCW-from-above order: reverse if the xy-projected signed area is negative.
Quad counter_clockwise(Quad q) {
  double area = 0.0;
  for (int k = 0; k < 4; ++k) {
    area += q[k].x() * q[(k + 1) % 4].y() - q[(k + 1) % 4].x() * q[k].y();
  }
  if (area < 0.0) std::reverse(q.begin(), q.end());
  return q;
}

/// The chassis, after checking the uncertainty options: the base table is
/// built in the member initialiser, so bad options must stop it first.
const ArticulatedChassis& checked(const ArticulatedChassis& chassis,
                                  const ChassisUncertaintyOptions& uncertainty) {
  uncertainty.validate();
  return chassis;
}

}  // namespace

void ChassisUncertaintyOptions::validate() const {
  if (!(position_uncertainty >= 0.0 && std::isfinite(position_uncertainty))) {
    std::ostringstream msg;
    msg << "ChassisUncertaintyOptions.position_uncertainty must be finite and >= 0 [m], got "
        << position_uncertainty;
    throw InputError(msg.str());
  }
  if (!(heading_uncertainty >= 0.0 && heading_uncertainty < 0.5 * kPi)) {
    std::ostringstream msg;
    msg << "ChassisUncertaintyOptions.heading_uncertainty must be in [0, pi/2) [rad], got "
        << heading_uncertainty;
    throw InputError(msg.str());
  }
}

ChassisUncertaintyTable::ChassisUncertaintyTable(const ArticulatedChassis& chassis,
                                                 const RuledTerrain& terrain,
                                                 const ChassisTableOptions& table,
                                                 const ChassisUncertaintyOptions& uncertainty)
    : base_(checked(chassis, uncertainty), terrain, table), options_(uncertainty) {
  const auto start = std::chrono::steady_clock::now();
  const double rho = uncertainty.position_uncertainty;
  const double dth = uncertainty.heading_uncertainty;
  const double d = chassis.axle_spacing;
  const int n_slices = base_.slices();
  const double slice = 2.0 * kPi / n_slices;
  const ElevationGrid& grid = base_.terrain().grid();
  const double h = grid.cellsize();
  const auto nc = static_cast<int>(grid.ncols()), nr = static_cast<int>(grid.nrows());
  const std::size_t nodes = grid.ncols() * grid.nrows();

  // N' (Fig. 26): the union of the three axles' neighbourhoods.
  const double hx0 = d * (1.0 - std::cos(dth));
  const double hy0 = rho + d * std::sin(dth);
  // A heading up to one slice from the slice angle reads this slice: the
  // query's box, rotated by up to one slice, fits in this bounding box.
  const double hx = hx0 * std::cos(slice) + hy0 * std::sin(slice);
  const double hy = hy0 * std::cos(slice) + hx0 * std::sin(slice);
  const double g = uncertainty.lattice_slack ? 2.0 * h : 0.0;
  const int reach = (dth > 0.0 ? 1 : 0) + static_cast<int>(std::ceil(dth / slice - 1e-12));
  const int span = std::min(2 * reach + 1, n_slices);

  const bool terrain_uncertain = base_.has_uncertainty();
  const Set lo_z = terrain_uncertain ? Set::kBothLower : Set::kNominal;
  const Set hi_z = terrain_uncertain ? Set::kBothUpper : Set::kNominal;
  const Set lo_r = terrain_uncertain ? Set::kLeftLowerRightUpper : Set::kNominal;
  const Set hi_r = terrain_uncertain ? Set::kLeftUpperRightLower : Set::kNominal;

  // Pass 1, over θ: each slice takes the extremes of the slices within `reach`.
  std::vector<double> tz_lo(nodes * n_slices), tz_hi(nodes * n_slices), tr_lo(nodes * n_slices),
      tr_hi(nodes * n_slices);
  std::vector<std::uint8_t> tstatus(nodes * n_slices);
  for (int k = 0; k < n_slices; ++k) {
    const std::size_t off = static_cast<std::size_t>(k) * nodes;
    for (std::size_t n = 0; n < nodes; ++n) {
      tz_lo[off + n] = tr_lo[off + n] = std::numeric_limits<double>::infinity();
      tz_hi[off + n] = tr_hi[off + n] = -std::numeric_limits<double>::infinity();
      tstatus[off + n] = static_cast<std::uint8_t>(PlacementStatus::kConverged);
    }
    for (int q = 0; q < span; ++q) {
      const int kk = ((k - reach + q) % n_slices + n_slices) % n_slices;
      const auto a = base_.nodes(lo_z, kk), b = base_.nodes(hi_z, kk);
      const auto r0 = base_.nodes(lo_r, kk), r1 = base_.nodes(hi_r, kk);
      for (std::size_t n = 0; n < nodes; ++n) {
        PlacementStatus st = static_cast<PlacementStatus>(tstatus[off + n]);
        for (const auto* s : {&a, &b, &r0, &r1}) {
          st = worse(st, static_cast<PlacementStatus>(s->status[n]));
        }
        tstatus[off + n] = static_cast<std::uint8_t>(st);
        if (!usable(st)) continue;
        tz_lo[off + n] = std::min(tz_lo[off + n], a.z[n]);
        tz_hi[off + n] = std::max(tz_hi[off + n], b.z[n]);
        tr_lo[off + n] = std::min(tr_lo[off + n], r0.roll[n]);
        tr_hi[off + n] = std::max(tr_hi[off + n], r1.roll[n]);
      }
    }
  }

  // Pass 2, over (x, y): the window of N' (grown by the lattice slack) at each node.
  z_lo_.assign(nodes * n_slices, 0.0);
  z_hi_.assign(nodes * n_slices, 0.0);
  roll_lo_.assign(nodes * n_slices, 0.0);
  roll_hi_.assign(nodes * n_slices, 0.0);
  status_.assign(nodes * n_slices, static_cast<std::uint8_t>(PlacementStatus::kOffMap));
  int max_window = 0;
  for (int k = 0; k < n_slices; ++k) {
    const auto window = window_offsets(base_.slice_angle(k), hx, hy, g, h);
    max_window = std::max(max_window, static_cast<int>(window.size()));
    const std::size_t off = static_cast<std::size_t>(k) * nodes;
    for (int j = 0; j < nr; ++j) {
      for (int i = 0; i < nc; ++i) {
        const std::size_t n = off + static_cast<std::size_t>(j) * nc + i;
        PlacementStatus st = PlacementStatus::kConverged;
        double zl = std::numeric_limits<double>::infinity(), zh = -zl, rl = zl, rh = -zl;
        for (const auto& [di, dj] : window) {
          const int ii = i + di, jj = j + dj;
          if (ii < 0 || jj < 0 || ii >= nc || jj >= nr) {
            st = PlacementStatus::kOffMap;  // part of the domain leaves the map
            break;
          }
          const std::size_t m = off + static_cast<std::size_t>(jj) * nc + ii;
          st = worse(st, static_cast<PlacementStatus>(tstatus[m]));
          if (!usable(st)) break;
          zl = std::min(zl, tz_lo[m]);
          zh = std::max(zh, tz_hi[m]);
          rl = std::min(rl, tr_lo[m]);
          rh = std::max(rh, tr_hi[m]);
        }
        status_[n] = static_cast<std::uint8_t>(st);
        if (!usable(st)) continue;
        z_lo_[n] = zl;
        z_hi_[n] = zh;
        roll_lo_[n] = rl;
        roll_hi_[n] = rh;
      }
    }
  }

  diagnostics_.base_seconds = base_.diagnostics().seconds;
  diagnostics_.minmax_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  diagnostics_.seconds = diagnostics_.base_seconds + diagnostics_.minmax_seconds;
  diagnostics_.placements = base_.diagnostics().placements;
  diagnostics_.half_length = hx0;
  diagnostics_.half_width = hy0;
  diagnostics_.slice_reach = reach;
  diagnostics_.max_window_nodes = max_window;
}

AxleBounds ChassisUncertaintyTable::axle_bounds(double x, double y, double theta) const {
  AxleBounds out;
  const RuledTerrain& terrain = base_.terrain();
  const Vec2 p(x, y);
  if (!terrain.contains(p) || !std::isfinite(theta)) return out;  // kOffMap
  const detail::SliceStencil st = detail::slice_stencil(terrain, base_.slices(), p, theta);
  double v[4][2] = {};  // [z_lo, z_hi, roll_lo, roll_hi][slice]
  out.status = PlacementStatus::kConverged;
  for (int q = 0; q < st.slices; ++q) {
    for (const std::size_t i : st.index[q])
      out.status = worse(out.status, static_cast<PlacementStatus>(status_[i]));
    v[0][q] = st.blend(z_lo_, q);
    v[1][q] = st.blend(z_hi_, q);
    v[2][q] = st.blend(roll_lo_, q);
    v[3][q] = st.blend(roll_hi_, q);
  }
  if (!usable(out.status)) return out;
  double r[4];
  for (int m = 0; m < 4; ++m) r[m] = st.in_theta(v[m]);
  out.z = {r[0], r[1]};
  out.roll = {r[2], r[3]};
  return out;
}

ChassisPlacementInterval ChassisUncertaintyTable::place_interval(double x, double y,
                                                                 double theta) const {
  const ArticulatedChassis& ch = base_.chassis();
  const AxlePlacementOptions& opt = base_.axle_options();
  const ChassisPlacement nom = base_.place(x, y, theta);
  ChassisPlacementInterval out = ChassisPlacementInterval::around(nom);
  if (!usable(nom.status)) return out;

  const AxleBounds mid = axle_bounds(x, y, theta);
  ++out.axle_placements;
  out.status = worse(out.status, mid.status);
  if (!usable(out.status)) return out;
  out.z.include(mid.z.lo);
  out.z.include(mid.z.hi);
  out.roll_middle.include(mid.roll.lo);
  out.roll_middle.include(mid.roll.hi);

  // Place_other_axle "applied to these surfaces" (§5.1.1): the lowest pitch
  // with the middle axle at its highest and the outer axle on S'_z_min, the
  // highest pitch conversely.
  int lookups = 0;
  const auto on_lower = [this, &lookups](double px, double py, double th) {
    const AxleBounds bd = axle_bounds(px, py, th);
    ++lookups;
    return AxlePlacement{bd.status, bd.roll.lo, bd.z.lo, 0};
  };
  const auto on_upper = [this, &lookups](double px, double py, double th) {
    const AxleBounds bd = axle_bounds(px, py, th);
    ++lookups;
    return AxlePlacement{bd.status, bd.roll.hi, bd.z.hi, 0};
  };
  const Vec2 m(x, y);
  const Vec2 f(std::cos(theta), std::sin(theta));
  for (int direction : {+1, -1}) {
    Interval& pitch = direction > 0 ? out.pitch_front : out.pitch_rear;
    Interval& roll = direction > 0 ? out.roll_front : out.roll_rear;
    const OtherAxlePlacement lo =
        place_other_axle(on_lower, ch, x, y, out.z.hi, theta, direction, opt);
    const OtherAxlePlacement hi =
        place_other_axle(on_upper, ch, x, y, out.z.lo, theta, direction, opt);
    out.status = worse(out.status, worse(lo.status, hi.status));
    if (!usable(out.status)) break;
    pitch.include(lo.pitch);
    pitch.include(hi.pitch);
    // The outer axle's centre lies at d cos ψ along the heading for some ψ in
    // the pitch interval: its roll bounds are taken along that stretch of the
    // body line (N' already covers the domain's sideways and heading moves).
    constexpr int kSamples = 5;
    const double c_lo = std::min(std::cos(pitch.lo), std::cos(pitch.hi));
    const double c_hi = (pitch.lo <= 0.0 && pitch.hi >= 0.0)
                            ? 1.0
                            : std::max(std::cos(pitch.lo), std::cos(pitch.hi));
    for (int q = 0; q <= kSamples; ++q) {
      const double cpsi = c_lo + (c_hi - c_lo) * q / kSamples;
      const Vec2 c = m + direction * ch.axle_spacing * cpsi * f;
      const AxleBounds bd = axle_bounds(c.x(), c.y(), theta);
      ++lookups;
      out.status = worse(out.status, bd.status);
      if (!usable(out.status)) break;
      roll.include(bd.roll.lo);
      roll.include(bd.roll.hi);
    }
    if (!usable(out.status)) break;
  }
  out.axle_placements += lookups;
  return out;
}

std::vector<Quad> moved_lower_faces(const ArticulatedChassis& ch,
                                    const ChassisPlacementInterval& in, double x, double y,
                                    double theta, double rho, double dtheta) {
  if (!usable(in.status)) return {};
  if (!(rho >= 0.0) || !(dtheta >= 0.0 && dtheta < 0.5 * kPi)) {
    std::ostringstream msg;
    msg << "moved_lower_faces: need rho >= 0 and dtheta in [0, pi/2), got " << rho << ", "
        << dtheta;
    throw InputError(msg.str());
  }
  const Vec3 f(std::cos(theta), std::sin(theta), 0.0);
  const Vec3 g(-std::sin(theta), std::cos(theta), 0.0);
  const Vec3 m(x, y, in.z.lo);
  // The body's footprint swept by the domain (s along the body, l to its left), an 8-gon
  // (4 vertices without Δθ), cut into convex quads for the collision test.
  const std::vector<Vec2> o =
      swept_body_outline(ch.axle_spacing + ch.body.overhang, ch.body.half_width, rho, dtheta);
  const std::vector<std::array<int, 4>> pieces =
      o.size() == 4 ? std::vector<std::array<int, 4>>{{0, 1, 2, 3}}
                    : std::vector<std::array<int, 4>>{{0, 1, 2, 3}, {3, 4, 5, 6}, {0, 3, 6, 7}};
  std::vector<Quad> faces;
  for (int direction : {+1, -1}) {
    const Interval& pitch = direction > 0 ? in.pitch_front : in.pitch_rear;
    const Interval& outer = direction > 0 ? in.roll_front : in.roll_rear;
    const Vec3 e = direction * std::cos(pitch.lo) * f + std::sin(pitch.lo) * Vec3::UnitZ();
    for (double roll :
         {0.5 * (in.roll_middle.lo + outer.lo), 0.5 * (in.roll_middle.hi + outer.hi)}) {
      // As lower_faces(): the body's lateral axis is the mean axle direction,
      // made normal to the body axis.
      const Vec3 axle = std::cos(roll) * g + std::sin(roll) * Vec3::UnitZ();
      const Vec3 lat = (axle - axle.dot(e) * e).normalized();
      const Vec3 up = (direction * e).cross(lat);
      const Vec3 base = m + ch.body.clearance * up;
      const auto at = [&](int k) { return Vec3(base + o[k].x() * e + o[k].y() * lat); };
      for (const auto& q : pieces)
        faces.push_back(counter_clockwise({at(q[0]), at(q[1]), at(q[2]), at(q[3])}));
    }
  }
  return faces;
}

}  // namespace talus
