#include "model/test_time_symmetry.h"

#include <stdexcept>
#include <string>

#include "dataset/selection/junction_selection.h"

namespace lc2wf {

std::vector<PlaneSymmetry> test_time_symmetries(int count) {
  // Ordered so that every prefix of 2 or 4 is a group: opposite views first, then mirrors, then quarter turns.
  static const std::array<PlaneSymmetry, 8> all{{{{1, 0, 0, 1}},
                                                 {{-1, 0, 0, -1}},
                                                 {{-1, 0, 0, 1}},
                                                 {{1, 0, 0, -1}},
                                                 {{0, -1, 1, 0}},
                                                 {{0, 1, -1, 0}},
                                                 {{0, 1, 1, 0}},
                                                 {{0, -1, -1, 0}}}};
  if (!JunctionSelectionOptions::valid_view_count(count))
    throw std::invalid_argument("test-time symmetries: " + std::to_string(count) + " is not 1, 2, 4 or 8");
  return {all.begin(), all.begin() + count};
}

void transform_patch_features(std::vector<float>& features, size_t features_per_slot, const PlaneSymmetry& s) {
  if (features_per_slot < 6 || features.size() % features_per_slot != 0)
    throw std::invalid_argument("transform_patch_features: " + std::to_string(features.size()) +
                                " floats are not slots of " + std::to_string(features_per_slot) + " with two 3-vectors");
  for (size_t at = 0; at < features.size(); at += features_per_slot) {
    s.apply(&features[at]);
    s.apply(&features[at + 3]);
  }
}

}  // namespace lc2wf
