// Rendered views of one building -> labelled line cloud: LSD per view, multi-view triangulation, and
// labels (f, i1, d1, i2, d2) from the supporting 2D segments via dataset/ labelling.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "dataset/geometry/building.h"
#include "dataset/labels/labelling.h"
#include "dataset/geometry/line_cloud.h"
#include "tools/lines/lsd_detector.h"
#include "tools/triangulation/line_triangulator.h"

namespace lc2wf {

struct RenderedView {
  cv::Mat image;  // 8-bit gray or BGR
  Camera camera;
};

struct CloudBuilderOptions {
  LsdOptions lsd;
  TriangulatorOptions triangulator;
  // f=1 needs votes from 3 distinct views (Line3D++'s 3-camera minimum per line): with dataset/'s 2, the
  // lines confirmed by a single view (3 supports) gave f=1 segments with a p90 distance of 1.7 m from
  // their GT edge (tools/README.md).
  SupportLabelOptions labels = [] {
    SupportLabelOptions o;
    o.min_views = 3;
    return o;
  }();
  void Check() const;
};

struct CloudBuildStats {
  std::vector<int> segments_per_view;
  TriangulationStats triangulation;
  double seconds_lsd = 0.0;
  double seconds_triangulation = 0.0;
  double seconds_labelling = 0.0;
};

// Throws DataError naming the building when no view yields any 2D segment or no 3D line results.
// `occluders`: the rendered scene when it holds more than the building (photo clutter), so GT edges that
// clutter hides get no votes; default the building's mesh.
LineCloud build_line_cloud(const Building& building, const std::vector<RenderedView>& views, const CloudBuilderOptions& options,
                           CloudBuildStats* stats = nullptr, const PolyMesh* occluders = nullptr);

}  // namespace lc2wf
