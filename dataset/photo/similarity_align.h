// A similarity dst ~ s R src + t fitted by least squares (Umeyama) with a robust step: points whose residual
// exceeds outlier_factor x the median residual (and the floor) are left out and the fit repeated. Used to put
// COLMAP camera centres onto their GPS positions (metric scale and up in one step).
#pragma once

#include <string>
#include <vector>

#include "dataset/photo/metric_frame.h"

namespace lc2wf {

struct SimilarityFitOptions {
  double outlier_factor = 3.0;  // residual > factor x median -> left out (0 = keep every point)
  double outlier_floor = 0.0;   // never leave out a point closer than this (dst units): GPS noise is metres
  int rounds = 2;
  // The source points must span a plane: the second singular value of the centred points over the first
  // must exceed this, or they lie on one line and the rotation about it is unknown.
  double min_spread_ratio = 0.05;
  void Check() const;  // throws std::invalid_argument naming the field
};

struct SimilarityFit {
  Similarity transform;            // src -> dst
  std::vector<int> inliers;        // indices used in the last fit
  double rms_residual = 0;         // over the inliers, dst units
  double median_residual = 0;      // over every point, dst units
  double dst_spread = 0;           // RMS distance of the inliers' dst points from their mean: what the residual is small against
};

// Throws std::invalid_argument when the sizes differ, there are < 3 points, a point is not finite, or the
// source points lie on one line (or in one point).
// The plain least-squares similarity (Umeyama) of src[ids[k]] onto dst[ids[k]], no robust step: the one
// implementation behind fit_similarity and the camera-pose comparison of tools/colmap.
Similarity least_squares_similarity(const std::vector<Vec3>& src, const std::vector<Vec3>& dst, const std::vector<int>& ids);

SimilarityFit fit_similarity(const std::vector<Vec3>& src, const std::vector<Vec3>& dst, const SimilarityFitOptions& options = {});

}  // namespace lc2wf
