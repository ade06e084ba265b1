#include "talus/kinematic/reeds_shepp.hpp"

#include <ompl/base/spaces/ReedsSheppStateSpace.h>

#include <cmath>
#include <numbers>
#include <sstream>

#include "talus/core/error.hpp"

namespace talus {

namespace ob = ompl::base;

struct ReedsShepp::Impl {
  explicit Impl(double r) : space(r), radius(r) {}
  ob::ReedsSheppStateSpace space;
  double radius;

  /// The shortest word a -> b: OMPL's, or a CSC word OMPL dropped by round-off.
  ob::ReedsSheppStateSpace::ReedsSheppPath shortest(const SE2Pose& a, const SE2Pose& b) const;

  /// Owns two OMPL SE(2) states for the duration of one query.
  struct Pair {
    explicit Pair(const ob::ReedsSheppStateSpace& s, const SE2Pose& a, const SE2Pose& b)
        : space(s), from(s.allocState()), to(s.allocState()) {
      set(from, a);
      set(to, b);
    }
    ~Pair() {
      space.freeState(from);
      space.freeState(to);
    }
    Pair(const Pair&) = delete;
    Pair& operator=(const Pair&) = delete;
    static void set(ob::State* s, const SE2Pose& q) {
      auto* se2 = s->as<ob::SE2StateSpace::StateType>();
      se2->setXY(q.x, q.y);
      se2->setYaw(q.theta);
    }
    const ob::ReedsSheppStateSpace& space;
    ob::State* from;
    ob::State* to;
  };
};

namespace {

void require_finite(const SE2Pose& q, const char* what) {
  if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.theta)) {
    std::ostringstream msg;
    msg << "ReedsShepp: " << what << " pose (" << q.x << ", " << q.y << ", " << q.theta
        << ") is not finite";
    throw InputError(msg.str());
  }
}

// OMPL 1.5 accepts a word only if each of its lengths is >= -1e-14 or so
// (ZERO = 10 eps, in units of the radius). Where the shortest word has a
// (near) zero-length arc, as every straight or straight-then-arc connection
// has, round-off of the end pose decides: with the wrong sign OMPL drops the
// word and returns a longer one (a 0.034 m straight reverse at radius 0.9
// came back as a 0.082 m four-arc curve). The CSC words are re-solved here
// with a round-off tolerance, lengths clamped at 0, and kept if shorter.
using RSType = ob::ReedsSheppStateSpace::ReedsSheppPathSegmentType;
constexpr RSType kLSL[5] = {ob::ReedsSheppStateSpace::RS_LEFT,
                            ob::ReedsSheppStateSpace::RS_STRAIGHT,
                            ob::ReedsSheppStateSpace::RS_LEFT, ob::ReedsSheppStateSpace::RS_NOP,
                            ob::ReedsSheppStateSpace::RS_NOP};
constexpr RSType kRSR[5] = {ob::ReedsSheppStateSpace::RS_RIGHT,
                            ob::ReedsSheppStateSpace::RS_STRAIGHT,
                            ob::ReedsSheppStateSpace::RS_RIGHT, ob::ReedsSheppStateSpace::RS_NOP,
                            ob::ReedsSheppStateSpace::RS_NOP};
constexpr RSType kLSR[5] = {ob::ReedsSheppStateSpace::RS_LEFT,
                            ob::ReedsSheppStateSpace::RS_STRAIGHT,
                            ob::ReedsSheppStateSpace::RS_RIGHT, ob::ReedsSheppStateSpace::RS_NOP,
                            ob::ReedsSheppStateSpace::RS_NOP};
constexpr RSType kRSL[5] = {ob::ReedsSheppStateSpace::RS_RIGHT,
                            ob::ReedsSheppStateSpace::RS_STRAIGHT,
                            ob::ReedsSheppStateSpace::RS_LEFT, ob::ReedsSheppStateSpace::RS_NOP,
                            ob::ReedsSheppStateSpace::RS_NOP};
constexpr double kRoundOff = 1e-9;  // [radii]

double mod2pi(double x) {
  return std::remainder(x, 2.0 * std::numbers::pi);
}

// Reeds & Shepp's formulas 8.1 (L+S+L+) and 8.2 (L+S+R+) as OMPL has them.
bool lp_sp_lp(double x, double y, double phi, double& t, double& u, double& v) {
  const double px = x - std::sin(phi), py = y - 1.0 + std::cos(phi);
  u = std::hypot(px, py);
  t = std::atan2(py, px);
  v = mod2pi(phi - t);
  return t >= -kRoundOff && v >= -kRoundOff;
}
bool lp_sp_rp(double x, double y, double phi, double& t, double& u, double& v) {
  const double px = x + std::sin(phi), py = y - 1.0 - std::cos(phi);
  const double u1 = px * px + py * py;
  if (u1 < 4.0) return false;
  u = std::sqrt(u1 - 4.0);
  t = mod2pi(std::atan2(py, px) + std::atan2(2.0, u));
  v = mod2pi(t - phi);
  return t >= -kRoundOff && v >= -kRoundOff;
}

