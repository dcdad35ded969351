// Reads the SIFT descriptors COLMAP's feature_extractor stored in its SQLite database, for our own matcher.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace lc2wf {

constexpr int kSiftDimensions = 128;

struct ImageDescriptors {
  int64_t image_id = 0;
  std::string name;               // as COLMAP stored it (relative to its image folder)
  int64_t rows = 0;               // features
  std::vector<float> descriptors;  // rows x 128, each row of unit length (an all-zero row stays zero)
};

// Every image that has descriptors, in name order. Throws std::runtime_error naming the database and the
// image when the file cannot be opened, a table is missing, or a descriptor blob does not hold rows x 128
// bytes.
std::vector<ImageDescriptors> read_colmap_descriptors(const std::filesystem::path& database);

}  // namespace lc2wf
