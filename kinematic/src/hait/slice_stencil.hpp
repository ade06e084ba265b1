#pragma once
// The entries of a θ-sliced placement table that a query (x, y, θ) blends:
// the four nodes of the terrain patch holding (x, y), bilinearly weighted, in
// the one or two slices around θ, linearly weighted. Shared by the nominal
// table and the uncertainty table, whose surfaces have the same layout
// (slice-major, then rows from the south, then columns).
#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>

#include "talus/core/ruled_terrain.hpp"

namespace talus::detail {

struct SliceStencil {
  int slices = 1;                                     ///< 1 (θ on a slice) or 2
  double t = 0.0;                                     ///< weight of the second slice
  std::array<std::array<std::size_t, 4>, 2> index{};  ///< per slice, the 4 node entries
  std::array<double, 4> weight{};                     ///< bilinear weights of the 4 nodes

  /// Σ weight · values[index] in slice q.
  template <class Values>
  double blend(const Values& values, int q) const {
    double sum = 0.0;
    for (int c = 0; c < 4; ++c) sum += weight[c] * values[index[q][c]];
    return sum;
  }
  /// The two slices' values blended linearly in θ.
  double in_theta(const double (&per_slice)[2]) const {
    return slices == 2 ? (1 - t) * per_slice[0] + t * per_slice[1] : per_slice[0];
  }
};

/// `p` must be inside the terrain (RuledTerrain::contains) and θ finite.
inline SliceStencil slice_stencil(const RuledTerrain& terrain, int n_slices, const Vec2& p,
                                  double theta) {
  SliceStencil out;
  const PatchLocation loc = terrain.locate(p);
  const std::size_t nc = terrain.grid().ncols(), nr = terrain.grid().nrows();
  const double turns = theta / (2.0 * std::numbers::pi);
  const double s = (turns - std::floor(turns)) * n_slices;
  int k0 = static_cast<int>(std::floor(s));
  out.t = s - k0;
  k0 %= n_slices;
  const int k1 = (k0 + 1) % n_slices;
  out.slices = out.t > 0.0 ? 2 : 1;
  const double a = loc.a, b = loc.b;
  out.weight = {(1 - a) * (1 - b), a * (1 - b), (1 - a) * b, a * b};
  for (int q = 0; q < out.slices; ++q) {
    const std::size_t base = static_cast<std::size_t>(q == 0 ? k0 : k1) * nr * nc;
    const std::size_t row = base + loc.j * nc + loc.i;
    out.index[q] = {row, row + 1, row + nc, row + nc + 1};
  }
  return out;
}

}  // namespace talus::detail
