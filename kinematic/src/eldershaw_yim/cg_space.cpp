#include "talus/kinematic/eldershaw_yim/cg_space.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <span>

#include "talus/core/error.hpp"

namespace talus {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

/// Node index range [lo, hi] covering [a, b] along one grid axis (empty when hi < lo).
void node_span(double a, double b, double origin, double h, std::size_t n, long& lo, long& hi) {
  lo = static_cast<long>(std::ceil((a - origin) / h - 1e-9));
  hi = static_cast<long>(std::floor((b - origin) / h + 1e-9));
  lo = std::max(lo, 0L);
  hi = std::min(hi, static_cast<long>(n) - 1);
}

/// The body frame of a CG pose: body (u forward, v left) ↔ world (x, y).
struct BodyFrame {
  explicit BodyFrame(const SE2Pose& q) : cg(q.x, q.y), c(std::cos(q.theta)), s(std::sin(q.theta)) {}
  Vec2 to_world(const Vec2& uv) const {
    return Vec2(cg.x() + c * uv.x() - s * uv.y(), cg.y() + s * uv.x() + c * uv.y());
  }
  Vec2 to_body(const Vec2& p) const {
    const Vec2 d = p - cg;
    return Vec2(c * d.x() + s * d.y(), -s * d.x() + c * d.y());
  }
  /// The grid's node span [i0, i1] x [j0, j1] covering the world bounding box
  /// of the body points `body_points`.
  void node_box(const ElevationGrid& g, std::span<const Vec2> body_points, long& i0, long& i1,
                long& j0, long& j1) const {
    double xa = std::numeric_limits<double>::infinity(), xb = -xa, ya = xa, yb = -xa;
    for (const Vec2& uv : body_points) {
      const Vec2 p = to_world(uv);
      xa = std::min(xa, p.x());
      xb = std::max(xb, p.x());
      ya = std::min(ya, p.y());
      yb = std::max(yb, p.y());
    }
    node_span(xa, xb, g.x_min(), g.cellsize(), g.ncols(), i0, i1);
    node_span(ya, yb, g.y_min(), g.cellsize(), g.nrows(), j0, j1);
  }
  Vec2 cg;
  double c, s;
};

}  // namespace

const char* to_string(CgState s) {
  switch (s) {
    case CgState::kUnknown:
      return "unknown";
    case CgState::kValid:
      return "valid";
    case CgState::kOffData:
      return "off_data";
    case CgState::kNoSupport:
      return "no_support";
    case CgState::kTooShort:
      return "too_short";
    case CgState::kFeedback:
      return "feedback";
  }
  return "unknown";
}

CgLattice::CgLattice(const ElevationGrid& grid, double spacing, int theta_slices)
    : x0_(grid.x_min()), y0_(grid.y_min()), f_(spacing), nt_(theta_slices) {
  if (!(theta_slices == 1 || (theta_slices >= 8 && theta_slices <= 1024)))
    throw InputError("theta slices must be 1 (no rotation) or 8 to 1024, got " +
                     std::to_string(theta_slices));
  if (!(std::isfinite(spacing) && spacing > 0))
    throw InputError("the CG-space spacing (foot_print) must be > 0");
  const double nx = std::floor((grid.x_max() - grid.x_min()) / spacing + 1e-9) + 1;
  const double ny = std::floor((grid.y_max() - grid.y_min()) / spacing + 1e-9) + 1;
  if (nx * ny * theta_slices > 2147483647.0)
    throw InputError(
        "the CG space would have more than 2^31 cells; use a larger foot_print or "
        "fewer theta slices");
  nx_ = static_cast<int>(nx);
  ny_ = static_cast<int>(ny);
}

CgCell CgLattice::cell(std::size_t index) const {
  CgCell c;
  c.ix = static_cast<int>(index % static_cast<std::size_t>(nx_));
  index /= static_cast<std::size_t>(nx_);
  c.iy = static_cast<int>(index % static_cast<std::size_t>(ny_));
  c.it = static_cast<int>(index / static_cast<std::size_t>(ny_));
  return c;
}

CgCell CgLattice::cell_of(const SE2Pose& q) const {
  CgCell c;
  c.ix =
      static_cast<int>(std::clamp(std::lround((q.x - x0_) / f_), 0L, static_cast<long>(nx_ - 1)));
  c.iy =
      static_cast<int>(std::clamp(std::lround((q.y - y0_) / f_), 0L, static_cast<long>(ny_ - 1)));
  double t = std::fmod(q.theta, kTwoPi);
  if (t < 0) t += kTwoPi;
  c.it = static_cast<int>(std::lround(t / kTwoPi * nt_)) % nt_;
  return c;
}

double CgLattice::heading(int it) const {
  return kTwoPi * it / nt_;
}

SE2Pose CgLattice::centre(const CgCell& c) const {
  return {x0_ + c.ix * f_, y0_ + c.iy * f_, heading(c.it)};
}

