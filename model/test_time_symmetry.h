// Test-time augmentation by the symmetries of the square about the vertical axis: a patch's features are
// vectors relative to its centre, so rotating them by 90° steps or mirroring them gives the network the
// same lines in another orientation (Roof-Image buildings come in every orientation, so each is in the
// training distribution). Averaging the class probabilities and the back-rotated offsets over the views
// evens out the network's orientation-dependent errors. The sample points and patches stay the same.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

namespace lc2wf {

// x' = m[0] x + m[1] y, y' = m[2] x + m[3] y, z' = z (a signed permutation; its inverse is its transpose).
struct PlaneSymmetry {
  std::array<int, 4> m{1, 0, 0, 1};

  template <class T>
  void apply(T* v) const {  // one 3-vector in place
    const T x = v[0], y = v[1];
    v[0] = static_cast<T>(m[0]) * x + static_cast<T>(m[1]) * y;
    v[1] = static_cast<T>(m[2]) * x + static_cast<T>(m[3]) * y;
  }
  template <class T>
  void apply_inverse(T* v) const {  // the transpose
    const T x = v[0], y = v[1];
    v[0] = static_cast<T>(m[0]) * x + static_cast<T>(m[2]) * y;
    v[1] = static_cast<T>(m[1]) * x + static_cast<T>(m[3]) * y;
  }
};

// The first `count` (1, 2, 4 or 8) of: identity, rotation by 180°, the two mirrors of x and y, rotations
// by 90° and 270°, the two diagonal mirrors. Throws std::invalid_argument for another count.
std::vector<PlaneSymmetry> test_time_symmetries(int count);

// Every slot of `features` (slots x features_per_slot floats) has its vectors at offsets 0 and 3 (a
// junction patch's [near - x, far - x, distance] or a pair patch's [near - m, far - m]): both transformed.
void transform_patch_features(std::vector<float>& features, size_t features_per_slot, const PlaneSymmetry& s);

}  // namespace lc2wf
