// One building's geometry for the HTML report, packed as a compact binary block (base64 text) that the
// page decodes only when the building is opened. Layout (little endian; every section starts at an even
// offset, so the browser reads the 16-bit sections as typed-array views):
//   float32 origin[3], float32 step        metres = origin + q * step for every int16 coordinate q
//   uint32  nc, npj, npe, ngj, nge          cloud segments, predicted junctions/edges, GT junctions/edges
//   uint32  nvt, net                        vertex / edge thresholds behind the match bits
//   int16   cloud[nc][6], pj[npj][3], gj[ngj][3]
//   uint16  pe[npe][2], ge[nge][2]          junction indices
//   uint8   pj_score[npj], pe_score[npe]    score * 255, rounded
//   uint8   pj_bits[npj], gj_bits[ngj], pe_bits[npe], ge_bits[nge]   bit t: matched at threshold t
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "infer/match_status.h"
#include "model/scored_wireframe.h"

namespace lc2wf {

struct ReportGeometryInput {
  const ScoredWireframe* pred = nullptr;  // the evaluated prediction (referenced junctions only)
  const Wireframe* gt = nullptr;
  const std::vector<Segment3>* cloud = nullptr;  // may be empty
  MatchStatus junctions, edges;
  int vertex_thresholds = 0, edge_thresholds = 0;
};

// At most `max_cloud_segments` cloud segments are kept (an even stride over the cloud) so large clouds stay
// light; throws std::invalid_argument when a wireframe has more than 65535 junctions.
std::string encode_report_geometry(const ReportGeometryInput& in, int max_cloud_segments);

std::string base64_encode(std::string_view bytes);

}  // namespace lc2wf
