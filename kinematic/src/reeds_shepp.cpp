#include "talus/kinematic/reeds_shepp.hpp"

#include <ompl/base/spaces/ReedsSheppStateSpace.h>

#include <cmath>
#include <numbers>
#include <sstream>

#include "talus/core/error.hpp"

namespace talus {

namespace ob = ompl::base;

struct ReedsShepp::Impl {
  explicit Impl(double radius) : space(radius) {}
  ob::ReedsSheppStateSpace space;

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

}  // namespace

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
  require_finite(a, "start");
  require_finite(b, "goal");
  Impl::Pair p(impl_->space, a, b);
  return impl_->space.distance(p.from, p.to);
}

std::vector<ReedsSheppSegment> ReedsShepp::segments(const SE2Pose& a, const SE2Pose& b) const {
  require_finite(a, "start");
  require_finite(b, "goal");
  Impl::Pair p(impl_->space, a, b);
  const ob::ReedsSheppStateSpace::ReedsSheppPath path = impl_->space.reedsShepp(p.from, p.to);
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
