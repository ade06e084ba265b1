#include "talus/core/terrain_generators.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>

#include <unsupported/Eigen/FFT>

#include "talus/core/error.hpp"

namespace talus {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

// ---------------------------------------------------------------------------
// Option validation. The messages name the option the caller actually set
// (e.g. "FractalTerrainOptions.shape.cellsize"), so they are assembled only on
// failure from an owner prefix and a field name.

std::string format_number(double value) {
  // Shortest round-trip form: prints 3.2 as "3.2", not "3.2000000000000002".
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

[[noreturn]] void throw_option_error(std::string_view owner, std::string_view field,
                                     std::string_view expectation, const std::string& got) {
  std::string message;
  message.append(owner).append(".").append(field).append(" must be ").append(expectation);
  message.append(", got ").append(got);
  throw InputError(message);
}

void require_finite(std::string_view owner, std::string_view field, double value) {
  if (!std::isfinite(value)) throw_option_error(owner, field, "finite", format_number(value));
}

void require_positive(std::string_view owner, std::string_view field, double value) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw_option_error(owner, field, "positive and finite", format_number(value));
  }
}

void require_non_negative(std::string_view owner, std::string_view field, double value) {
  if (!(value >= 0.0) || !std::isfinite(value)) {
    throw_option_error(owner, field, ">= 0 and finite", format_number(value));
  }
}

void validate_shape(const GridShape& shape, std::string_view owner) {
  if (shape.ncols < 2) throw_option_error(owner, "ncols", ">= 2", std::to_string(shape.ncols));
  if (shape.nrows < 2) throw_option_error(owner, "nrows", ">= 2", std::to_string(shape.nrows));
  require_positive(owner, "cellsize", shape.cellsize);
  require_finite(owner, "x_min", shape.x_min);
  require_finite(owner, "y_min", shape.y_min);
}

// ---------------------------------------------------------------------------
// Grid geometry shared by the generators.

double extent_x(const GridShape& shape) {
  return static_cast<double>(shape.ncols - 1) * shape.cellsize;
}

double extent_y(const GridShape& shape) {
  return static_cast<double>(shape.nrows - 1) * shape.cellsize;
}

/// Midpoint of the node domain, the reference point of the analytic surfaces.
Vec2 grid_centre(const GridShape& shape) {
  return {shape.x_min + 0.5 * extent_x(shape), shape.y_min + 0.5 * extent_y(shape)};
}

/// The four corner nodes, computed exactly as ElevationGrid::node_position
/// computes them, so a bound checked here holds for the generated nodes.
std::array<Vec2, 4> corner_nodes(const GridShape& shape) {
  const double x_max = shape.x_min + static_cast<double>(shape.ncols - 1) * shape.cellsize;
  const double y_max = shape.y_min + static_cast<double>(shape.nrows - 1) * shape.cellsize;
  return {Vec2(shape.x_min, shape.y_min), Vec2(x_max, shape.y_min), Vec2(shape.x_min, y_max),
          Vec2(x_max, y_max)};
}

ElevationGrid make_grid(const GridShape& shape) {
  return ElevationGrid(shape.ncols, shape.nrows, shape.cellsize, shape.x_min, shape.y_min);
}

/// Adds height(p) to every node p of the grid.
template <typename HeightFunction>
void add_to_nodes(ElevationGrid& grid, HeightFunction height) {
  for (std::size_t j = 0; j < grid.nrows(); ++j) {
    for (std::size_t i = 0; i < grid.ncols(); ++i) {
      grid.at(i, j) += height(grid.node_position(i, j));
    }
  }
}

/// Horizontal distance from the cylinder's axis, which runs through `centre`
/// along `direction`: the component of p - centre along the axis normal.
double distance_from_axis(const Vec2& p, const Vec2& centre, double direction) {
  const Vec2 normal(-std::sin(direction), std::cos(direction));
  return std::abs(normal.dot(p - centre));
}

// ---------------------------------------------------------------------------
// Reproducible randomness. std::mt19937_64's output sequence is fixed by the
// standard, but the standard distributions are not, so uniforms and normals
// are derived here from its raw 64-bit output. Each random ingredient of a
// terrain draws from its own stream, so that, e.g., adding peaks leaves the
// fractal part of a seed intact.

