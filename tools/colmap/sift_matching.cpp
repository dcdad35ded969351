#include "tools/colmap/sift_matching.h"

#include <Eigen/Core>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <ostream>
#include <stdexcept>
#include <string>

#include "core/util/atomic_file.h"

namespace lc2wf {
namespace {

using RowMatrix = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

Eigen::Map<const RowMatrix> descriptor_matrix(const ImageDescriptors& im) {
  return {im.descriptors.data(), im.rows, kSiftDimensions};
}

// Angle between unit descriptors from their dot product (rounding can push it past 1).
double angle_of(float dot) { return std::acos(std::clamp(static_cast<double>(dot), -1.0, 1.0)); }

// Rows of a scored against b at once: bounds the similarity block at 256 x |b| floats.
constexpr int64_t kRowBlock = 256;

// Largest and second-largest of row[0..n) and the first index of the largest. Eight independent lanes
// (element j goes to lane j % 8) keep the scan free of branches; the lanes are merged at the end, the
// lowest index winning a tie, as a plain left-to-right scan would.
void top_two(const float* row, int64_t n, float& first, float& second, int32_t& at) {
  constexpr int kLanes = 8;
  const float lowest = -std::numeric_limits<float>::infinity();
  float t1[kLanes], t2[kLanes];
  int32_t i1[kLanes];
  for (int l = 0; l < kLanes; ++l) t1[l] = t2[l] = lowest, i1[l] = -1;
  int64_t j = 0;
  for (; j + kLanes <= n; j += kLanes)
    for (int l = 0; l < kLanes; ++l) {
      const float s = row[j + l];
      const bool better = s > t1[l];
      t2[l] = better ? t1[l] : std::max(t2[l], s);
      i1[l] = better ? static_cast<int32_t>(j + l) : i1[l];
      t1[l] = better ? s : t1[l];
    }
  for (; j < n; ++j) {
    const int l = static_cast<int>(j % kLanes);
    const float s = row[j];
    if (s > t1[l]) t2[l] = t1[l], t1[l] = s, i1[l] = static_cast<int32_t>(j);
    else t2[l] = std::max(t2[l], s);
  }
  int win = 0;
  for (int l = 1; l < kLanes; ++l)
    if (t1[l] > t1[win] || (t1[l] == t1[win] && i1[l] >= 0 && (i1[win] < 0 || i1[l] < i1[win]))) win = l;
  first = t1[win], at = i1[win], second = t2[win];
  for (int l = 0; l < kLanes; ++l)
    if (l != win) second = std::max(second, t1[l]);
}

}  // namespace

void SiftMatchOptions::Check() const {
  if (!(max_ratio > 0 && max_ratio <= 1)) throw std::invalid_argument("SiftMatchOptions.max_ratio must be in (0, 1]");
  if (!(max_angle > 0 && max_angle <= M_PI)) throw std::invalid_argument("SiftMatchOptions.max_angle must be in (0, pi]");
  if (threads < 0) throw std::invalid_argument("SiftMatchOptions.threads must be >= 0");
}

FeatureMatches match_descriptors(const ImageDescriptors& a, const ImageDescriptors& b, const SiftMatchOptions& o) {
  FeatureMatches matches;
  if (a.rows == 0 || b.rows == 0) return matches;
  const auto A = descriptor_matrix(a), B = descriptor_matrix(b);
  const float lowest = -std::numeric_limits<float>::infinity();
  std::vector<int32_t> best(a.rows, -1), best_of_b(b.rows, -1);
  std::vector<float> dot1(a.rows, lowest), dot2(a.rows, lowest), dot_of_b(b.rows, lowest);
  RowMatrix S;
  for (int64_t r0 = 0; r0 < a.rows; r0 += kRowBlock) {
    const int64_t rows = std::min(kRowBlock, a.rows - r0);
    S.noalias() = A.middleRows(r0, rows) * B.transpose();
    for (int64_t i = 0; i < rows; ++i) {
      const int64_t ia = r0 + i;
      const float* row = S.data() + i * b.rows;
      // Selects instead of branches, so the compiler vectorises both scans.
      for (int64_t j = 0; j < b.rows; ++j) {
        const bool better = row[j] > dot_of_b[j];
        dot_of_b[j] = better ? row[j] : dot_of_b[j];
        best_of_b[j] = better ? static_cast<int32_t>(ia) : best_of_b[j];
      }
      top_two(row, b.rows, dot1[ia], dot2[ia], best[ia]);
    }
  }
  for (int64_t i = 0; i < a.rows; ++i) {
    const double first = angle_of(dot1[i]);
    // With one feature in b there is no second neighbour: the ratio test cannot fail.
    const double second = b.rows > 1 ? angle_of(dot2[i]) : M_PI;
    if (first > o.max_angle || !(first < o.max_ratio * second)) continue;
    if (o.cross_check && best_of_b[best[i]] != i) continue;
    matches.emplace_back(static_cast<int32_t>(i), best[i]);
  }
  return matches;
}

std::vector<std::pair<int, int>> image_pairs(int count, int sequential_overlap) {
  std::vector<std::pair<int, int>> pairs;
  for (int i = 0; i < count; ++i)
    for (int j = i + 1; j < count && (sequential_overlap <= 0 || j <= i + sequential_overlap); ++j) pairs.emplace_back(i, j);
  return pairs;
}

int64_t write_match_list(const std::vector<ImageDescriptors>& images, const std::vector<std::pair<int, int>>& pairs,
                         const SiftMatchOptions& options, const std::filesystem::path& out) {
  options.Check();
  for (const ImageDescriptors& im : images)
    if (im.name.empty() || im.name.find_first_of(" \t\r\n") != std::string::npos)
      throw std::invalid_argument("image name '" + im.name + "' cannot go into a COLMAP match list (empty or whitespace)");
  for (const auto& [i, j] : pairs)
    if (i < 0 || j < 0 || i >= static_cast<int>(images.size()) || j >= static_cast<int>(images.size()) || i == j)
      throw std::invalid_argument("image pair (" + std::to_string(i) + ", " + std::to_string(j) + ") out of range");
  std::vector<FeatureMatches> matched(pairs.size());
  const int threads = options.threads > 0 ? options.threads : 0;
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads > 0 ? threads : omp_get_max_threads())
  for (int64_t p = 0; p < static_cast<int64_t>(pairs.size()); ++p)
    matched[p] = match_descriptors(images[pairs[p].first], images[pairs[p].second], options);
  int64_t total = 0;
  write_file_atomically(out, [&](std::ostream& f) {
    for (size_t p = 0; p < pairs.size(); ++p) {
      f << images[pairs[p].first].name << ' ' << images[pairs[p].second].name << '\n';
      for (const auto& [ia, ib] : matched[p]) f << ia << ' ' << ib << '\n';
      f << '\n';
      total += static_cast<int64_t>(matched[p].size());
    }
  }, std::ios::out);
  return total;
}

}  // namespace lc2wf
