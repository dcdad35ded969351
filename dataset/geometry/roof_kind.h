// The roof kind of a building mesh, from its roof faces' slopes and planes: one rule for the split's
// statistics and for every per-kind score, so "flat" or "gabled" means the same in every table.
#pragma once

#include <string>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

enum class RoofKind { Flat, FlatMulti, Shed, Gabled, Hipped, Mixed, Complex, Unknown };

struct RoofKindOptions {
  double flat_tilt_deg = 5.0;         // a roof face flatter than this counts as flat
  double flat_share_flat = 0.9;       // area share of flat faces from which a roof is flat (one or more levels)
  double flat_share_mixed = 0.1;      // ... between the two, pitched and flat parts mix
  double level_tol_m = 0.5;           // flat faces within this height are one level
  double plane_angle_tol_deg = 3.0;   // pitched faces whose planes agree within these are one plane
  double plane_offset_tol_m = 0.2;
  void Check() const;
};

// Rule (metres, z up): roof faces are those labelled Roof (all faces whose normal points up by more than
// 10 degrees when the mesh has no labels). Flat share >= flat_share_flat: Flat with one level, FlatMulti with
// more. Flat share > flat_share_mixed: Mixed. Otherwise by the number of distinct pitched planes: 1 Shed,
// 2 Gabled, 3-4 Gabled when a wall rises above the pitched roof's lowest point (a gable end: cross gables)
// else Hipped (hip, pyramid), more Complex. No roof face: Unknown.
RoofKind classify_roof(const PolyMesh& mesh, const RoofKindOptions& options = {});

// "flat", "flat-multi", "shed", "gabled", "hipped", "mixed", "complex", "unknown".
std::string roof_kind_name(RoofKind kind);

}  // namespace lc2wf
