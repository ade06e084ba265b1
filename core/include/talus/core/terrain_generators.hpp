#pragma once
/// @file
/// Seeded, reproducible terrain generators: the fractal rough terrain of the
/// Iagnemma–Shimoda–Shiller study, analytic surfaces with known geometry for
/// tests, and the Eldershaw–Yim style legged-robot test terrain. Every
/// generator returns an ElevationGrid whose south-west node is at the options'
/// (x_min, y_min); the same options (and seed) always give the same grid, on
/// any machine.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "talus/core/elevation_grid.hpp"

namespace talus {

/// Size and placement of a generated grid.
struct GridShape {
  std::size_t ncols = 129;  ///< nodes west to east (>= 2)
  std::size_t nrows = 129;  ///< nodes south to north (>= 2)
  double cellsize = 1.0;    ///< node spacing [m] (> 0)
  double x_min = 0.0;       ///< x of the south-west node [m]
  double y_min = 0.0;       ///< y of the south-west node [m]
  /// Throws InputError naming the offending field.
  void validate() const;
};

/// Fractional Brownian surface by spectral synthesis, optionally with a gross
/// undulation and discrete peaks (Iagnemma, Shimoda, Shiller, IROS 2008, §V).
/// Defaults reproduce that study for a 0.12 m wheel: D = 2.05, spacing 2 wheel
/// diameters (0.24 m), height scale 35 wheel diameters (4.2 m).
/// Most peaks a fractal terrain takes: each one visits every node.
inline constexpr std::size_t kMaxFractalPeaks = 100'000;

struct FractalTerrainOptions {
  GridShape shape{129, 129, 0.24, 0.0, 0.0};
  double fractal_dimension = 2.05;     ///< D in (2, 3); Hurst exponent H = 3 - D
  double height_scale = 4.2;           ///< peak-to-peak range of the fractal part [m] (>= 0)
  double undulation_amplitude = 0.0;   ///< amplitude of the gross undulation [m] (>= 0)
  double undulation_wavelength = 0.0;  ///< its wavelength [m]; 0 = the grid's longer side
  std::size_t peaks = 0;               ///< number of discrete peaks added (<= kMaxFractalPeaks)
  double peak_height = 0.0;            ///< height of each peak [m] (>= 0)
  double peak_radius = 1.0;            ///< Gaussian radius (standard deviation) of a peak [m] (> 0)
  std::uint64_t seed = 1;              ///< random seed
  /// Throws InputError naming the offending field.
  void validate() const;
};
ElevationGrid generate_fractal_terrain(const FractalTerrainOptions& options);

/// Plane z = z0 + tan(slope) * (distance uphill), rising towards the compass
/// direction `aspect` (radians, counter-clockwise from +x: 0 rises to the east).
struct PlaneOptions {
  GridShape shape;
  double slope = 0.0;   ///< inclination [rad], in [0, pi/2)
  double aspect = 0.0;  ///< direction of steepest ascent [rad, CCW from +x]
  double z0 = 0.0;      ///< elevation at the grid's centre [m]
  void validate() const;
};
ElevationGrid generate_plane(const PlaneOptions& options);

/// Circular cylinder of radius R with axis horizontal along `axis_direction`
/// through the grid's centre: a crest z = zc + sqrt(R^2 - d^2) - R, or a dip
/// z = zc - (sqrt(R^2 - d^2) - R), where d is the horizontal distance from the
/// axis. Requires d < R over the whole grid.
struct CylinderOptions {
  GridShape shape;
  double radius = 100.0;        ///< R [m] (> 0)
  double axis_direction = 0.0;  ///< axis direction [rad, CCW from +x]
  bool crest = true;            ///< true: convex up (crest); false: concave up (dip)
  double z0 = 0.0;              ///< elevation on the axis [m]
  void validate() const;
};
ElevationGrid generate_cylinder(const CylinderOptions& options);

/// Spherical cap of radius R centred over the grid's centre:
/// z = z0 + sqrt(R^2 - rho^2) - R (rho = horizontal distance from the centre).
/// Requires rho < R over the whole grid.
struct SphereCapOptions {
  GridShape shape;
  double radius = 100.0;  ///< R [m] (> 0)
  double z0 = 0.0;        ///< elevation at the top [m]
  void validate() const;
};
ElevationGrid generate_sphere_cap(const SphereCapOptions& options);

/// One Gaussian hill: height * exp(-|p - centre|^2 / (2 sigma^2)).
struct GaussianHill {
  Vec2 centre = Vec2::Zero();  ///< [m]
  double height = 1.0;         ///< [m], may be negative (a pit)
  double sigma = 1.0;          ///< [m] (> 0)
};
/// Sum of Gaussian hills over a flat base at z0.
struct GaussianHillsOptions {
  GridShape shape;
  std::vector<GaussianHill> hills;  ///< empty = one hill at the centre, height 10 % of the
                                    ///< grid's width, sigma 15 % of it
  double z0 = 0.0;
  void validate() const;
};
ElevationGrid generate_gaussian_hills(const GaussianHillsOptions& options);

/// Paraboloid bowl z = z0 + curvature/2 * rho^2, rho from the grid's centre.
struct BowlOptions {
  GridShape shape;
  double curvature = 0.01;  ///< second derivative at the centre [1/m] (> 0)
  double z0 = 0.0;
  void validate() const;
};
ElevationGrid generate_bowl(const BowlOptions& options);

/// Eldershaw–Yim style test terrain (ICRA 2001, Fig. 3): a raised central
/// plateau with a sheer cliff on one side and ramps elsewhere, nine sharp
/// peaks around it, and low-amplitude seeded roughness.
struct EldershawYimOptions {
  GridShape shape{101, 101, 0.1, 0.0, 0.0};
  double plateau_height = 1.0;  ///< [m] (> 0)
  double peak_height = 1.5;     ///< [m] (> 0)
  double roughness = 0.02;      ///< standard deviation of the roughness [m] (>= 0)
  std::uint64_t seed = 1;
  void validate() const;
};
ElevationGrid generate_eldershaw_yim(const EldershawYimOptions& options);

}  // namespace talus
