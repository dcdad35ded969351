#include "reconstruct/reconstruct_options.h"

#include <cmath>
#include <stdexcept>

namespace lc2wf {

void ReconstructOptions::Check() const {
  if (images.empty()) throw std::invalid_argument("ReconstructOptions.images is empty");
  if (weights.empty()) throw std::invalid_argument("ReconstructOptions.weights is empty");
  if (out.empty()) throw std::invalid_argument("ReconstructOptions.out is empty");
  if (threads < 0) throw std::invalid_argument("ReconstructOptions.threads must be >= 0");
  if (min_images < 3) throw std::invalid_argument("ReconstructOptions.min_images must be >= 3 (a line needs 3 views)");
  if (focal_35mm && (!(*focal_35mm > 0) || !std::isfinite(*focal_35mm)))
    throw std::invalid_argument("ReconstructOptions.focal_35mm must be > 0");
  if (intrinsics && !(intrinsics->allFinite() && (*intrinsics)(0) > 0 && (*intrinsics)(1) > 0))
    throw std::invalid_argument("ReconstructOptions.intrinsics: fx and fy must be > 0");
  if (frame.known_distance_m > 0 && (known_image_a.empty() || known_image_b.empty() || known_image_a == known_image_b))
    throw std::invalid_argument("ReconstructOptions: a known distance needs two different image names");
  if (min_gps_photos < 3) throw std::invalid_argument("ReconstructOptions.min_gps_photos must be >= 3");
  if (!(max_gps_residual_share > 0 && max_gps_residual_share <= 10))
    throw std::invalid_argument("ReconstructOptions.max_gps_residual_share must be in (0, 10]");
  gps_fit.Check();
  scale_search.Check();
  if (frame_max_supports < 3 || frame_min_lines < 1) throw std::invalid_argument("ReconstructOptions.frame_max_supports must be >= 3, frame_min_lines >= 1");
  colmap.Check();
  lsd.Check();
  triangulator.Check();
  confirmation.Check();
  MetricFrameOptions f = frame;
  f.known_view_a = f.known_view_b = -1;  // resolved from the image names later
  if (f.known_distance_m > 0) f.known_view_a = 0, f.known_view_b = 1;
  f.Check();
  post.Check();
}

}  // namespace lc2wf