enum class RandomStream : std::uint64_t {
  kFractalPhases = 1,
  kUndulation = 2,
  kFractalPeaks = 3,
  kEldershawYimLayout = 4,
  kEldershawYimRoughness = 5,
};

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

class RandomSource {
 public:
  RandomSource(std::uint64_t seed, RandomStream stream)
      : engine_(splitmix64(splitmix64(seed) + static_cast<std::uint64_t>(stream))) {}

  /// Uniform on [0, 1) from the top 53 bits: every double is a multiple of 2^-53.
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }

  double uniform(double low, double high) { return low + (high - low) * uniform(); }

  /// Standard normal by the Box–Muller transform, using both of its outputs.
  double normal() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    const double u1 = 1.0 - uniform();  // (0, 1]: keeps the logarithm finite
    const double u2 = uniform();
    const double radius = std::sqrt(-2.0 * std::log(u1));
    spare_ = radius * std::sin(kTwoPi * u2);
    has_spare_ = true;
    return radius * std::cos(kTwoPi * u2);
  }

 private:
  std::mt19937_64 engine_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

// ---------------------------------------------------------------------------
// Fractal terrain.

/// In-place inverse 2-D DFT of an n x n row-major array, as 1-D transforms on
/// the rows and then on the columns.
void inverse_fft_2d(std::vector<std::complex<double>>& data, std::size_t n) {
  Eigen::FFT<double> fft;
  const auto length = static_cast<Eigen::Index>(n);
  std::vector<std::complex<double>> line_in(n);
  std::vector<std::complex<double>> line_out(n);
  for (std::size_t row = 0; row < n; ++row) {
    std::complex<double>* row_start = data.data() + row * n;
    fft.inv(line_out.data(), row_start, length);
    std::copy(line_out.begin(), line_out.end(), row_start);
  }
  for (std::size_t col = 0; col < n; ++col) {
    for (std::size_t row = 0; row < n; ++row) line_in[row] = data[row * n + col];
    fft.inv(line_out.data(), line_in.data(), length);
    for (std::size_t row = 0; row < n; ++row) data[row * n + col] = line_out[row];
  }
}

/// Signed frequency of DFT bin k of n: 0, 1, ..., n/2, -(n/2 - 1), ..., -1.
double signed_frequency(std::size_t k, std::size_t n) {
  return k <= n / 2 ? static_cast<double>(k) : -static_cast<double>(n - k);
}

// Fractional Brownian surface by spectral synthesis (Saupe, "Algorithms for
// random fractals", 1988). A fBm surface with Hurst exponent H has a radially
// symmetric power spectrum P(f) ∝ |f|^-(2H + 2), so the Fourier coefficients
// get amplitude |f|^-(H + 1) and independent uniform phases; the padded
// surface then has exactly that periodogram in every realisation. Saupe also randomises
// the amplitudes (Gaussian), which only adds realisation-to-realisation
// scatter in the spectrum, so they are kept deterministic here.
//
// The DFT makes the synthesised surface periodic. Synthesising on a square
// power-of-two grid at least twice the requested span in cells and keeping
// one corner stops the requested grid's opposite edges from being tied
// together and gives it wavelengths longer than itself, as real terrain has.
// Taking the real part of the complex result (rather than imposing Hermitian
// symmetry) is equivalent in distribution: every wavevector then carries the
// sum of two cosines with independent phases.
//
// The absolute scale of |f|^-(H+1) is meaningless on a finite grid, so the
// cropped result is rescaled to the requested peak-to-peak range with its
// lowest node at z = 0; the undulation and peaks are added on top afterwards,
// so height_scale stays the range of the fractal part alone.
void set_fractal_surface(ElevationGrid& grid, double fractal_dimension, double height_scale,
                         std::uint64_t seed) {
  if (height_scale == 0.0) return;  // the grid starts flat at 0

  const double hurst = 3.0 - fractal_dimension;
  const std::size_t span = std::max(grid.ncols(), grid.nrows()) - 1;
  const std::size_t n = std::bit_ceil(std::max<std::size_t>(2 * span, 2));

  RandomSource random(seed, RandomStream::kFractalPhases);
  std::vector<std::complex<double>> spectrum(n * n);
  for (std::size_t ky = 0; ky < n; ++ky) {
    const double fy = signed_frequency(ky, n);
    for (std::size_t kx = 0; kx < n; ++kx) {
      if (kx == 0 && ky == 0) continue;  // the mean is set by the rescaling
      const double fx = signed_frequency(kx, n);
      const double amplitude = std::pow(fx * fx + fy * fy, -0.5 * (hurst + 1.0));
      spectrum[ky * n + kx] = std::polar(amplitude, kTwoPi * random.uniform());
    }
  }
  inverse_fft_2d(spectrum, n);

  double lowest = std::numeric_limits<double>::infinity();
  double highest = -lowest;
  for (std::size_t j = 0; j < grid.nrows(); ++j) {
    for (std::size_t i = 0; i < grid.ncols(); ++i) {
      const double value = spectrum[j * n + i].real();
      lowest = std::min(lowest, value);
      highest = std::max(highest, value);
    }
  }
  if (!(highest > lowest)) return;  // degenerate: no relief to rescale
  const double scale = height_scale / (highest - lowest);
  for (std::size_t j = 0; j < grid.nrows(); ++j) {
    for (std::size_t i = 0; i < grid.ncols(); ++i) {
      grid.at(i, j) = (spectrum[j * n + i].real() - lowest) * scale;
    }
  }
}

