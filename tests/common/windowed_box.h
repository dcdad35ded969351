// Hand-made line clouds of windowed buildings (z up, metres) for the tests of what reads a building's lines:
// its height (line_height.h) and its up (line_up.h), and a height model fitted on some of them.
#pragma once

#include <random>
#include <vector>

#include "dataset/geometry/geometry.h"
#include "dataset/photo/line_height.h"

namespace lc2wf::test {

// A box building of `storeys` storeys on a w x d footprint: eaves, base, corners, and on every wall a row of
// 1.2 x 1.3 m windows per storey (sill, lintel, two sides, ends jittered by triangulation noise).
inline std::vector<Segment3> windowed_box(int storeys, double storey_m, double w, double d, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.03);
  const double h = storeys * storey_m;
  std::vector<Segment3> s;
  const Vec3 corners[4] = {{0, 0, 0}, {w, 0, 0}, {w, d, 0}, {0, d, 0}};
  for (int c = 0; c < 4; ++c) {
    const Vec3 a = corners[c], b = corners[(c + 1) % 4], up(0, 0, h);
    s.push_back({a, b});
    s.push_back({a + up, b + up});
    s.push_back({a, a + up});
    const Vec3 along = (b - a).normalized();
    const double len = (b - a).norm();
    for (int k = 0; k < storeys; ++k)
      for (double x = 1.0; x + 1.2 < len - 0.5; x += 2.8) {
        const double sill = k * storey_m + 0.9, lintel = sill + 1.3;
        const Vec3 p = a + x * along, q = a + (x + 1.2) * along;
        for (double z : {sill, lintel}) s.push_back({p + Vec3(0, 0, z + noise(rng)), q + Vec3(0, 0, z + noise(rng))});
        for (const Vec3& side : {p, q}) s.push_back({side + Vec3(0, 0, sill + noise(rng)), side + Vec3(0, 0, lintel + noise(rng))});
      }
  }
  return s;
}


// One wall of windowed_box (along x at y = 0) as photos from the street triangulate it: its vertical lines
// (corners, window sides), the eaves and base, a quarter of the window sills and lintels (horizontal lines in
// the cameras' epipolar planes rarely triangulate), and ground lines in front of it (kerbs, cars, paving) unless
// `ground_lines` is false (a map of the facade alone).
inline std::vector<Segment3> street_facade(int storeys, double storey_m, double w, unsigned seed, bool ground_lines = true) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.03);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double h = storeys * storey_m;
  std::vector<Segment3> s = {{Vec3(0, 0, 0), Vec3(w, 0, 0)}, {Vec3(0, 0, h), Vec3(w, 0, h)},
                             {Vec3(0, 0, 0), Vec3(0, 0, h)}, {Vec3(w, 0, 0), Vec3(w, 0, h)}};
  int kept = 0;
  for (int k = 0; k < storeys; ++k)
    for (double x = 1.0; x + 1.2 < w - 0.5; x += 2.8) {
      const double sill = k * storey_m + 0.9, lintel = sill + 1.3;
      for (double side : {x, x + 1.2}) s.push_back({Vec3(side, 0, sill + noise(rng)), Vec3(side, 0, lintel + noise(rng))});
      for (double z : {sill, lintel})
        if (kept++ % 4 == 0) s.push_back({Vec3(x, 0, z + noise(rng)), Vec3(x + 1.2, 0, z + noise(rng))});
    }
  for (int g = 0; g < (ground_lines ? 12 : 0); ++g) {  // ground lines up to 8 m in front, along and across the street
    const Vec3 p(w * u(rng), -8.0 * u(rng), 0.02 * noise(rng));
    s.push_back({p, p + (g % 2 ? Vec3(1.5 + 3 * u(rng), 0, 0) : Vec3(0, -1 - 2 * u(rng), 0))});
  }
  return s;
}

// A height model fitted on metric, z-up street facades of 1-10 storeys and 9-31 m (seeds from `first_seed`), as
// lc2wf-fit-height fits one: for the tests of what reads a map's up and ground with it.
inline HeightModel street_facade_model(unsigned first_seed = 1) {
  std::vector<LineStatistics> clouds;
  std::vector<double> heights;
  unsigned seed = first_seed;
  for (int storeys : {1, 2, 3, 4, 5, 6, 8, 10})
    for (double w : {9.0, 16.0, 24.0, 31.0}) {
      clouds.push_back(line_statistics(street_facade(storeys, 3.0, w, seed++)));
      heights.push_back(clouds.back().height);
    }
  HeightFitOptions o;
  o.ks = {3};
  return fit_height_model(clouds, heights, o);
}

}  // namespace lc2wf::test
