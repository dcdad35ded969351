// Hash-based lattice randoms and smooth value noise: pure functions of (position, seed), so every view and
// both renderers' texture code agree on a building's surfaces.
#pragma once

#include <cmath>
#include <cstdint>

#include "dataset/sampling/rng.h"

namespace lc2wf {

// Uniform [0,1) from an integer lattice cell.
inline double cell_random(int64_t i, int64_t j, uint64_t seed) {
  const uint64_t h = mix_seed(seed ^ mix_seed(static_cast<uint64_t>(i) * 0x632BE59BD9B4E019ull + static_cast<uint64_t>(j)));
  return static_cast<double>(h >> 11) * 0x1.0p-53;
}

// Smooth value noise in [0,1): smoothstep interpolation of the four surrounding cells.
inline double value_noise(double x, double y, uint64_t seed) {
  const double fx = std::floor(x), fy = std::floor(y);
  const int64_t ix = static_cast<int64_t>(fx), iy = static_cast<int64_t>(fy);
  double tx = x - fx, ty = y - fy;
  tx = tx * tx * (3 - 2 * tx);
  ty = ty * ty * (3 - 2 * ty);
  const double a = cell_random(ix, iy, seed), b = cell_random(ix + 1, iy, seed);
  const double c = cell_random(ix, iy + 1, seed), d = cell_random(ix + 1, iy + 1, seed);
  return (a * (1 - tx) + b * tx) * (1 - ty) + (c * (1 - tx) + d * tx) * ty;
}

// Mean of `octaves` value-noise layers of periods finest, 2 finest, 4 finest, ... (equal weights): detail
// at every scale from `finest` up that never repeats. In [0,1), mean 0.5; the standard deviation is about
// 0.2 / sqrt(octaves) (0.08 for 7 octaves).
inline double octave_noise(double x, double y, double finest, int octaves, uint64_t seed) {
  double sum = 0, period = finest;
  for (int k = 0; k < octaves; ++k, period *= 2) sum += value_noise(x / period, y / period, seed + 0x51ED27ull * k);
  return sum / octaves;
}

}  // namespace lc2wf
