#pragma once
/// @file
/// Admissibility of a configuration-space box (Dacre-Wright and Siméon, "Free
/// space representation for a mobile robot moving on a rough terrain", ICRA
/// 1993, §3). The robot is the Haït sprung-wheel rigid body (WheeledRobot,
/// placement.hpp) with a symmetric wheel layout; a configuration q = (x, y, θ)
/// is admissible (Definition 2) when its placement has |l_i| < L_max for every
/// wheel and (φ, ψ) in the stability box S = (−max_roll, max_roll) ×
/// (−max_pitch, max_pitch). Angles follow placement.hpp: R = Rz(θ) Ry(−ψ)
/// Rx(φ), roll φ > 0 raises the left side, pitch ψ > 0 raises the nose.
///
/// analyse_box() bounds every placement over the box from the elevation map:
/// contact regions R_i, the least-squares average plane P_a, the envelopes
/// δz_i^min/max, d0, max|A|, max|B|, min|C|, β_max, Δφ, Δψ, Δl_i; FREE iff
/// conditions (4) and (5) hold. Where the paper's bound is not sound for the
/// placement the project computes (placement.hpp), the bound is widened; every
/// such choice is listed at BoxAnalysis and in kinematic/README-style notes of
/// the closing report:
///  - R_i is the axis-aligned rectangle bounding the exact sweep (the paper:
///    "a polygon"), grown to whole terrain patches, because the bilinear
///    surface minus a plane has its extremes at patch corners;
///  - d_i − d0 is bounded with d0 = mean(d_j) written out (tighter than
///    d_i^max − d0^min and exact for that linear form); max|A| sums each
///    wheel's largest square (the paper takes the larger of two sums, which
///    can miss the maximum);
///  - β_max is the larger of the paper's 2 arctan[(√(K²+1) − 1)/K] and
///    arcsin(max|B| / min C): at the fixed point of the Haït placement the rest
///    plane is the least-squares plane of the contacts, so Σ l_i w_i = 0 and
///    sin β = B / C exactly;
///  - φ_a, ψ_a are taken over the whole θ interval (the paper: at θ_a only),
///    and the pitch half-width is β_max / cos Φ with Φ the largest |φ| (the
///    paper's cos β = cos(φ − φ_a) cos(ψ − ψ_a) does not hold for this
///    rotation order);
///  - l_i bounds use 1/cos β ∈ [1, 1/cos β_max] on the sign they need.
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "talus/core/ruled_terrain.hpp"
#include "talus/core/types.hpp"
#include "talus/kinematic/configuration_space.hpp"
#include "talus/kinematic/hait/placement.hpp"
#include "talus/kinematic/hait/robot.hpp"

namespace talus {

/// Throws InputError unless the wheel layout is symmetric about G in the
/// paper's sense (§3.3.2): |Σ u_i|, |Σ v_i| and |Σ u_i v_i| at most
/// `tolerance` times the layout's scale (Σ u_i² + v_i²). The message names the
/// failing sum and its value.
void require_symmetric_wheels(const WheeledRobot& robot, double tolerance = 1e-9);

/// load_robot(path), which must be a `type: wheeled` robot with a symmetric
/// layout (require_symmetric_wheels); InputError naming the file otherwise.
WheeledRobot load_dacre_wright_robot(const std::string& path);

/// Definition 2 on one placement: usable, every |l_i| < L_max, |φ| < max_roll,
/// |ψ| < max_pitch.
bool admissible(const WheeledRobot& robot, const RobotPlacement& placement);

/// A box [x1, x2] × [y1, y2] × [θ1, θ2] of configuration space [m, m, rad].
struct CsBox {
  double x1 = 0.0, x2 = 0.0;
  double y1 = 0.0, y2 = 0.0;
  double theta1 = 0.0, theta2 = 0.0;
  bool contains(const SE2Pose& q) const;
};

/// Running least-squares plane z = a x + b y + c (§3.2.2): accumulates AᵀA and
/// AᵀB point by point, solves the 3 × 3 system at the end. Coordinates are
/// taken relative to `origin` (the box centre) for conditioning.
class AveragePlaneAccumulator {
 public:
  explicit AveragePlaneAccumulator(Vec2 origin = Vec2::Zero()) : origin_(origin) {}
  /// Adds the row (x, y, 1) of A and z of B: AᵀA += rowᵀ row, AᵀB += rowᵀ z.
  void add(double x, double y, double z) {
    const double u = x - origin_.x(), v = y - origin_.y();
    suu_ += u * u;
    suv_ += u * v;
    su_ += u;
    svv_ += v * v;
    sv_ += v;
    suz_ += u * z;
    svz_ += v * z;
    sz_ += z;
    ++count_;
  }
  /// Adds the sums of `count` points at once: Σu, Σv, Σu², Σuv, Σv², Σz,
  /// Σuz, Σvz with u, v relative to the origin (as add() would accumulate).
  void add_sums(std::size_t count, double su, double sv, double suu, double suv, double svv,
                double sz, double suz, double svz) {
    su_ += su;
    sv_ += sv;
    suu_ += suu;
    suv_ += suv;
    svv_ += svv;
    sz_ += sz;
    suz_ += suz;
    svz_ += svz;
    count_ += count;
  }
  const Vec2& origin() const { return origin_; }
  std::size_t count() const { return count_; }
  /// AᵀA (symmetric) and AᵀB in coordinates relative to the origin.
  Mat3 ata() const;
  Vec3 atb() const { return {suz_, svz_, sz_}; }
  /// (a, b, c) in world coordinates; false if fewer than 3 points or the
  /// points are collinear (then `abc` is untouched).
  bool solve(Vec3& abc) const;

