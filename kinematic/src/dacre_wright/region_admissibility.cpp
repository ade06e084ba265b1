#include "talus/kinematic/dacre_wright/region_admissibility.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <variant>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "talus/core/error.hpp"

namespace talus {
namespace {

constexpr double kPi = std::numbers::pi;

/// Range of A cos θ + B sin θ over θ ∈ [t1, t2] (exact: the endpoints and the
/// stationary points θ = atan2(B, A) + kπ inside the interval).
Range sinusoid_range(double a, double b, double t1, double t2) {
  const auto f = [&](double t) { return a * std::cos(t) + b * std::sin(t); };
  Range r{std::min(f(t1), f(t2)), std::max(f(t1), f(t2))};
  const double amp = std::hypot(a, b);
  if (amp == 0.0) return r;
  const double phase = std::atan2(b, a);
  // Stationary points phase + kπ in [t1, t2]: max at phase + 2mπ, min at phase + (2m+1)π.
  const double k0 = std::ceil((t1 - phase) / kPi);
  for (double k = k0; phase + k * kPi <= t2; k += 1.0) {
    const bool is_max = std::fmod(std::abs(k), 2.0) == 0.0;
    if (is_max)
      r.hi = amp;
    else
      r.lo = -amp;
  }
  return r;
}

/// The heading interval [t1, t2] with its end directions, so that the range
/// of A cos θ + B sin θ costs no trigonometric call when t2 − t1 < π: the
/// maximum amp is reached inside iff the direction (A, B) lies between the end
/// directions, the minimum iff (−A, −B) does.
struct Arc {
  double t1, t2, c1, s1, c2, s2;
  bool wide;  ///< t2 − t1 >= π: fall back to sinusoid_range
  Arc(double a, double b)
      : t1(a),
        t2(b),
        c1(std::cos(a)),
        s1(std::sin(a)),
        c2(std::cos(b)),
        s2(std::sin(b)),
        wide(b - a >= kPi) {}
  bool holds(double x, double y) const { return c1 * y - s1 * x >= 0.0 && x * s2 - y * c2 >= 0.0; }
  Range range(double a, double b) const {
    if (wide) return sinusoid_range(a, b, t1, t2);
    const double f1 = a * c1 + b * s1, f2 = a * c2 + b * s2;
    Range r{std::min(f1, f2), std::max(f1, f2)};
    if (a == 0.0 && b == 0.0) return r;
    if (holds(a, b)) r.hi = std::sqrt(a * a + b * b);
    if (holds(-a, -b)) r.lo = -std::sqrt(a * a + b * b);
    return r;
  }
};

Range add(Range a, Range b) {
  return {a.lo + b.lo, a.hi + b.hi};
}
Range neg(Range a) {
  return {-a.hi, -a.lo};
}
Range mul(Range a, Range b) {
  const double p[4] = {a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi};
  return {*std::min_element(p, p + 4), *std::max_element(p, p + 4)};
}
Range scale(double s, Range a) {
  return s >= 0 ? Range{s * a.lo, s * a.hi} : Range{s * a.hi, s * a.lo};
}
/// sin over an interval inside (−π/2, π/2) (monotone there).
Range sin_range(Range a) {
  return {std::sin(a.lo), std::sin(a.hi)};
}
/// cos over an interval inside (−π/2, π/2).
Range cos_range(Range a) {
  const double lo = std::min(std::cos(a.lo), std::cos(a.hi));
  const double hi = (a.lo <= 0.0 && a.hi >= 0.0) ? 1.0 : std::max(std::cos(a.lo), std::cos(a.hi));
  return {lo, hi};
}
Range intersect(Range a, Range b) {
  return {std::max(a.lo, b.lo), std::min(a.hi, b.hi)};
}
bool empty(Range a) {
  return a.lo > a.hi;
}
bool strictly_inside(Range a, double limit) {
  return a.lo > -limit && a.hi < limit;
}

/// The placement domain Δr of one pass: attitude and spring extensions.
struct Domain {
  Range roll, pitch;
  std::array<Range, WheeledRobot::kMaxWheels> ext{};
};

/// Node index range [lo, hi] of the patches meeting [v1, v2] along one axis;
/// false when it leaves the lattice.
bool node_range(double v1, double v2, double origin, double h, std::size_t nodes, long& lo,
                long& hi) {
  // A relative guard of 1e-9 cells widens the range, never narrows it.
  lo = static_cast<long>(std::floor((v1 - origin) / h - 1e-9));
  hi = static_cast<long>(std::ceil((v2 - origin) / h + 1e-9));
  lo = std::max(lo, 0L);  // a region grazing the border from inside keeps its nodes
  if ((v1 - origin) / h < -1e-9) return false;
  if ((v2 - origin) / h > static_cast<double>(nodes - 1) + 1e-9) return false;
  hi = std::min(hi, static_cast<long>(nodes) - 1);
  return true;
}

}  // namespace

void require_symmetric_wheels(const WheeledRobot& robot, double tolerance) {
  double su = 0, sv = 0, suv = 0, scale = 0;
  for (const Vec2& w : robot.wheels) {
    su += w.x();
    sv += w.y();
    suv += w.x() * w.y();
    scale += w.squaredNorm();
  }
  const double lin = tolerance * std::sqrt(std::max(scale, 1e-300));
  const double quad = tolerance * std::max(scale, 1e-300);
  const auto fail = [&](const char* what, double value) {
    std::ostringstream msg;
    msg << (robot.name.empty() ? std::string("the robot") : "robot '" + robot.name + "'")
        << ": the Dacre-Wright-Simeon analysis needs a wheel layout "
        << "symmetric about G (sum u = sum v = sum u*v = 0, s3.3.2), but " << what << " = "
        << value;
    throw InputError(msg.str());
  };
  if (std::abs(su) > lin) fail("sum u", su);
  if (std::abs(sv) > lin) fail("sum v", sv);
  if (std::abs(suv) > quad) fail("sum u*v", suv);
}

WheeledRobot load_dacre_wright_robot(const std::string& path) {
  Robot r = load_robot(path);
  const WheeledRobot* w = std::get_if<WheeledRobot>(&r);
  if (!w)
    throw InputError(path + ": the Dacre-Wright-Simeon planner needs a 'type: wheeled' robot");
  try {
    require_symmetric_wheels(*w);
  } catch (const InputError& e) {
    throw InputError(path + ": " + e.what());
  }
  return *w;
}

bool admissible(const WheeledRobot& robot, const RobotPlacement& p) {
  if (!usable(p.status)) return false;
  if (!(std::abs(p.roll) < robot.max_roll && std::abs(p.pitch) < robot.max_pitch)) return false;
  for (int j = 0; j < p.wheel_count; ++j) {
    if (!(std::abs(p.extensions[j]) < robot.max_spring_extension)) return false;
  }
  return true;
}

bool CsBox::contains(const SE2Pose& q) const {
  return q.x >= x1 && q.x <= x2 && q.y >= y1 && q.y <= y2 && q.theta >= theta1 && q.theta <= theta2;
}

Mat3 AveragePlaneAccumulator::ata() const {
  Mat3 m;
  m << suu_, suv_, su_, suv_, svv_, sv_, su_, sv_, static_cast<double>(count_);
  return m;
}

bool AveragePlaneAccumulator::solve(Vec3& abc) const {
  if (count_ < 3) return false;
  const Eigen::LDLT<Mat3> ldlt(ata());
  if (ldlt.info() != Eigen::Success) return false;
  // Collinear points make AᵀA singular: its smallest pivot vanishes against the largest.
  const Vec3 d = ldlt.vectorD().cwiseAbs();
  if (!(d.minCoeff() > 1e-12 * d.maxCoeff())) return false;
  const Vec3 local = ldlt.solve(atb());
  // z = a (x - x0) + b (y - y0) + c'  →  c = c' - a x0 - b y0.
  abc = Vec3(local.x(), local.y(), local.z() - local.x() * origin_.x() - local.y() * origin_.y());
  return true;
}

void BoxAnalysisOptions::validate() const {
  if (refinements < 0) {
    throw InputError("BoxAnalysisOptions.refinements must be >= 0, got " +
                     std::to_string(refinements));
  }
}

const char* to_string(BoxVerdict verdict) {
  switch (verdict) {
    case BoxVerdict::kFree:
      return "free";
    case BoxVerdict::kOffMap:
      return "off_map";
    case BoxVerdict::kDegeneratePlane:
      return "degenerate_plane";
    case BoxVerdict::kNoBetaBound:
      return "no_beta_bound";
    case BoxVerdict::kAttitude:
      return "attitude";
    case BoxVerdict::kSpring:
      return "spring";
  }
  return "unknown";
}

double paper_beta_max(double k) {
  if (k == 0.0) return 0.0;
  // −(1 − √(K²+1))/K written as K / (√(K²+1) + 1): the same number without
  // the cancellation of √(K²+1) − 1 for small K.
  return 2.0 * std::atan(k / (std::sqrt(k * k + 1.0) + 1.0));
}

ElevationSums::ElevationSums(const RuledTerrain& terrain) : terrain_(terrain) {
  const ElevationGrid& g = terrain.grid();
  const std::size_t nc = g.ncols(), nr = g.nrows();
  stride_ = nc + 1;
  // The reference elevation: the first data node (conditioning of the sums).
  for (std::size_t k = 0; k < nc * nr; ++k) {
    if (g.valid(k % nc, k / nc)) {
      z_ref_ = g.at(k % nc, k / nc);
      break;
    }
  }
  const std::size_t size = stride_ * (nr + 1);
  z_.assign(size, 0.0);
  iz_.assign(size, 0.0);
  jz_.assign(size, 0.0);
  invalid_.assign(size, 0.0);
  for (std::size_t j = 0; j < nr; ++j) {
    double rz = 0, riz = 0, rjz = 0, rinv = 0;  // running sums along the row
    for (std::size_t i = 0; i < nc; ++i) {
      const bool ok = g.valid(i, j);
      const double z = ok ? g.at(i, j) - z_ref_ : 0.0;
      rz += z;
      riz += static_cast<double>(i) * z;
      rjz += static_cast<double>(j) * z;
      rinv += ok ? 0.0 : 1.0;
      const std::size_t k = (j + 1) * stride_ + (i + 1), up = j * stride_ + (i + 1);
      z_[k] = z_[up] + rz;
      iz_[k] = iz_[up] + riz;
      jz_[k] = jz_[up] + rjz;
      invalid_[k] = invalid_[up] + rinv;
    }
  }
}

bool ElevationSums::accumulate(long i_lo, long i_hi, long j_lo, long j_hi,
                               AveragePlaneAccumulator& acc) const {
  if (rect(invalid_, i_lo, i_hi, j_lo, j_hi) > 0.5) return false;
  const ElevationGrid& g = terrain_.grid();
  const double h = g.cellsize();
  // Local indices i' = i - i_lo in [0, w), j' = j - j_lo in [0, r): exact moments.
  const double w = static_cast<double>(i_hi - i_lo + 1), r = static_cast<double>(j_hi - j_lo + 1);
  const double n = w * r;
  const double si = r * w * (w - 1) / 2, sj = w * r * (r - 1) / 2;
  const double sii = r * (w - 1) * w * (2 * w - 1) / 6, sjj = w * (r - 1) * r * (2 * r - 1) / 6;
  const double sij = (w * (w - 1) / 2) * (r * (r - 1) / 2);
  const double z = rect(z_, i_lo, i_hi, j_lo, j_hi);
  const double iz = rect(iz_, i_lo, i_hi, j_lo, j_hi) - static_cast<double>(i_lo) * z;
  const double jz = rect(jz_, i_lo, i_hi, j_lo, j_hi) - static_cast<double>(j_lo) * z;
  // u = ox + h i', v = oy + h j' relative to the accumulator's origin.
  const double ox = g.x_min() + h * static_cast<double>(i_lo) - acc.origin().x();
  const double oy = g.y_min() + h * static_cast<double>(j_lo) - acc.origin().y();
  const double su = n * ox + h * si, sv = n * oy + h * sj;
  acc.add_sums(static_cast<std::size_t>(n), su, sv, n * ox * ox + 2 * ox * h * si + h * h * sii,
               n * ox * oy + ox * h * sj + oy * h * si + h * h * sij,
               n * oy * oy + 2 * oy * h * sj + h * h * sjj, z + n * z_ref_,
               ox * z + h * iz + z_ref_ * su, oy * z + h * jz + z_ref_ * sv);
  return true;
}

namespace {

/// min and max over the row's nodes of z - (a x + b y + c), x = x0 + h i: the
/// same expression, evaluated the same way, as the plain loop.
void row_envelope(const double* z, const double* ax, long count, double by, double c, double& lo,
                  double& hi) {
  long k = 0;
#if defined(__SSE2__)
  __m128d vlo = _mm_set1_pd(lo), vhi = _mm_set1_pd(hi);
  const __m128d vby = _mm_set1_pd(by), vc = _mm_set1_pd(c);
  for (; k + 2 <= count; k += 2) {
    const __m128d t = _mm_add_pd(_mm_add_pd(_mm_loadu_pd(ax + k), vby), vc);
    const __m128d d = _mm_sub_pd(_mm_loadu_pd(z + k), t);
    vlo = _mm_min_pd(vlo, d);
    vhi = _mm_max_pd(vhi, d);
  }
  double l2[2], h2[2];
  _mm_storeu_pd(l2, vlo);
  _mm_storeu_pd(h2, vhi);
  lo = std::min(l2[0], l2[1]);
  hi = std::max(h2[0], h2[1]);
#endif
  for (; k < count; ++k) {
    const double d = z[k] - (ax[k] + by + c);
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
}

BoxAnalysis analyse_box_impl(const WheeledRobot& robot, const RuledTerrain& terrain,
                             const ElevationSums* sums, const CsBox& in,
                             const BoxAnalysisOptions& options);

}  // namespace

BoxAnalysis analyse_box(const WheeledRobot& robot, const RuledTerrain& terrain, const CsBox& in,
                        const BoxAnalysisOptions& options) {
  return analyse_box_impl(robot, terrain, nullptr, in, options);
}

BoxAnalysis analyse_box(const WheeledRobot& robot, const ElevationSums& sums, const CsBox& in,
                        const BoxAnalysisOptions& options) {
  return analyse_box_impl(robot, sums.terrain(), &sums, in, options);
}

namespace {

using WheelRanges = std::array<Range, WheeledRobot::kMaxWheels>;

/// The node index ranges of each wheel's contact region.
struct ContactRegions {
  std::array<long, WheeledRobot::kMaxWheels> i_lo{}, i_hi{}, j_lo{}, j_hi{};
};

/// §3.2.1: contact regions. The wheel's projection in the heading frame, first two
/// coordinates of Ry(−ψ) Rx(φ) (u, v, w0 + l), bounded by interval arithmetic over Δφ, Δψ,
/// Δl_i; then the exact bounding box of that rectangle swept over [θ1, θ2] and translated
/// over [x1, x2] × [y1, y2]. False when a region leaves the map.
bool contact_regions(const WheeledRobot& robot, const ElevationGrid& grid, const CsBox& box,
                     const Arc& arc, const Domain& dom, ContactRegions& reg, BoxAnalysis& out) {
  const double h = grid.cellsize();
  const Range sphi = sin_range(dom.roll), cphi = cos_range(dom.roll);
  const Range spsi = sin_range(dom.pitch), cpsi = cos_range(dom.pitch);
  for (int i = 0; i < out.wheel_count; ++i) {
    const double u = robot.wheels[i].x(), v = robot.wheels[i].y();
    const Range w{-robot.cg_height + dom.ext[i].lo, -robot.cg_height + dom.ext[i].hi};
    const Range yp = add(scale(v, cphi), neg(mul(w, sphi)));
    const Range xp = add(scale(u, cpsi), neg(mul(add(scale(v, sphi), mul(w, cphi)), spsi)));
    Range rx{1e300, -1e300}, ry{1e300, -1e300};
    for (double cx : {xp.lo, xp.hi}) {
      for (double cy : {yp.lo, yp.hi}) {
        const Range ox = arc.range(cx, -cy);
        const Range oy = arc.range(cy, cx);
        rx = {std::min(rx.lo, ox.lo), std::max(rx.hi, ox.hi)};
        ry = {std::min(ry.lo, oy.lo), std::max(ry.hi, oy.hi)};
      }
    }
    rx = {rx.lo + box.x1, rx.hi + box.x2};
    ry = {ry.lo + box.y1, ry.hi + box.y2};
    if (!node_range(rx.lo, rx.hi, grid.x_min(), h, grid.ncols(), reg.i_lo[i], reg.i_hi[i]) ||
        !node_range(ry.lo, ry.hi, grid.y_min(), h, grid.nrows(), reg.j_lo[i], reg.j_hi[i])) {
      return false;
    }
    out.region_x[i] = {grid.x_min() + h * static_cast<double>(reg.i_lo[i]),
                       grid.x_min() + h * static_cast<double>(reg.i_hi[i])};
    out.region_y[i] = {grid.y_min() + h * static_cast<double>(reg.j_lo[i]),
                       grid.y_min() + h * static_cast<double>(reg.j_hi[i])};
  }
  return true;
}

/// §3.2.2: the average plane over the nodes of every contact region (a node in two regions
/// counts twice; P_a is only a reference plane), from the prefix sums when given. Sets
/// out.points and out.plane, or the verdict when a node is off the map or the plane
/// degenerate (then false).
bool average_plane(const ElevationGrid& grid, const ElevationSums* sums, const Vec2& centre,
                   const ContactRegions& reg, BoxAnalysis& out) {
  const double h = grid.cellsize();
  const int n = out.wheel_count;
  AveragePlaneAccumulator acc(centre);
  for (int i = 0; i < n && sums; ++i) {
    if (!sums->accumulate(reg.i_lo[i], reg.i_hi[i], reg.j_lo[i], reg.j_hi[i], acc)) {
      out.verdict = BoxVerdict::kOffMap;
      return false;
    }
  }
  for (int i = 0; i < n && !sums; ++i) {
    for (long jj = reg.j_lo[i]; jj <= reg.j_hi[i]; ++jj) {
      const double y = grid.y_min() + h * static_cast<double>(jj);
      for (long ii = reg.i_lo[i]; ii <= reg.i_hi[i]; ++ii) {
        const auto ui = static_cast<std::size_t>(ii), uj = static_cast<std::size_t>(jj);
        if (!grid.valid(ui, uj)) {
          out.verdict = BoxVerdict::kOffMap;
          return false;
        }
        acc.add(grid.x_min() + h * static_cast<double>(ii), y, grid.at(ui, uj));
      }
    }
  }
  out.points = acc.count();
  Vec3 abc;
  if (!acc.solve(abc)) {
    out.verdict = BoxVerdict::kDegeneratePlane;
    return false;
  }
  out.plane = abc;
  return true;
}

/// §3.2.3: envelopes δz_i^min, δz_i^max of the surface over each region against the plane;
/// the bilinear patches minus a plane take their extremes at the nodes, so these bound the
/// whole surface over R_i. Returns the distances d_i = cos φ_a cos ψ_a δz_i.
WheelRanges plane_distances(const ElevationGrid& grid, const ContactRegions& reg,
                            BoxAnalysis& out) {
  const double a = out.plane.x(), b = out.plane.y(), c = out.plane.z();
  const double h = grid.cellsize();
  thread_local std::vector<double> ax;                     // a x of one region's columns
  const double ca = 1.0 / std::sqrt(1.0 + a * a + b * b);  // cos φ_a cos ψ_a
  WheelRanges d{};
  const double* zs = grid.values().data();
  for (int i = 0; i < out.wheel_count; ++i) {
    Range r{1e300, -1e300};
    const long w = reg.i_hi[i] - reg.i_lo[i] + 1;
    ax.resize(static_cast<std::size_t>(w));
    for (long ii = reg.i_lo[i]; ii <= reg.i_hi[i]; ++ii) {
      ax[static_cast<std::size_t>(ii - reg.i_lo[i])] =
          a * (grid.x_min() + h * static_cast<double>(ii));
    }
    for (long jj = reg.j_lo[i]; jj <= reg.j_hi[i]; ++jj) {
      const double y = grid.y_min() + h * static_cast<double>(jj);
      row_envelope(
          zs + static_cast<std::size_t>(jj) * grid.ncols() + static_cast<std::size_t>(reg.i_lo[i]),
          ax.data(), w, b * y, c, r.lo, r.hi);
    }
    out.dz[i] = r;
    d[i] = {ca * r.lo, ca * r.hi};
  }
  return d;
}

/// §3.3.2: the bound β_max on the placement's tilt from the plane, from the distances d_i;
/// e_i = d_i − d0 in `e`. False (verdict kNoBetaBound) when the paper's condition fails.
bool beta_bound(const WheeledRobot& robot, const WheelRanges& d, WheelRanges& e, BoxAnalysis& out) {
  const int n = out.wheel_count;
  double sum_u2 = 0, sum_v2 = 0;
  for (const Vec2& w : robot.wheels) {
    sum_u2 += w.x() * w.x();
    sum_v2 += w.y() * w.y();
  }
  // d0 = mean d_i (Σ l_i = 0 at the minimum and Σ u_i = Σ v_i = 0).
  double sum_lo = 0, sum_hi = 0;
  for (int i = 0; i < n; ++i) {
    sum_lo += d[i].lo;
    sum_hi += d[i].hi;
  }
  out.d0 = {sum_lo / n, sum_hi / n};
  // d_i − d0 = (1 − 1/n) d_i − (1/n) Σ_{j≠i} d_j, bounded exactly.
  double max_a = 0;
  for (int i = 0; i < n; ++i) {
    const double k = 1.0 - 1.0 / n;
    e[i] = {k * d[i].lo - (sum_hi - d[i].hi) / n, k * d[i].hi - (sum_lo - d[i].lo) / n};
    max_a += std::max(e[i].lo * e[i].lo, e[i].hi * e[i].hi);
  }
  // Footnote 6: extremes of Σ d_i u_i and Σ d_i v_i.
  Range su{0, 0}, sv{0, 0};
  for (int i = 0; i < n; ++i) {
    const double u = robot.wheels[i].x(), v = robot.wheels[i].y();
    su = add(su, scale(u, d[i]));
    sv = add(sv, scale(v, d[i]));
  }
  const double mu = std::max(std::abs(su.lo), std::abs(su.hi));
  const double mv = std::max(std::abs(sv.lo), std::abs(sv.hi));
  out.max_a = max_a;
  out.max_b = std::hypot(mu, mv);
  out.min_c = std::min(sum_u2, sum_v2);
  if (!(out.max_a < out.min_c) || !(out.max_b < out.min_c)) {
    out.verdict = BoxVerdict::kNoBetaBound;
    return false;
  }
  const double kk = out.max_b / (out.min_c - out.max_a);
  out.beta_paper = paper_beta_max(kk);
  out.beta_max = std::max(out.beta_paper, std::asin(out.max_b / out.min_c));
  return true;
}

/// §3.3.3: Δφ, Δψ around the plane's attitude over the whole θ interval, and each spring's
/// extension range, within β_max of the plane: this pass's domain (out.roll, out.pitch,
/// out.extension set to it).
Domain placement_ranges(const WheeledRobot& robot, const Arc& arc, const WheelRanges& e,
                        BoxAnalysis& out) {
  const double a = out.plane.x(), b = out.plane.y();
  const double beta = out.beta_max;
  const double nrm = std::sqrt(1.0 + a * a + b * b);
  const Range t = arc.range(b, -a);  // cross slope × N, along the body's v axis
  const Range s = arc.range(a, b);   // slope along the body's u axis
  const Range roll_a{std::asin(std::clamp(t.lo / nrm, -1.0, 1.0)),
                     std::asin(std::clamp(t.hi / nrm, -1.0, 1.0))};
  const Range pitch_a{std::atan(s.lo), std::atan(s.hi)};
  Domain pass;
  pass.roll = {roll_a.lo - beta, roll_a.hi + beta};
  const double big_phi = std::max(std::abs(pass.roll.lo), std::abs(pass.roll.hi));
  pass.pitch = {-1e300, 1e300};
  if (big_phi < 0.5 * kPi) {
    const double half = beta / std::cos(big_phi);
    pass.pitch = {pitch_a.lo - half, pitch_a.hi + half};
  }
  const double inv_cos = 1.0 / std::cos(beta), tan_b = std::tan(beta);
  for (int i = 0; i < out.wheel_count; ++i) {
    const double r = robot.wheels[i].norm();
    pass.ext[i] = {(e[i].lo < 0 ? e[i].lo * inv_cos : e[i].lo) - tan_b * r,
                   (e[i].hi > 0 ? e[i].hi * inv_cos : e[i].hi) + tan_b * r};
  }
  out.roll = pass.roll;
  out.pitch = pass.pitch;
  for (int i = 0; i < out.wheel_count; ++i) out.extension[i] = pass.ext[i];
  return pass;
}

/// Every placement in Δr0 lies in this pass's Δr: `dom` becomes the intersection. The
/// verdict: kSpring when it is empty (no configuration of the box has an admissible
/// placement), kFree when it lies strictly inside the robot's limits (true: decided),
/// otherwise the limit it reaches (false: another pass may narrow it).
bool narrow_domain(const WheeledRobot& robot, const Domain& pass, Domain& dom, BoxAnalysis& out) {
  const int n = out.wheel_count;
  const double lmax = robot.max_spring_extension;
  dom.roll = intersect(dom.roll, pass.roll);
  dom.pitch = intersect(dom.pitch, pass.pitch);
  bool any_empty = empty(dom.roll) || empty(dom.pitch);
  for (int i = 0; i < n; ++i) {
    dom.ext[i] = intersect(dom.ext[i], pass.ext[i]);
    any_empty = any_empty || empty(dom.ext[i]);
  }
  if (any_empty) {
    out.verdict = BoxVerdict::kSpring;
    return true;
  }
  const bool attitude_ok =
      strictly_inside(dom.roll, robot.max_roll) && strictly_inside(dom.pitch, robot.max_pitch);
  bool spring_ok = true;
  for (int i = 0; i < n; ++i) spring_ok = spring_ok && strictly_inside(dom.ext[i], lmax);
  out.roll = dom.roll;
  out.pitch = dom.pitch;
  for (int i = 0; i < n; ++i) out.extension[i] = dom.ext[i];
  if (attitude_ok && spring_ok) {
    out.verdict = BoxVerdict::kFree;
    return true;
  }
  out.verdict = attitude_ok ? BoxVerdict::kSpring : BoxVerdict::kAttitude;
  return false;
}

BoxAnalysis analyse_box_impl(const WheeledRobot& robot, const RuledTerrain& terrain,
                             const ElevationSums* sums, const CsBox& in,
                             const BoxAnalysisOptions& options) {
  options.validate();
  CsBox box = in;
  if (box.x1 > box.x2) std::swap(box.x1, box.x2);
  if (box.y1 > box.y2) std::swap(box.y1, box.y2);
  if (box.theta1 > box.theta2) std::swap(box.theta1, box.theta2);
  const ElevationGrid& grid = terrain.grid();
  BoxAnalysis out;
  out.wheel_count = static_cast<int>(robot.wheels.size());
  Domain dom;
  dom.roll = {-robot.max_roll, robot.max_roll};
  dom.pitch = {-robot.max_pitch, robot.max_pitch};
  const double lmax = robot.max_spring_extension;
  for (int i = 0; i < out.wheel_count; ++i) dom.ext[i] = {-lmax, lmax};
  const Vec2 centre(0.5 * (box.x1 + box.x2), 0.5 * (box.y1 + box.y2));
  const Arc arc(box.theta1, box.theta2);
  ContactRegions regions;
  for (int pass = 0; pass <= options.refinements; ++pass) {
    out.passes = pass + 1;
    if (!contact_regions(robot, grid, box, arc, dom, regions, out)) {
      out.verdict = BoxVerdict::kOffMap;
      return out;
    }
    if (!average_plane(grid, sums, centre, regions, out)) return out;
    const WheelRanges d = plane_distances(grid, regions, out);
    WheelRanges e{};
    if (!beta_bound(robot, d, e, out)) return out;
    const Domain this_pass = placement_ranges(robot, arc, e, out);
    if (narrow_domain(robot, this_pass, dom, out)) return out;
  }
  return out;
}

}  // namespace

}  // namespace talus
