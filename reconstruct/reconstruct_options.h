// Everything lc2wf-reconstruct needs: inputs, the COLMAP and line-extraction settings, how the frame's
// scale and up axis are fixed (dataset/metric_frame.h), post-processing, and the workspace policy.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <string>

#include "dataset/metric_frame.h"
#include "infer/post_process_options.h"
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

  // COLMAP intrinsics (fixed during mapping): fx, fy, cx, cy (OpenCV pixel centres), or from the
  // 35 mm-equivalent focal length (EXIF FocalLengthIn35mmFilm): fx = fy = focal_35mm / 36 * width.
  std::optional<Eigen::Vector4d> intrinsics;
  double focal_35mm = 35.0;
  ColmapOptions colmap = [] {
    ColmapOptions o;
    o.max_features = 2000;  // 20 photos of 640x480: exhaustive matching stays within the time budget
    return o;
  }();

  LsdOptions lsd;
  TriangulatorOptions triangulator;

  MetricFrameOptions frame;
  // The frame is measured on lines with at least this many supporting 2D segments (source, partner and
  // 3 agreeing views), when there are frame_min_lines of them; else on all lines.
  int frame_min_supports = 5;
  int frame_min_lines = 50;
  bool up_given = false;     // frame.up set on the command line
  bool scale_given = false;  // frame.scale or a known distance set on the command line
  std::string known_image_a, known_image_b;  // file names for frame.known_distance_m

  PostProcessOptions post;
  void Check() const;  // throws std::invalid_argument naming the field
};

}  // namespace lc2wf