 private:
  Vec2 origin_;
  double suu_ = 0, suv_ = 0, su_ = 0, svv_ = 0, sv_ = 0, suz_ = 0, svz_ = 0, sz_ = 0;
  std::size_t count_ = 0;
};

/// Summed-area tables (integral images) of an elevation grid for the average
/// plane of §3.2.2: the sums over any node rectangle of z, i·z and j·z (node
/// indices i, j; z taken relative to a reference elevation for conditioning)
/// and of NODATA nodes, each in O(1); the index moments Σi, Σi², Σij, … are
/// closed forms. accumulate() equals adding every node of the rectangle to an
/// AveragePlaneAccumulator up to rounding (about 1e-13 relative on the
/// project's maps). Memory: 4 doubles per node. Holds a reference to the
/// terrain, which must outlive it.
class ElevationSums {
 public:
  explicit ElevationSums(const RuledTerrain& terrain);
  const RuledTerrain& terrain() const { return terrain_; }
  /// Adds the nodes (i, j), i in [i_lo, i_hi], j in [j_lo, j_hi] (inside the
  /// grid, i_lo <= i_hi, j_lo <= j_hi) to `acc`; false, adding nothing, if one
  /// of them is NODATA.
  bool accumulate(long i_lo, long i_hi, long j_lo, long j_hi, AveragePlaneAccumulator& acc) const;

 private:
  double at(const std::vector<double>& t, long i, long j) const {
    return t[static_cast<std::size_t>(j) * stride_ + static_cast<std::size_t>(i)];
  }
  /// Σ over the rectangle of table t (prefix sums with a zero first row and column).
  double rect(const std::vector<double>& t, long i_lo, long i_hi, long j_lo, long j_hi) const {
    return at(t, i_hi + 1, j_hi + 1) - at(t, i_lo, j_hi + 1) - at(t, i_hi + 1, j_lo) +
           at(t, i_lo, j_lo);
  }
  const RuledTerrain& terrain_;
  std::size_t stride_ = 0;
  double z_ref_ = 0.0;
  std::vector<double> z_, iz_, jz_, invalid_;
};

/// Options of analyse_box.
struct BoxAnalysisOptions {
  /// Extra passes that recompute the contact regions from the placement domain
  /// Δr found by the previous pass (intersected with Δr0; every placement in
  /// Δr0 stays inside), then the envelopes and the bounds again (>= 0).
  int refinements = 1;
  /// Throws InputError naming the field.
  void validate() const;
};

/// Why a box is not FREE (the first reason met), or kFree.
enum class BoxVerdict {
  kFree,             ///< conditions (4) and (5) hold: every configuration is admissible
  kOffMap,           ///< a contact region leaves the map or touches NODATA
  kDegeneratePlane,  ///< too few / collinear points for the average plane
  kNoBetaBound,      ///< max|A| >= min|C| or max|B| >= min C: β is not bounded
  kAttitude,         ///< Δφ × Δψ is not inside S (condition 5)
  kSpring,           ///< some Δl_i is not inside (−L_max, L_max) (condition 4)
};
/// "free", "off_map", "degenerate_plane", "no_beta_bound", "attitude", "spring".
const char* to_string(BoxVerdict verdict);

/// A closed interval of the analysis.
struct Range {
  double lo = 0.0;
  double hi = 0.0;
};

/// Everything one analysis computed (the last pass).
struct BoxAnalysis {
  BoxVerdict verdict = BoxVerdict::kOffMap;
  bool free() const { return verdict == BoxVerdict::kFree; }
  int passes = 0;  ///< passes made (1 + refinements used)
  int wheel_count = 0;
  std::array<Range, WheeledRobot::kMaxWheels> region_x{};  ///< R_i, x [m] (node-aligned)
  std::array<Range, WheeledRobot::kMaxWheels> region_y{};  ///< R_i, y [m]
  std::size_t points = 0;     ///< elevation points gathered for P_a (over all regions)
  Vec3 plane = Vec3::Zero();  ///< P_a: (a, b, c), z = a x + b y + c
  std::array<Range, WheeledRobot::kMaxWheels> dz{};  ///< δz_i^min, δz_i^max [m]
  Range d0;                                          ///< d0^min, d0^max [m]
  double max_a = 0.0;                                ///< max|A| [m²]
  double max_b = 0.0;                                ///< max|B| [m²]
  double min_c = 0.0;                                ///< min|C| [m²]
  double beta_paper = 0.0;  ///< the paper's 2 arctan[(√(K²+1) − 1)/K] [rad]
  double beta_max = 0.0;    ///< the bound used (see the file comment) [rad]
  Range roll;               ///< Δφ [rad]
  Range pitch;              ///< Δψ [rad]
  std::array<Range, WheeledRobot::kMaxWheels> extension{};  ///< Δl_i [m]
};

/// §3: analyses `box` for `robot` (symmetric, validated) on `terrain`.
/// Deterministic; no exceptions for any box (an empty or inverted box is
/// treated as its hull). Throws InputError for invalid options.
BoxAnalysis analyse_box(const WheeledRobot& robot, const RuledTerrain& terrain, const CsBox& box,
                        const BoxAnalysisOptions& options = {});
/// The same with the average plane's sums read from `sums` (built once per
/// terrain) instead of added node by node: equal up to rounding (the verdicts
/// of the 64 × 64 experiment map's whole octree are identical; see the tests).
/// What ConfigurationOctree uses.
BoxAnalysis analyse_box(const WheeledRobot& robot, const ElevationSums& sums, const CsBox& box,
                        const BoxAnalysisOptions& options = {});

/// β from K: 2 arctan[−(1 − √(K² + 1))/K] (0 for K = 0), the paper's β_max.
double paper_beta_max(double k);

}  // namespace talus