/// `path` replaced by the shortest CSC word (time-flipped and reflected
/// variants included) if one is shorter, for the relative pose (x, y, phi) in
/// radii.
void tolerant_csc(double x, double y, double phi, ob::ReedsSheppStateSpace::ReedsSheppPath& path) {
  double t, u, v;
  const auto keep = [&](const RSType* type, double sign) {
    t = std::max(t, 0.0);
    v = std::max(v, 0.0);
    if (t + u + v < path.length() - 1e-12) {
      path = ob::ReedsSheppStateSpace::ReedsSheppPath(type, sign * t, sign * u, sign * v);
    }
  };
  if (lp_sp_lp(x, y, phi, t, u, v)) keep(kLSL, 1.0);
  if (lp_sp_lp(-x, y, -phi, t, u, v)) keep(kLSL, -1.0);  // time flip
  if (lp_sp_lp(x, -y, -phi, t, u, v)) keep(kRSR, 1.0);   // reflect
  if (lp_sp_lp(-x, -y, phi, t, u, v)) keep(kRSR, -1.0);  // both
  if (lp_sp_rp(x, y, phi, t, u, v)) keep(kLSR, 1.0);
  if (lp_sp_rp(-x, y, -phi, t, u, v)) keep(kLSR, -1.0);
  if (lp_sp_rp(x, -y, -phi, t, u, v)) keep(kRSL, 1.0);
  if (lp_sp_rp(-x, -y, phi, t, u, v)) keep(kRSL, -1.0);
}

}  // namespace

ob::ReedsSheppStateSpace::ReedsSheppPath ReedsShepp::Impl::shortest(const SE2Pose& a,
                                                                    const SE2Pose& b) const {
  require_finite(a, "start");
  require_finite(b, "goal");
  Pair p(space, a, b);
  ob::ReedsSheppStateSpace::ReedsSheppPath path = space.reedsShepp(p.from, p.to);
  // The relative pose as OMPL's reedsShepp(state1, state2) computes it.
  const double dx = b.x - a.x, dy = b.y - a.y, c = std::cos(a.theta), s = std::sin(a.theta);
  tolerant_csc((c * dx + s * dy) / radius, (-s * dx + c * dy) / radius, b.theta - a.theta, path);
  return path;
}

ReedsShepp::ReedsShepp(double radius) : radius_(radius) {
  if (!(radius > 0.0) || !std::isfinite(radius)) {
    std::ostringstream msg;
    msg << "ReedsShepp: turning radius must be positive and finite, got " << radius;
    throw InputError(msg.str());
  }
  impl_ = std::make_unique<Impl>(radius);
}

ReedsShepp::~ReedsShepp() = default;
ReedsShepp::ReedsShepp(ReedsShepp&&) noexcept = default;
ReedsShepp& ReedsShepp::operator=(ReedsShepp&&) noexcept = default;

double ReedsShepp::distance(const SE2Pose& a, const SE2Pose& b) const {
  return radius_ * impl_->shortest(a, b).length();
}

std::vector<ReedsSheppSegment> ReedsShepp::segments(const SE2Pose& a, const SE2Pose& b) const {
  const ob::ReedsSheppStateSpace::ReedsSheppPath path = impl_->shortest(a, b);
  std::vector<ReedsSheppSegment> out;
  for (int k = 0; k < 5; ++k) {
    const double len = path.length_[k];  // signed, in units of the radius; < 0 = reverse
    // OMPL leaves round-off lengths (~1e-16) where a word degenerates; drop them.
    if (path.type_[k] == ob::ReedsSheppStateSpace::RS_NOP || std::abs(len) < 1e-10) continue;
    const int v = len > 0.0 ? 1 : -1;
    int omega = 0;
    // A left arc turns the heading by +len (counter-clockwise forwards,
    // clockwise in reverse), a right arc by −len (OMPL's interpolate()).
    if (path.type_[k] == ob::ReedsSheppStateSpace::RS_LEFT) omega = v;
    if (path.type_[k] == ob::ReedsSheppStateSpace::RS_RIGHT) omega = -v;
    out.push_back({Control{v, omega}, std::abs(len) * radius_});
  }
  return out;
}

std::vector<PathPoint> ReedsShepp::sample(const SE2Pose& a, const SE2Pose& b,
                                          double spacing) const {
  if (!(spacing > 0.0) || !std::isfinite(spacing)) {
    std::ostringstream msg;
    msg << "ReedsShepp::sample: spacing must be positive and finite, got " << spacing;
    throw InputError(msg.str());
  }
  std::vector<PathPoint> out{{a, Control{}}};
  SE2Pose start = a;
  for (const ReedsSheppSegment& seg : segments(a, b)) {
    const int n = std::max(1, static_cast<int>(std::ceil(seg.length / spacing - 1e-9)));
    // Each sample from the segment's start, so rounding does not accumulate.
    for (int k = 1; k <= n; ++k) {
      out.push_back({apply_control(start, seg.control, seg.length * k / n, radius_), seg.control});
    }
    start = out.back().pose;
  }
  const SE2Pose& end = out.back().pose;
  const double miss =
      std::max(std::hypot(end.x - b.x, end.y - b.y),
               std::abs(std::remainder(end.theta - b.theta, 2.0 * std::numbers::pi)));
  if (miss > 1e-6) {
    std::ostringstream msg;
    msg << "ReedsShepp::sample: the curve from (" << a.x << ", " << a.y << ", " << a.theta
        << ") ends " << miss << " away from (" << b.x << ", " << b.y << ", " << b.theta << ")";
    throw SolverError(msg.str());
  }
  out.back().pose = b;  // exact end
  return out;
}

SE2Pose ReedsShepp::ompl_interpolate(const SE2Pose& a, const SE2Pose& b, double t) const {
  Impl::Pair p(impl_->space, a, b);
  ob::State* s = impl_->space.allocState();
  impl_->space.interpolate(p.from, p.to, t, s);
  const auto* se2 = s->as<ob::SE2StateSpace::StateType>();
  const SE2Pose q{se2->getX(), se2->getY(), se2->getYaw()};
  impl_->space.freeState(s);
  return q;
}

}  // namespace talus
