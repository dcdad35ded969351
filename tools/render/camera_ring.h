// Oblique views around a building: cameras on rings at several elevations, all aimed near the building
// centre, each placed at the smallest distance that keeps every mesh vertex inside the frame. The same
// ring, cut to a sector in front of one or two facades and lowered to a camera height, gives the street
// captures (tools/render/capture_kind.h).
#pragma once

#include <cstdint>
#include <vector>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

struct CameraRingOptions {
  int views = 20;
  int width = 640;
  int height = 480;
  double focal_px = 0.0;             // 0: a 35 mm lens on a 36 mm sensor (fx = 0.9722 * width)
  double min_elevation_deg = 20.0;
  double max_elevation_deg = 45.0;
  int rings = 3;                     // elevations cycle through this many evenly spaced rings
  double azimuth_jitter_deg = 6.0;
  double elevation_jitter_deg = 3.0;
  double target_jitter = 0.03;       // aim-point jitter as a fraction of the building's size
  double margin = 0.06;              // keep vertices this fraction of the image size away from the border
  // Azimuth sector the views share (360 = the whole ring, with a random phase). Below 360 the views are
  // spread evenly over the sector (jitter kept inside it), centred on the outward normal of one of the two
  // long sides of the footprint's minimum-area rectangle (`sector_on_corner` false) or on one of that side's
  // corners (halfway between its normal and the neighbouring side's); which one comes from the seed.
  double azimuth_span_deg = 360.0;
  bool sector_on_corner = false;
  // Both > 0: each camera stands this high above the lowest point (uniform in [min, max]) instead of on an
  // elevation ring, at the smallest horizontal distance that frames every point. Both 0: elevation rings.
  double min_camera_height_m = 0.0;
  double max_camera_height_m = 0.0;
  // With camera heights and a sector of at most 150 degrees: the views stand on one straight line parallel to
  // the side the sector faces (a walk along a street), where each view's azimuth meets it, all at the distance
  // the farthest view needs to frame the building. Lines along the walk then lie in epipolar planes.
  bool straight_walk = false;
  uint64_t seed = 0;
  void Check() const;
};

// Throws std::invalid_argument when `points` is empty or the options are bad.
std::vector<Camera> make_camera_ring(const std::vector<Vec3>& points, const CameraRingOptions& options);

// How many times larger than `options`' width x height a building's images must be for its bounding-box
// diagonal (the size make_camera_ring frames) to take at most `max_metres_per_pixel` per pixel of the image
// width: 1 when it already does or the rule is off (0), else that factor, but never beyond `max_side`
// pixels on the longer image side. The framing stays; the pixels get finer, so a 100 m block is seen as
// sharply as a house (a fixed image size would assume the building's size).
double view_scale_for(const std::vector<Vec3>& points, const CameraRingOptions& options, double max_metres_per_pixel,
                      int max_side);

// `options` with width, height (and a set focal_px) multiplied by `scale`, rounded.
CameraRingOptions scaled_ring(const CameraRingOptions& options, double scale);

// OpenCV-convention camera at `center` looking at `target` with world +z up in the image.
Camera look_at(const Vec3& center, const Vec3& target, const Eigen::Matrix3d& K, int width, int height);

}  // namespace lc2wf