std::optional<double> cg_min_height(const Footmap& footmap, const LeggedRobot& robot,
                                    const SE2Pose& q) {
  const RuledTerrain& terrain = footmap.terrain();
  const ElevationGrid& g = terrain.grid();
  const BodyFrame body(q);

  // MinHeight over the under-carriage.
  const BodyField& depth = robot.under_carriage.depth;
  const double ua = depth.origin.x(), va = depth.origin.y();
  const double ub = ua + static_cast<double>(depth.nu - 1) * depth.spacing;
  const double vb = va + static_cast<double>(depth.nv - 1) * depth.spacing;
  double min_height = -std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < depth.nv; ++k) {
    for (std::size_t i = 0; i < depth.nu; ++i) {
      const Vec2 p = body.to_world({ua + static_cast<double>(i) * depth.spacing,
                                    va + static_cast<double>(k) * depth.spacing});
      if (!terrain.has_data(p)) return std::nullopt;
      min_height = std::max(min_height, terrain.elevation(p) + depth.values[k * depth.nu + i]);
    }
  }
  {
    long i0, i1, j0, j1;
    const std::array<Vec2, 4> corners = {Vec2(ua, va), Vec2(ub, va), Vec2(ub, vb), Vec2(ua, vb)};
    body.node_box(g, corners, i0, i1, j0, j1);
    for (long j = j0; j <= j1; ++j) {
      for (long i = i0; i <= i1; ++i) {
        const auto iu = static_cast<std::size_t>(i), ju = static_cast<std::size_t>(j);
        const Vec2 uv = body.to_body(g.node_position(iu, ju));
        if (!depth.covers(uv)) continue;
        if (!g.valid(iu, ju)) return std::nullopt;
        min_height = std::max(min_height, g.at(iu, ju) + depth.at(uv));
      }
    }
  }

  return min_height;
}

CgState evaluate_cg_pose(const Footmap& footmap, const LeggedRobot& robot, const SE2Pose& q) {
  const RuledTerrain& terrain = footmap.terrain();
  const ElevationGrid& g = terrain.grid();
  const BodyFrame body(q);

  const std::optional<double> mh = cg_min_height(footmap, robot, q);
  if (!mh) return CgState::kOffData;
  const double min_height = *mh;

  // Rules (a) and (b): a reaching valid foot position in every quadrant.
  bool support[4] = {false, false, false, false};
  bool reached[4] = {false, false, false, false};
  int reached_count = 0;
  for (const Leg& leg : robot.legs) {
    long i0, i1, j0, j1;
    body.node_box(g, leg.range, i0, i1, j0, j1);
    for (long j = j0; j <= j1; ++j) {
      for (long i = i0; i <= i1; ++i) {
        const auto iu = static_cast<std::size_t>(i), ju = static_cast<std::size_t>(j);
        if (!footmap.valid(iu, ju)) continue;
        const Vec2 uv = body.to_body(g.node_position(iu, ju));
        const int quadrant = (uv.x() < 0 ? 1 : 0) + (uv.y() < 0 ? 2 : 0);
        if (reached[quadrant]) continue;
        if (!leg.in_range(uv)) continue;
        support[quadrant] = true;
        if (g.at(iu, ju) + leg.reach.at(uv) > min_height) {
          reached[quadrant] = true;
          if (++reached_count == 4) return CgState::kValid;
        }
      }
    }
  }
  for (int k = 0; k < 4; ++k)
    if (!support[k]) return CgState::kNoSupport;
  return CgState::kTooShort;
}

std::vector<CgState> evaluate_cg_slice(const Footmap& footmap, const LeggedRobot& robot,
                                       const CgLattice& lattice, int it) {
  if (it < 0 || it >= lattice.ntheta())
    throw InputError("evaluate_cg_slice: slice " + std::to_string(it) + " is not in 0.." +
                     std::to_string(lattice.ntheta() - 1));
  std::vector<CgState> out;
  out.reserve(static_cast<std::size_t>(lattice.nx()) * static_cast<std::size_t>(lattice.ny()));
  for (int iy = 0; iy < lattice.ny(); ++iy)
    for (int ix = 0; ix < lattice.nx(); ++ix)
      out.push_back(evaluate_cg_pose(footmap, robot, lattice.centre({ix, iy, it})));
  return out;
}

CgSpace::CgSpace(const Footmap& footmap, const LeggedRobot& robot, int theta_slices, int block_side)
    : footmap_(&footmap),
      robot_(&robot),
      lattice_(footmap.terrain().grid(), robot.foot_print, theta_slices),
      block_(block_side) {
  if (block_side < 1) throw InputError("CgSpace: block side must be >= 1");
  bx_ = (lattice_.nx() + block_ - 1) / block_;
}

CgSpace::CgSpace(OverlayOn, const CgSpace& base)
    : footmap_(base.footmap_),
      robot_(base.robot_),
      base_(&base),
      lattice_(base.lattice_),
      block_(base.block_),
      bx_(base.bx_) {}