// ---------------------------------------------------------------------------
// Eldershaw–Yim terrain.
//
// A recognisable stand-in for the test terrain of Eldershaw and Yim's Fig. 3,
// laid out in units of u = half the shorter side of the domain around the
// domain's centre c (x east, y north), so it scales with any grid:
//   - plateau: the square |dx|, |dy| <= 0.3 u at plateau_height. On the
//     west, north and south it falls to the ground over 0.25 u with a
//     smoothstep ramp (the west and north/south profiles multiply, so the
//     corners round off); on the east it ends in a sheer cliff, so the last
//     plateau node and the first ground node are one cell apart. One cliff
//     and three ramps is what makes the approach direction matter.
//   - peaks: nine cones of base radius 0.08 u (at least 1.5 cells) and height
//     peak_height, on a ring of radius 0.8 u around c, evenly spaced in angle
//     with seeded jitter of up to a quarter of the spacing in angle and
//     +-0.05 u in radius, so they never overlap each other or the plateau's
//     ramps. Each apex snaps to its nearest node, so every peak reaches its
//     full height whatever the resolution.
//   - roughness: independent Gaussian noise of standard deviation `roughness`
//     at every node, drawn from its own stream so the layout of a seed does
//     not depend on it.
constexpr double kPlateauHalfWidth = 0.3;
constexpr double kRampWidth = 0.25;
constexpr std::size_t kPeakCount = 9;
constexpr double kPeakRingRadius = 0.8;
constexpr double kPeakBaseRadius = 0.08;
constexpr double kPeakMinBaseRadiusCells = 1.5;
constexpr double kPeakAngleJitter = 0.25;  // fraction of the angular spacing
constexpr double kPeakRadiusJitter = 0.05;

