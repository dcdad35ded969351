// Everything lc2wf-reconstruct needs: inputs, the COLMAP and line-extraction settings, how the frame's
// scale and up axis are fixed (dataset/photo/metric_frame.h), post-processing, and the workspace policy.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <string>

#include "dataset/photo/line_confirmation.h"
#include "dataset/photo/metric_frame.h"
#include "dataset/photo/similarity_align.h"
#include "model/scale_search.h"
#include "model/post_process_options.h"
#include "tools/colmap/colmap_poses.h"
#include "tools/lines/lsd_detector.h"
#include "tools/triangulation/line_triangulator.h"

namespace lc2wf {

struct ReconstructOptions {
  std::filesystem::path images;             // folder of photos
  std::filesystem::path weights;            // junction.safetensors + edge.safetensors
  std::filesystem::path out;                // final outputs only
  std::filesystem::path cameras;            // optional: COLMAP model folder or cameras JSON
  std::filesystem::path reference_cameras;  // optional: cameras JSON to align the result to (evaluation)
  std::filesystem::path workspace;          // optional user-named workspace (kept, never cleared)
  bool keep = false;                        // keep the private temporary workspace
  bool quiet = false;
  int threads = 0;                          // 0 = all cores
  int min_images = 3;                       // readable and registered images needed

  // COLMAP intrinsics (fixed during mapping unless the focal length is a guess): fx, fy, cx, cy (OpenCV pixel
  // centres), or from the 35 mm-equivalent focal length: fx = fy = focal_35mm / 36 * the longer side of each photo (--intrinsics:
  // photos of one size only). Unset: each photo's EXIF (exif_focal.h), else kDefaultFocal35mm.
  std::optional<Eigen::Vector4d> intrinsics;
  std::optional<double> focal_35mm;
  static constexpr double kDefaultFocal35mm = 35.0;  // a normal lens; phones' main cameras are 24-28
  ColmapOptions colmap = [] {
    ColmapOptions o;
    o.max_features = 2000;  // 20 photos of 640x480: exhaustive matching stays within the time budget
    return o;
  }();

  // LSD sees each photo at most as large as SIFT does (colmap.max_image_size; its segments come back in
  // full-size pixels): the time of 2-12 MP photos stays that of a 2 MP one. --max-image-side sets both.
  LsdOptions lsd = [] {
    LsdOptions o;
    o.max_side = ColmapOptions{}.max_image_size;
    return o;
  }();
  TriangulatorOptions triangulator;
  // Lines no other source view confirms are dropped before inference (dataset/photo/line_confirmation.h): in
  // photo clouds most of them are chance matches among texture lines, floating above the roof.
  LineConfirmationOptions confirmation;

  MetricFrameOptions frame;
  // The frame is measured on the lines with >= k supporting 2D segments, k the largest in
  // [3, frame_max_supports] that leaves frame_min_lines lines (all lines when none does). On the
  // known-camera clouds of 11 held-out buildings (20 views) this picks k = 6 and puts a height-based
  // scale within 1.5 % on 10 of them (8 % on one); with all lines it was off by up to 2.4x.
  int frame_max_supports = 8;
  int frame_min_lines = 100;
  bool up_given = false;     // frame.up set on the command line
  bool scale_given = false;  // frame.scale or a known distance set on the command line
  std::string known_image_a, known_image_b;  // file names for frame.known_distance_m
  // Scale and up from the photos' EXIF GPS (>= 3 registered photos with a fix and altitude, not on one line),
  // after a known distance and before a building height (frame.building_height_m) and the scale search.
  bool use_gps = true;
  int min_gps_photos = 3;
  // GPS is used only when the camera centres fit the fixes to an RMS residual of at most this share of the
  // fixes' spread (RMS distance from their mean): a drone's orbit fits to ≈ 2 m of 20-40 m (bench/README.md),
  // a phone's walk down a street (10 m fixes) to 33 m of 57 m, whose scale and up were garbage.
  double max_gps_residual_share = 0.25;
  // GPS fixes are metres off: a camera is left out of the fit only beyond 3 x the median residual and 5 m.
  SimilarityFitOptions gps_fit{.outlier_factor = 3.0, .outlier_floor = 5.0, .rounds = 3, .min_spread_ratio = 0.05};
  // The height model read after the storeys (dataset/photo/line_height.h): "none", a file, or empty for
  // the weights folder's height.json when there is one.
  std::string height_model;
  ScaleSearchOptions scale_search;  // when nothing else gives the scale

  // Photo clouds are judged by their lines on every capture, full orbits too, and so are their small flat
  // parts apart from the longest: the networks draw edges between the corners of windows and texture on every
  // side (infer/README.md, "Drawing only what was seen" and "Flat fragments"). The junction model averages 4
  // views of each patch: photo clutter makes single votes noisy, and COLMAP's seconds dwarf the cost
  // (reconstruct/README.md, "Test-time views of photo clouds").
  PostProcessOptions post = [] {
    PostProcessOptions p;
    p.edge_support.partial_captures_only = false;
    p.flat_parts.max_edges = 10;
    p.flat_parts.partial_captures_only = false;
    p.selection.test_time_views = 4;
    return p;
  }();
  bool surfaces = true;  // also write wireframe.city.json + wireframe.faces.obj (infer/surfaces/); --no-surfaces
  void Check() const;  // throws std::invalid_argument naming the field
};

}  // namespace lc2wf
