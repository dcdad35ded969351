// Scale from a facade's storeys, for photo clouds no GPS, known distance or building height fixes: every storey
// repeats its windows and doors, so the heights the short vertical lines cover (window and door sides) are
// periodic, and a storey is about 3 m floor to floor (homes 2.6-3.2 m, offices and old city houses 3.5-4 m)
// however tall the building is. The period is the autocorrelation's peak of that coverage profile. Horizontal
// lines are not used: roof tiles and the window's own height repeat too (experiments/README.md, "Storeys").
// A cloud without such a rhythm (bare walls, the paper look, one storey) gives no estimate, and the caller
// falls back to the scale search.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

struct StoreyScaleOptions {
  double storey_height_m = 3.0;      // floor to floor; 0 turns the estimate off
  double storey_uncertainty = 0.2;   // relative: what real storeys spread around storey_height_m (report only)
  double vertical_max_deg = 10;      // a line this close to vertical counts, if shorter than half the height
  int min_lines = 40;                // fewer such lines: no estimate
  int max_storeys = 30;              // the shortest period tried is height / max_storeys
  int min_repeats = 2;               // the longest period tried is height / min_repeats
  double bin_fraction = 1.0 / 1000;  // profile resolution, a fraction of the cloud's height
  double smooth_fraction = 1.0 / 300;  // Gaussian sigma of the profile, a fraction of the height (triangulation noise)
  double min_strength = 0.10;        // autocorrelation the period's peak needs (chosen on validation clouds)
  double fundamental_share = 0.8;    // a peak at 1/2 or 1/3 of the best period this strong wins (not 2 storeys)
  void Check() const;                // throws std::invalid_argument naming the field
};

struct StoreyScale {
  bool found = false;
  std::string why_not;         // when not found
  int vertical_lines = 0;      // the short vertical lines the profile was made of
  double period = 0;           // one storey, in the units of the segments
  double strength = 0;         // the peak's autocorrelation, (0, 1]
  double storeys = 0;          // height / period
  double metres_per_unit = 0;  // storey_height_m / period
};

// `segments`: z up with the ground at z = 0 (any scale), `height`: the building's height in their units (> 0).
StoreyScale estimate_storey_scale(const std::vector<Segment3>& segments, double height, const StoreyScaleOptions& options = {});

// What report.json says of it: found or why not, the period, its strength, the storeys and the storey height
// assumed, with the relative uncertainty that height carries.
nlohmann::json storey_scale_json(const StoreyScale& s, const StoreyScaleOptions& o);

}  // namespace lc2wf
