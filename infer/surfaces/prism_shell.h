// Closing a shell from its roof: Roof-Image buildings, and most LoD2 buildings, are prisms below their eaves,
// so the roof faces found in a wireframe (with the walls between roof levels) fix the whole shell: walls are
// the vertical extrusion of the roof's outline down to the ground level and the ground is the footprint.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "infer/surfaces/surface_model.h"
#include "infer/surfaces/work_budget.h"

namespace lc2wf {

struct PrismOptions {
  double ground_z = 0;          // the ground level (metres)
  double level_distance = 0.2;  // a face with a vertex this close to the ground level reaches it (is not roof)
  double column_distance = 0.1; // outline vertices this close in plan stand on one wall corner
  double wall_tilt_deg = 15;    // an outline side within this of vertical is a step of a wall corner
  double straight_deg = 5;      // outline corners turning less than this do not split a wall
  std::vector<bool> parts;      // which parts of the roof sheet (largest plan first) to use; empty: all
  double min_overlap = 0.1;     // faces whose plans overlap by more than this share of the smaller: the lower is no roof
};

// The faces of `model` that lie above the ground level (roofs, walls between roof levels, gable ends above the
// eaves) extended by one wall per side of their outline's plan (vertical, down to options.ground_z) and one
// ground face; unused vertices dropped. nullopt, with the reason in `why`, when those faces are not one sheet
// whose outline is one loop over a simple footprint (separate parts, holes, folds, sides in three faces).
// `part_count`, when given, receives the number of parts of the roof sheet.
std::optional<SurfaceModel> extrude_roof_to_ground(const SurfaceModel& model, const PrismOptions& options,
                                                   std::string* why = nullptr, int* part_count = nullptr);

// extrude_roof_to_ground in two steps, for extruding several choices of parts of one sheet: the sheet (the
// faces above the ground level that no higher face hides, oriented upwards, and its parts, largest plan
// first; options.parts is not used), then the prism of the parts options.parts selects.
struct RoofSheet {
  std::vector<std::vector<int>> faces;  // rings of model vertex ids
  std::vector<SurfaceLabel> labels;
  std::vector<std::vector<int>> parts;  // indices into faces
};
// `budget` (when given) is charged with the pairs of faces compared for hiding; once it is exhausted: nullopt.
std::optional<RoofSheet> roof_sheet(const SurfaceModel& model, const PrismOptions& options, std::string* why = nullptr,
                                    WorkBudget* budget = nullptr);
std::optional<SurfaceModel> extrude_roof_sheet(const SurfaceModel& model, const RoofSheet& sheet, const PrismOptions& options,
                                               std::string* why = nullptr);

}  // namespace lc2wf