double smoothstep(double t) {
  t = std::clamp(t, 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

/// 1 on the plateau, falling smoothly to 0 across a ramp of width `ramp`.
double ramp_profile(double offset_beyond_edge, double ramp) {
  return smoothstep(1.0 - offset_beyond_edge / ramp);
}

/// Node of `grid` nearest to p (p inside the domain or near it).
Vec2 nearest_node(const ElevationGrid& grid, const Vec2& p) {
  const auto snap = [](double value, double origin, double cellsize, std::size_t count) {
    const double index = std::round((value - origin) / cellsize);
    return static_cast<std::size_t>(std::clamp(index, 0.0, static_cast<double>(count - 1)));
  };
  return grid.node_position(snap(p.x(), grid.x_min(), grid.cellsize(), grid.ncols()),
                            snap(p.y(), grid.y_min(), grid.cellsize(), grid.nrows()));
}

/// The generated grid, or InputError when an option drove an elevation past
/// kMaxElevationMagnitude (or to inf/NaN): a result Talus could not read back.
ElevationGrid checked(ElevationGrid grid, const char* generator) {
  for (std::size_t j = 0; j < grid.nrows(); ++j) {
    for (std::size_t i = 0; i < grid.ncols(); ++i) {
      if (grid.valid(i, j) && !(std::abs(grid.at(i, j)) <= kMaxElevationMagnitude)) {
        std::ostringstream message;
        message << generator << " terrain: the options give elevation " << grid.at(i, j)
                << " m at node (" << i << ", " << j << "), beyond the supported magnitude of "
                << kMaxElevationMagnitude << " m; use smaller heights, curvatures or slopes";
        throw InputError(message.str());
      }
    }
  }
  return grid;
}

}  // namespace

// ---------------------------------------------------------------------------
// Validation.

void GridShape::validate() const {
  validate_shape(*this, "GridShape");
}

void FractalTerrainOptions::validate() const {
  constexpr std::string_view kOwner = "FractalTerrainOptions";
  validate_shape(shape, "FractalTerrainOptions.shape");
  if (!(fractal_dimension > 2.0 && fractal_dimension < 3.0)) {
    throw_option_error(kOwner, "fractal_dimension", "in (2, 3)", format_number(fractal_dimension));
  }
  require_non_negative(kOwner, "height_scale", height_scale);
  require_non_negative(kOwner, "undulation_amplitude", undulation_amplitude);
  require_non_negative(kOwner, "undulation_wavelength", undulation_wavelength);
  require_non_negative(kOwner, "peak_height", peak_height);
  require_positive(kOwner, "peak_radius", peak_radius);
  if (peaks > kMaxFractalPeaks) {
    throw_option_error(kOwner, "peaks", "at most " + std::to_string(kMaxFractalPeaks),
                       std::to_string(peaks));
  }
}

void PlaneOptions::validate() const {
  constexpr std::string_view kOwner = "PlaneOptions";
  validate_shape(shape, "PlaneOptions.shape");
  if (!(slope >= 0.0 && slope < std::numbers::pi / 2.0)) {
    throw_option_error(kOwner, "slope", "in [0, pi/2) rad", format_number(slope));
  }
  require_finite(kOwner, "aspect", aspect);
  require_finite(kOwner, "z0", z0);
}

void CylinderOptions::validate() const {
  constexpr std::string_view kOwner = "CylinderOptions";
  validate_shape(shape, "CylinderOptions.shape");
  require_positive(kOwner, "radius", radius);
  require_finite(kOwner, "axis_direction", axis_direction);
  require_finite(kOwner, "z0", z0);
  // The distance from the axis is linear along the grid, so a corner node is farthest.
  const Vec2 centre = grid_centre(shape);
  double farthest = 0.0;
  for (const Vec2& corner : corner_nodes(shape)) {
    farthest = std::max(farthest, distance_from_axis(corner, centre, axis_direction));
  }
  if (!(radius > farthest)) {
    throw_option_error(
        kOwner, "radius",
        "greater than the largest node distance from the axis, " + format_number(farthest) + " m",
        format_number(radius));
  }
}

void SphereCapOptions::validate() const {
  constexpr std::string_view kOwner = "SphereCapOptions";
  validate_shape(shape, "SphereCapOptions.shape");
  require_positive(kOwner, "radius", radius);
  require_finite(kOwner, "z0", z0);
  const Vec2 centre = grid_centre(shape);
  double farthest = 0.0;
  for (const Vec2& corner : corner_nodes(shape)) {
    farthest = std::max(farthest, (corner - centre).norm());
  }
  if (!(radius > farthest)) {
    throw_option_error(kOwner, "radius",
                       "greater than the largest node distance from the grid centre, " +
                           format_number(farthest) + " m",
                       format_number(radius));
  }
}

void GaussianHillsOptions::validate() const {
  constexpr std::string_view kOwner = "GaussianHillsOptions";
  validate_shape(shape, "GaussianHillsOptions.shape");
  require_finite(kOwner, "z0", z0);
  for (std::size_t k = 0; k < hills.size(); ++k) {
    const GaussianHill& hill = hills[k];
    const bool valid = hill.centre.allFinite() && std::isfinite(hill.height) && hill.sigma > 0.0 &&
                       std::isfinite(hill.sigma);
    if (valid) continue;
    // Only now is the indexed field name worth building.
    const std::string hill_field = "hills[" + std::to_string(k) + "]";
    require_finite(kOwner, hill_field + ".centre.x", hill.centre.x());
    require_finite(kOwner, hill_field + ".centre.y", hill.centre.y());
    require_finite(kOwner, hill_field + ".height", hill.height);
    require_positive(kOwner, hill_field + ".sigma", hill.sigma);
  }
}

void BowlOptions::validate() const {
  constexpr std::string_view kOwner = "BowlOptions";
  validate_shape(shape, "BowlOptions.shape");
  require_positive(kOwner, "curvature", curvature);
  require_finite(kOwner, "z0", z0);
}

void EldershawYimOptions::validate() const {
  constexpr std::string_view kOwner = "EldershawYimOptions";
  validate_shape(shape, "EldershawYimOptions.shape");
  require_positive(kOwner, "plateau_height", plateau_height);
  require_positive(kOwner, "peak_height", peak_height);
  require_non_negative(kOwner, "roughness", roughness);
}

// ---------------------------------------------------------------------------
// Generators.

ElevationGrid generate_fractal_terrain(const FractalTerrainOptions& options) {
  options.validate();
  const GridShape& shape = options.shape;
  ElevationGrid grid = make_grid(shape);
  set_fractal_surface(grid, options.fractal_dimension, options.height_scale, options.seed);

  if (options.undulation_amplitude > 0.0) {
    RandomSource random(options.seed, RandomStream::kUndulation);
    const double direction = kTwoPi * random.uniform();
    const Vec2 unit(std::cos(direction), std::sin(direction));
    const double wavelength = options.undulation_wavelength > 0.0
                                  ? options.undulation_wavelength
                                  : std::max(extent_x(shape), extent_y(shape));
    const double wavenumber = kTwoPi / wavelength;
    const Vec2 centre = grid_centre(shape);
    add_to_nodes(grid, [&](const Vec2& p) {
      return options.undulation_amplitude * std::sin(wavenumber * unit.dot(p - centre));
    });
  }

  if (options.peaks > 0 && options.peak_height > 0.0) {
    RandomSource random(options.seed, RandomStream::kFractalPeaks);
    const double inverse_two_variance = 1.0 / (2.0 * options.peak_radius * options.peak_radius);
    for (std::size_t k = 0; k < options.peaks; ++k) {
      const double x = random.uniform(grid.x_min(), grid.x_max());
      const double y = random.uniform(grid.y_min(), grid.y_max());
      const Vec2 peak_centre(x, y);
      add_to_nodes(grid, [&](const Vec2& p) {
        return options.peak_height *
               std::exp(-(p - peak_centre).squaredNorm() * inverse_two_variance);
      });
    }
  }
  return checked(std::move(grid), "fractal");
}

ElevationGrid generate_plane(const PlaneOptions& options) {
  options.validate();
  ElevationGrid grid = make_grid(options.shape);
  const Vec2 centre = grid_centre(options.shape);
  const Vec2 uphill(std::cos(options.aspect), std::sin(options.aspect));
  const double gradient = std::tan(options.slope);
  add_to_nodes(grid, [&](const Vec2& p) { return options.z0 + gradient * uphill.dot(p - centre); });
  return checked(std::move(grid), "plane");
}

ElevationGrid generate_cylinder(const CylinderOptions& options) {
  options.validate();
  ElevationGrid grid = make_grid(options.shape);
  const Vec2 centre = grid_centre(options.shape);
  const double r = options.radius;
  const double sign = options.crest ? 1.0 : -1.0;
  add_to_nodes(grid, [&](const Vec2& p) {
    const double d = distance_from_axis(p, centre, options.axis_direction);
    // max() only guards against rounding: validate() ensured d < R at the corners.
    return options.z0 + sign * (std::sqrt(std::max(0.0, r * r - d * d)) - r);
  });
  return checked(std::move(grid), "cylinder");
}

ElevationGrid generate_sphere_cap(const SphereCapOptions& options) {
  options.validate();
  ElevationGrid grid = make_grid(options.shape);
  const Vec2 centre = grid_centre(options.shape);
  const double r = options.radius;
  add_to_nodes(grid, [&](const Vec2& p) {
    const double rho_squared = (p - centre).squaredNorm();
    return options.z0 + std::sqrt(std::max(0.0, r * r - rho_squared)) - r;
  });
  return checked(std::move(grid), "sphere-cap");
}

ElevationGrid generate_gaussian_hills(const GaussianHillsOptions& options) {
  options.validate();
  ElevationGrid grid = make_grid(options.shape);
  std::vector<GaussianHill> hills = options.hills;
  if (hills.empty()) {
    // "Width" is the west-east extent of the node domain.
    const double width = extent_x(options.shape);
    hills.push_back({grid_centre(options.shape), 0.10 * width, 0.15 * width});
  }
  add_to_nodes(grid, [&](const Vec2& p) {
    double z = options.z0;
    for (const GaussianHill& hill : hills) {
      z += hill.height *
           std::exp(-(p - hill.centre).squaredNorm() / (2.0 * hill.sigma * hill.sigma));
    }
    return z;
  });
  return checked(std::move(grid), "gaussian-hills");
}

ElevationGrid generate_bowl(const BowlOptions& options) {
  options.validate();
  ElevationGrid grid = make_grid(options.shape);
  const Vec2 centre = grid_centre(options.shape);
  add_to_nodes(grid, [&](const Vec2& p) {
    return options.z0 + 0.5 * options.curvature * (p - centre).squaredNorm();
  });
  return checked(std::move(grid), "bowl");
}

ElevationGrid generate_eldershaw_yim(const EldershawYimOptions& options) {
  options.validate();
  const GridShape& shape = options.shape;
  ElevationGrid grid = make_grid(shape);
  const Vec2 centre = grid_centre(shape);
  const double unit = 0.5 * std::min(extent_x(shape), extent_y(shape));
  const double half_width = kPlateauHalfWidth * unit;
  const double ramp = kRampWidth * unit;

  add_to_nodes(grid, [&](const Vec2& p) {
    const Vec2 offset = p - centre;
    if (offset.x() > half_width) return 0.0;  // east of the cliff
    const double beyond_west = std::max(0.0, -offset.x() - half_width);
    const double beyond_north_south = std::max(0.0, std::abs(offset.y()) - half_width);
    return options.plateau_height * ramp_profile(beyond_west, ramp) *
           ramp_profile(beyond_north_south, ramp);
  });

  RandomSource layout(options.seed, RandomStream::kEldershawYimLayout);
  const double spacing = kTwoPi / static_cast<double>(kPeakCount);
  const double base_radius =
      std::max(kPeakBaseRadius * unit, kPeakMinBaseRadiusCells * shape.cellsize);
  for (std::size_t k = 0; k < kPeakCount; ++k) {
    const double angle =
        spacing * (static_cast<double>(k) + layout.uniform(-kPeakAngleJitter, kPeakAngleJitter));
    const double ring_radius =
        unit * (kPeakRingRadius + layout.uniform(-kPeakRadiusJitter, kPeakRadiusJitter));
    const Vec2 apex =
        nearest_node(grid, centre + ring_radius * Vec2(std::cos(angle), std::sin(angle)));
    add_to_nodes(grid, [&](const Vec2& p) {
      return options.peak_height * std::max(0.0, 1.0 - (p - apex).norm() / base_radius);
    });
  }

  if (options.roughness > 0.0) {
    RandomSource noise(options.seed, RandomStream::kEldershawYimRoughness);
    for (std::size_t j = 0; j < grid.nrows(); ++j) {
      for (std::size_t i = 0; i < grid.ncols(); ++i)
        grid.at(i, j) += options.roughness * noise.normal();
    }
  }
  return checked(std::move(grid), "eldershaw-yim");
}

}  // namespace talus
