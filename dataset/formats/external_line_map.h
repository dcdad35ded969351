// Line maps made by other programs (Line3D++, LIMAP): 3D segments in the producer's frame and units, with
// the 2D segments that support them keyed by the producer's image ids. `to_line_cloud` turns one into our
// LineCloud; the formats and the conversion rules are in dataset/README.md ("Line clouds made elsewhere").
#pragma once

#include <map>
#include <string>
#include <vector>

#include "dataset/geometry/line_cloud.h"

namespace lc2wf {

// One 2D segment supporting a line, as the producer names it: its image id and the segment's id there.
struct ExternalSupport {
  long long image_id = 0;
  long long segment_id = 0;
  Segment2 seg;  // pixels of the undistorted full-resolution image
};

// One reconstructed line: one or more (Line3D++: collinear) 3D segments sharing one support list.
struct ExternalLine {
  std::vector<Segment3> segments;
  std::vector<ExternalSupport> supports;
};

struct ExternalLineMap {
  std::vector<ExternalLine> lines;
};

struct ExternalConversionOptions {
  double metres_per_unit = 1.0;  // the producer's frame is taken as metres, z up, unless scaled here
  // Cameras by the producer's image id (e.g. COLMAP image_id): supports of these images become
  // Observations; without cameras the supports are dropped (inference uses the 3D segments only).
  const std::map<long long, Camera>* cameras = nullptr;
  void Check() const;
};

struct ExternalConversionReport {
  int zero_length_dropped = 0;       // 3D segments shorter than 1e-9 units
  long long supports_kept = 0;       // became Observations
  long long supports_dropped = 0;    // no camera given for their image id
};

// Every 3D segment becomes a segment of the cloud (in file order), each carrying its line's supports.
// No ground truth, no labels. Throws DataError naming `source` when no segment is left.
LineCloud to_line_cloud(const ExternalLineMap& map, const std::string& name, const std::string& source,
                        const ExternalConversionOptions& options = {}, ExternalConversionReport* report = nullptr);

}  // namespace lc2wf
