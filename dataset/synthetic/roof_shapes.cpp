#include "dataset/synthetic/roof_shapes.h"

namespace lc2wf {
namespace {

RoofedBlock block(const Rect& r) {
  RoofedBlock b;
  b.x0 = r.x0;
  b.y0 = r.y0;
  b.x1 = r.x1;
  b.y1 = r.y1;
  return b;
}

Side opposite(Side s) {
  switch (s) {
    case Side::South: return Side::North;
    case Side::North: return Side::South;
    case Side::West: return Side::East;
    case Side::East: return Side::West;
  }
  return s;
}

}  // namespace

RoofPlane plane_rising_from(const Rect& r, Side side, double height, double slope, double inset) {
  RoofPlane p;
  switch (side) {
    case Side::South: p.b = slope, p.c = height - slope * (r.y0 + inset); break;
    case Side::North: p.b = -slope, p.c = height + slope * (r.y1 - inset); break;
    case Side::West: p.a = slope, p.c = height - slope * (r.x0 + inset); break;
    case Side::East: p.a = -slope, p.c = height + slope * (r.x1 - inset); break;
  }
  return p;
}

RoofedBlock flat_block(const Rect& r, double height) {
  RoofedBlock b = block(r);
  b.planes = {RoofPlane{0, 0, height}};
  return b;
}

RoofedBlock shed_block(const Rect& r, Side low_side, double low, double slope) {
  RoofedBlock b = block(r);
  b.planes = {plane_rising_from(r, low_side, low, slope)};
  return b;
}

RoofedBlock gable_block(const Rect& r, double eave, double slope, bool along_x) {
  RoofedBlock b = block(r);
  const Side s = along_x ? Side::South : Side::West;
  b.planes = {plane_rising_from(r, s, eave, slope), plane_rising_from(r, opposite(s), eave, slope)};
  return b;
}

RoofedBlock hip_block(const Rect& r, double eave, double slope, double end_slope, bool along_x) {
  RoofedBlock b = gable_block(r, eave, slope, along_x);
  const Side e = along_x ? Side::West : Side::South;
  b.planes.push_back(plane_rising_from(r, e, eave, end_slope));
  b.planes.push_back(plane_rising_from(r, opposite(e), eave, end_slope));
  return b;
}

RoofedBlock pyramid_block(const Rect& r, double eave, double rise) {
  RoofedBlock b = block(r);
  const double sy = rise / (0.5 * r.dy()), sx = rise / (0.5 * r.dx());
  b.planes = {plane_rising_from(r, Side::South, eave, sy), plane_rising_from(r, Side::North, eave, sy),
              plane_rising_from(r, Side::West, eave, sx), plane_rising_from(r, Side::East, eave, sx)};
  return b;
}

RoofedBlock mansard_block(const Rect& r, double eave, double lower_slope, double inset, double upper_slope) {
  RoofedBlock b = block(r);
  const double kerb = eave + lower_slope * inset;
  for (Side s : {Side::South, Side::North, Side::West, Side::East}) {
    b.planes.push_back(plane_rising_from(r, s, eave, lower_slope));
    if (upper_slope > 0) b.planes.push_back(plane_rising_from(r, s, kerb, upper_slope, inset));
  }
  if (upper_slope <= 0) b.planes.push_back(RoofPlane{0, 0, kerb});
  return b;
}

RoofedBlock gambrel_block(const Rect& r, double eave, double lower_slope, double inset, double upper_slope, bool along_x) {
  RoofedBlock b = block(r);
  const double kerb = eave + lower_slope * inset;
  const Side s = along_x ? Side::South : Side::West;
  for (Side side : {s, opposite(s)}) {
    b.planes.push_back(plane_rising_from(r, side, eave, lower_slope));
    b.planes.push_back(plane_rising_from(r, side, kerb, upper_slope, inset));
  }
  return b;
}

}  // namespace lc2wf
