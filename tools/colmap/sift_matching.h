// Exact SIFT matching for COLMAP: mutual nearest neighbours that pass the ratio test, written as a COLMAP
// match list for its geometric verification (matches_importer). COLMAP 3.8's CPU matcher builds two FLANN
// kd-trees for every image pair (≈ 0.2 CPU-s per pair at 1,000 features); one product of the two descriptor
// matrices finds the exact neighbours for a small fraction of that.
#pragma once

#include <cstdint>
#include <filesystem>
#include <utility>
#include <vector>

#include "tools/colmap/colmap_database.h"

namespace lc2wf {

struct SiftMatchOptions {
  double max_ratio = 0.8;   // best angle < max_ratio x second-best angle (Lowe's test on descriptor angles)
  double max_angle = 0.7;   // radians between the unit descriptors of a match (COLMAP's max_distance)
  bool cross_check = true;  // each feature must be the other's nearest neighbour as well
  int threads = 0;          // image pairs matched at once; 0 = all cores
  void Check() const;
};

// (feature in a, feature in b), in the order of a's features.
using FeatureMatches = std::vector<std::pair<int32_t, int32_t>>;

FeatureMatches match_descriptors(const ImageDescriptors& a, const ImageDescriptors& b, const SiftMatchOptions& options);

// Image pairs (i, j), i < j, in list order: all of them, or with sequential_overlap > 0 only j <= i + overlap
// (photos taken in order).
std::vector<std::pair<int, int>> image_pairs(int count, int sequential_overlap);

// Matches the listed pairs of `images` and writes COLMAP's raw match list to `out`: per pair a line
// "name_a name_b", a line "index_a index_b" per match and a blank line. Returns the number of matches. The
// file does not depend on the thread count. Image names must not hold whitespace (the list's separator).
int64_t write_match_list(const std::vector<ImageDescriptors>& images, const std::vector<std::pair<int, int>>& pairs,
                         const SiftMatchOptions& options, const std::filesystem::path& out);

}  // namespace lc2wf