std::size_t CgSpace::block_cells(std::size_t key) const {
  const auto bxi = static_cast<int>(key % static_cast<std::size_t>(bx_));
  const auto byi = static_cast<int>(key / static_cast<std::size_t>(bx_));
  const auto w = static_cast<std::size_t>(std::min(block_, lattice_.nx() - bxi * block_));
  const auto h = static_cast<std::size_t>(std::min(block_, lattice_.ny() - byi * block_));
  return w * h * static_cast<std::size_t>(lattice_.ntheta());
}

void CgSpace::absorb(CgSpace&& overlay) {
  if (overlay.base_ != this) throw InputError("CgSpace::absorb: not an overlay on this space");
  for (auto& [key, cells] : overlay.blocks_) {
    if (blocks_.count(key)) continue;
    if (foreign_.erase(key) == 0) cells_ += block_cells(key);
    blocks_.emplace(key, std::move(cells));
  }
  seconds_ += overlay.seconds_;
  overlay.blocks_.clear();
  overlay.cells_ = 0;
  overlay.seconds_ = 0.0;
}

std::vector<std::size_t> CgSpace::block_keys() const {
  std::vector<std::size_t> out;
  out.reserve(blocks_.size());
  for (const auto& entry : blocks_) out.push_back(entry.first);
  std::sort(out.begin(), out.end());
  return out;
}

void CgSpace::count_blocks(const std::vector<std::size_t>& keys) {
  for (std::size_t key : keys) {
    if (key >= static_cast<std::size_t>(bx_) *
                   static_cast<std::size_t>((lattice_.ny() + block_ - 1) / block_))
      throw InputError("CgSpace::count_blocks: no block " + std::to_string(key));
    if (blocks_.count(key) || foreign_.count(key)) continue;
    foreign_.insert(key);
    cells_ += block_cells(key);
  }
}

CgState CgSpace::peek(const CgCell& c) const {
  if (!lattice_.contains(c)) return CgState::kOffData;
  if (base_) {
    const CgState b = base_->peek(c);
    if (b != CgState::kUnknown) return b;
  }
  if (!marked_.empty() && marked_.count(lattice_.index(c))) return CgState::kFeedback;
  const std::size_t key = static_cast<std::size_t>(c.iy / block_) * static_cast<std::size_t>(bx_) +
                          static_cast<std::size_t>(c.ix / block_);
  const auto it = blocks_.find(key);
  if (it == blocks_.end()) return CgState::kUnknown;
  const int lx = c.ix % block_, ly = c.iy % block_;
  return it->second[(static_cast<std::size_t>(c.it) * block_ + ly) * block_ + lx];
}

void CgSpace::mark_invalid(const CgCell& c) {
  if (lattice_.contains(c)) marked_.insert(lattice_.index(c));
}

CgState CgSpace::state(const CgCell& c) {
  if (!lattice_.contains(c)) return CgState::kOffData;
  if (base_) {  // the base's blocks and marks first (an overlay has no marks of its own)
    const CgState b = base_->peek(c);
    if (b != CgState::kUnknown) return b;
  }
  if (!marked_.empty() && marked_.count(lattice_.index(c))) {
    (void)peek(c);  // keeps the materialisation accounting independent of the marks
    return CgState::kFeedback;
  }
  const int bxi = c.ix / block_, byi = c.iy / block_;
  const std::size_t key =
      static_cast<std::size_t>(byi) * static_cast<std::size_t>(bx_) + static_cast<std::size_t>(bxi);
  auto it = blocks_.find(key);
  if (it == blocks_.end()) {
    // A block counted already (here or, for an overlay, in its base) is not counted again.
    const bool counted = foreign_.erase(key) > 0 || (base_ && base_->foreign_.count(key) > 0);
    const auto t0 = std::chrono::steady_clock::now();
    const auto n = static_cast<std::size_t>(block_);
    std::vector<CgState> cells(n * n * static_cast<std::size_t>(lattice_.ntheta()),
                               CgState::kOffData);
    for (int t = 0; t < lattice_.ntheta(); ++t) {
      for (int ly = 0; ly < block_; ++ly) {
        for (int lx = 0; lx < block_; ++lx) {
          const CgCell cell{bxi * block_ + lx, byi * block_ + ly, t};
          if (!lattice_.contains(cell)) continue;
          cells[(static_cast<std::size_t>(t) * n + ly) * n + lx] =
              evaluate_cg_pose(*footmap_, *robot_, lattice_.centre(cell));
          if (!counted) ++cells_;
        }
      }
    }
    it = blocks_.emplace(key, std::move(cells)).first;
    seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  const int lx = c.ix % block_, ly = c.iy % block_;
  return it->second[(static_cast<std::size_t>(c.it) * block_ + ly) * block_ + lx];
}

}  // namespace talus
