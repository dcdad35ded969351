// A synthetic line cloud for a building without rendering: noisy sub-segments of the GT edges (f = 1,
// labels known by construction), roof/wall texture lines and random clutter (f = 0), a ring of cameras
// and per-segment 2D support from the views that see the segment. Lengths follow the paper's shape:
// most segments are shorter than the mean GT edge.
#pragma once

#include <cstdint>

#include "dataset/geometry/building.h"
#include "dataset/geometry/line_cloud.h"

namespace lc2wf {

struct CameraRingOptions {
  int num_views = 16;
  double elevation_deg = 40.0;     // oblique views from above, as in the paper's renders
  double distance_factor = 2.2;    // camera distance / building bounding radius
  int width = 1024;
  int height = 768;
  double focal_px = 900.0;
  void Check() const;
};

// Cameras evenly spaced in azimuth around the building's bounding-box centre, looking at it.
std::vector<Camera> make_camera_ring(const Building& building, const CameraRingOptions& options = {});

struct SyntheticCloudOptions {
  double edge_pieces_per_metre = 2.0;   // redundant pieces per metre of GT edge (many views see each edge)
  double piece_median_m = 1.2;          // log-normal piece length (clipped to the edge)
  double piece_log_sigma = 0.6;
  double anchored_fraction = 0.5;       // pieces starting at a GT junction (line detectors stop at corners)
  double noise_m = 0.02;                // per-endpoint 3D noise (isotropic Gaussian sigma)
  double texture_per_roof_m2 = 1.0;     // in-plane roof/wall texture lines per square metre of roof
  double clutter_fraction = 0.15;       // random segments around the building, relative to edge pieces
  double min_length_m = 0.1;
  double pixel_noise = 0.5;             // px, on the 2D support endpoints
  int max_support_views = 8;
  CameraRingOptions cameras;
  void Check() const;
};

// Deterministic for a seed. Labels are the generator's truth (edge pieces: f = 1 with their edge;
// everything else f = 0).
LineCloud make_synthetic_line_cloud(const Building& building, uint64_t seed, const SyntheticCloudOptions& options = {});

}  // namespace lc2wf
