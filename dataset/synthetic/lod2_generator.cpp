#include "dataset/synthetic/lod2_generator.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "dataset/geometry/closed_mesh.h"
#include "dataset/sampling/rng.h"
#include "dataset/synthetic/footprints.h"
#include "dataset/synthetic/roof_shapes.h"

namespace lc2wf {
namespace {

// Draws rounded to centimetres (lengths) and thousandths (slopes): a last-bit difference of exp/log between
// C libraries cannot change a building.
class Draw {
 public:
  explicit Draw(uint64_t seed) : rng_(seed) {}
  double length(double lo, double hi) { return round_to(rng_.uniform(lo, hi), 0.01); }
  double log_length(double lo, double hi) { return round_to(lo * std::exp(rng_.uniform() * std::log(hi / lo)), 0.01); }
  double slope(double lo, double hi) { return round_to(rng_.uniform(lo, hi), 0.001); }
  bool chance(double p) { return rng_.uniform() < p; }
  int integer(int lo, int hi) { return lo + static_cast<int>(rng_.below(static_cast<uint64_t>(hi - lo + 1))); }
  DataRng& rng() { return rng_; }

 private:
  static double round_to(double x, double step) { return std::round(x / step) * step; }
  DataRng rng_;
};

using Blocks = std::vector<RoofedBlock>;

// Roof-Image-like pitches: 20-50 degrees.
double house_slope(Draw& d) { return d.slope(0.36, 1.2); }

Blocks flat(Draw& d) {
  const double l = d.log_length(6, 45), w = std::max(4.0, d.length(l / 2.5, l));
  return {flat_block({0, 0, l, w}, d.log_length(3, 24))};
}

// A base block with 1-3 set-back blocks on top, each higher than the one below; sometimes a lower wing.
Blocks flat_multi(Draw& d) {
  const double l = d.log_length(12, 70), w = std::max(8.0, d.length(l / 2.2, l));
  double h = d.log_length(3.5, 14);
  Blocks blocks = {flat_block({0, 0, l, w}, h)};
  if (h > 5 && d.chance(0.35)) blocks.push_back(flat_block({0, w, d.length(0.3 * l, 0.7 * l), w + d.length(4, 10)}, d.length(3, h - 1.5)));
  Rect r{0, 0, l, w};
  const int levels = d.integer(1, 3);
  for (int i = 0; i < levels; ++i) {
    const double nx = d.length(0.4, 0.8) * r.dx(), ny = d.chance(0.3) ? r.dy() : d.length(0.5, 0.8) * r.dy();
    if (nx < 4 || ny < 4) break;
    auto place = [&](double lo, double span, double size) {
      const int mode = d.integer(0, 2);  // aligned low, aligned high, centred
      return mode == 0 ? lo : mode == 1 ? lo + span - size : lo + 0.5 * (span - size);
    };
    const double x0 = place(r.x0, r.dx(), nx), y0 = ny == r.dy() ? r.y0 : place(r.y0, r.dy(), ny);
    r = {x0, y0, x0 + nx, y0 + ny};
    h += d.length(3, 12);
    blocks.push_back(flat_block(r, h));
  }
  return blocks;
}

Blocks gabled(Draw& d) {
  const double l = d.log_length(6, 28), w = d.length(5, std::min(13.0, l));
  return {gable_block({0, 0, l, w}, d.length(2.6, 9), house_slope(d), !d.chance(0.15))};
}

Blocks hipped(Draw& d) {
  const double l = d.log_length(7, 28), w = d.length(5, std::min(13.0, l - 1));
  const double s = house_slope(d);
  return {hip_block({0, 0, l, w}, d.length(2.6, 9), s, d.slope(s, 1.5 * s), true)};
}

Blocks pyramid(Draw& d) {
  const double l = d.length(5, 14), w = d.length(0.85 * l, l);
  return {pyramid_block({0, 0, l, w}, d.length(2.6, 12), 0.5 * w * d.slope(0.5, 1.6))};
}

Blocks shed(Draw& d) {
  const double l = d.log_length(3.5, 20), w = d.length(3, std::min(12.0, l));
  return {shed_block({0, 0, l, w}, d.chance(0.3) ? Side::West : Side::South, d.length(2.2, 7), d.slope(0.08, 0.36))};
}

Blocks mansard(Draw& d) {
  const double l = d.length(10, 35), w = d.length(8, std::min(18.0, l));
  const double eave = d.length(3, 15), inset = d.length(0.8, std::min(2.5, w / 4)), lower = d.slope(2, 4);
  return {mansard_block({0, 0, l, w}, eave, lower, inset, d.chance(0.5) ? 0.0 : d.slope(0.15, 0.5))};
}

Blocks gambrel(Draw& d) {
  const double l = d.length(7, 22), w = d.length(6, std::min(13.0, l));
  const double eave = d.length(2.6, 6), inset = 0.5 * w * d.slope(0.3, 0.5);
  return {gambrel_block({0, 0, l, w}, eave, d.slope(1.5, 3), inset, d.slope(0.3, 0.8), true)};
}

// Shed strips in a row, each rising to a vertical glazed face where the next one starts low again.
Blocks saw_tooth(Draw& d) {
  const int teeth = d.integer(3, 8);
  const double span = d.length(5, 12), w = d.length(12, 50), low = d.length(4, 9), slope = d.slope(0.15, 0.6);
  Blocks blocks;
  for (int i = 0; i < teeth; ++i) blocks.push_back(shed_block({i * span, 0, (i + 1) * span, w}, Side::West, low, slope));
  return blocks;
}

// A main house and 1-3 parts against its south, north and east walls: lower flat, shed or gabled
// annexes (a gabled one whose ridge rises above the main eaves runs into the main roof), or a taller
// stair tower.
Blocks multi_part(Draw& d) {
  const double l = d.length(9, 24), w = d.length(7, std::min(12.0, l)), eave = d.length(3, 9), s = d.slope(0.4, 1.1);
  const int main_roof = d.integer(0, 3);  // gable, gable, hip, flat
  const Rect main{0, 0, l, w};
  const double ridge = main_roof == 3 ? eave + d.length(0, 3) : eave + s * 0.5 * w;
  Blocks blocks = {main_roof == 3 ? flat_block(main, ridge) : main_roof == 2 ? hip_block(main, eave, s, s, true)
                                                                              : gable_block(main, eave, s, true)};
  std::vector<Side> sides = {Side::South, Side::North, Side::East};
  d.rng().shuffle(sides);
  const int parts = d.integer(1, 3);
  for (int i = 0; i < parts; ++i) {
    const Side side = sides[i];
    const bool long_side = side != Side::East;
    const double run = long_side ? l : w;
    const double size = d.length(3, 0.75 * run), depth = d.length(2.5, 7);
    double at = d.length(0, run - size);
    if (at < 1) at = 0;
    if (run - size - at < 1) at = run - size;
    Rect r = side == Side::South ? Rect{at, -depth, at + size, 0}
             : side == Side::North ? Rect{at, w, at + size, w + depth}
                                   : Rect{l, at, l + depth, at + size};
    const Side outer = side;  // the part's wall away from the house
    const int kind = d.integer(0, 4);  // flat, shed, gable, gable, tower
    if (kind == 4 && size <= 7) {
      blocks.push_back(flat_block(r, ridge + d.length(1, 6)));
    } else if (kind == 0 || eave < 3.2) {
      blocks.push_back(flat_block(r, d.length(2.4, std::max(2.5, eave - 0.5))));
    } else if (kind == 1) {
      const double low = d.length(2.2, eave - 1);
      blocks.push_back(shed_block(r, outer, low, std::min(d.slope(0.08, 0.4), (eave - 0.3 - low) / depth)));
    } else {
      const double a_eave = d.length(2.4, eave - 0.3);
      const double a_slope = std::min(d.slope(0.5, 1.0), (ridge - 0.4 - a_eave) / (0.5 * size));
      const double a_ridge = a_eave + a_slope * 0.5 * size;
      if (a_slope < 0.2) {
        blocks.push_back(flat_block(r, a_eave));
        continue;
      }
      // Into the main roof up to its ridge line when the annex ridge rises above the main eaves.
      if (long_side && main_roof != 3 && a_ridge > eave) {
        if (side == Side::South) r.y1 = 0.5 * w;
        else r.y0 = 0.5 * w;
      }
      blocks.push_back(gable_block(r, a_eave, a_slope, !long_side));
    }
  }
  return blocks;
}

enum class WingRoof { Hipped, Gabled, Flat };

WingRoof wing_roof(Draw& d, double hipped, double gabled) {
  const double u = d.rng().uniform();
  return u < hipped ? WingRoof::Hipped : u < hipped + gabled ? WingRoof::Gabled : WingRoof::Flat;
}

// Roofs on wing rectangles: one eave and slope for all; flat wings of one height or (per_wing) their own.
Blocks roof_wings(Draw& d, const std::vector<Wing>& wings, WingRoof roof, double eave, bool per_wing_heights) {
  const double s = d.slope(0.4, 1.0);
  Blocks blocks;
  for (const Wing& wing : wings) {
    if (roof == WingRoof::Hipped) blocks.push_back(hip_block(wing.rect, eave, s, s, wing.along_x));
    else if (roof == WingRoof::Gabled) blocks.push_back(gable_block(wing.rect, eave, s, wing.along_x));
    else blocks.push_back(flat_block(wing.rect, per_wing_heights && blocks.size() > 0 ? eave + d.length(1.5, 8) : eave));
  }
  return blocks;
}

Blocks l_shape(Draw& d) {
  const double w = d.length(7, 13), a = d.length(w + 5, 40), b = d.length(w + 5, 32);
  const WingRoof roof = wing_roof(d, 0.45, 0.3);
  return roof_wings(d, l_wings(a, b, w, roof == WingRoof::Gabled), roof, d.length(3, 14), d.chance(0.4));
}

Blocks t_shape(Draw& d) {
  const double w = d.length(7, 13), a = d.length(2 * w + 6, 45), stem = d.length(0.6 * w, w);
  const double at = d.length(2.5, a - stem - 2.5), b = d.length(w + 5, 30);
  const WingRoof roof = wing_roof(d, 0.45, 0.3);
  return roof_wings(d, t_wings(a, b, w, stem, at, roof == WingRoof::Gabled), roof, d.length(3, 14), d.chance(0.4));
}

Blocks u_shape(Draw& d) {
  const double w = d.length(7, 13), a = d.length(2 * w + 5, 45), b = d.length(w + 5, 30);
  const WingRoof roof = wing_roof(d, 0.45, 0.3);
  return roof_wings(d, u_wings(a, b, w, roof == WingRoof::Gabled), roof, d.length(3, 14), d.chance(0.4));
}

// Flat courtyards get two heights (the wings along x, the wings along y): one flat ring would be a roof
// face with a hole, split by two edges no one would draw.
Blocks courtyard(Draw& d) {
  const double w = d.length(7, 13), a = d.length(2 * w + 6, 60), b = d.length(2 * w + 6, 50), eave = d.length(3, 14);
  const WingRoof roof = wing_roof(d, 0.5, 0.2);
  Blocks blocks = roof_wings(d, courtyard_wings(a, b, w, roof == WingRoof::Gabled), roof, eave, false);
  if (roof == WingRoof::Flat) {
    const double other = eave + d.length(1.5, 8);
    blocks[2].planes = {RoofPlane{0, 0, other}};
    blocks[3].planes = {RoofPlane{0, 0, other}};
  }
  return blocks;
}

// A gabled or hipped house with gable or shed dormers on the south slope and sometimes the north one.
Blocks dormers(Draw& d) {
  const double l = d.length(9, 20), w = d.length(7, 11.5), eave = d.length(3, 6.5), s = d.slope(0.75, 1.3);
  const bool hip = l - w >= 4.5 && d.chance(0.35);
  const Rect house{0, 0, l, w};
  Blocks blocks = {hip ? hip_block(house, eave, s, s, true) : gable_block(house, eave, s, true)};
  const double ridge = eave + s * 0.5 * w;
  const double margin = hip ? 0.5 * w + 0.8 : 0.8;  // clear of the hips
  const double usable = l - 2 * margin;
  for (const Side slope_side : {Side::South, Side::North}) {
    if (slope_side == Side::North && !d.chance(0.5)) continue;
    const double width = d.length(1.2, 2.6);
    const int count = std::min(d.integer(1, 4), static_cast<int>(usable / (width + 0.8)));
    const double setback = d.length(0.4, 1.4), front = d.length(1.0, 1.6);
    const double d_eave = eave + s * setback + front;
    const bool gable = d.chance(0.6);
    const double d_slope = d.slope(0.5, 1.0), shed_slope = s * d.slope(0.1, 0.35);
    for (int i = 0; i < count; ++i) {
      const double centre = margin + usable * (i + 0.5) / count;
      Rect r{centre - 0.5 * width, 0, centre + 0.5 * width, 0};
      if (slope_side == Side::South) r.y0 = setback, r.y1 = 0.5 * w;
      else r.y0 = 0.5 * w, r.y1 = w - setback;
      const Side front_side = slope_side;
      if (gable && d_eave + d_slope * 0.5 * width < ridge - 0.4) {
        blocks.push_back(gable_block(r, d_eave, d_slope, false));
      } else if (setback + front / (s - shed_slope) < 0.5 * w - 0.5) {
        blocks.push_back(shed_block(r, front_side, d_eave, shed_slope));
      }
    }
  }
  if (blocks.size() == 1) throw std::logic_error("no dormer fits this roof");
  return blocks;
}

// 3-8 units side by side along x; eaves, depths and roofs (gabled along the row, or flat) differ per unit.
Blocks row_houses(Draw& d) {
  const int units = d.integer(3, 8);
  const double depth = d.length(8, 12), eave = d.length(5, 9), s = d.slope(0.5, 1.0);
  const int style = d.integer(0, 4);  // 0-2 gabled, 3 flat, 4 mixed
  const bool same_eaves = d.chance(0.35), staggered = d.chance(0.5);
  Blocks blocks;
  double x = 0;
  for (int i = 0; i < units; ++i) {
    const double width = d.length(4.5, 8);
    double y0 = staggered ? d.length(-1, 1) : 0.0, e = same_eaves ? eave : eave + d.length(-1.5, 1.5);
    if (std::abs(y0) < 0.3) y0 = 0;
    if (std::abs(e - eave) < 0.3) e = eave;
    const double y1 = staggered ? y0 + depth + (d.chance(0.5) ? d.length(-1, 1) : 0.0) : depth;
    const Rect r{x, y0, x + width, y1};
    const bool flat_unit = style == 3 || (style == 4 && d.chance(0.5));
    blocks.push_back(flat_unit ? flat_block(r, e + d.length(0, 1.5)) : gable_block(r, e, s, true));
    x += width;
  }
  return blocks;
}

// 18-60 m, small footprint; flat, pyramid (up to a spire) or hipped top; sometimes on a podium.
Blocks tower(Draw& d) {
  const double l = d.length(5, 13), w = d.length(0.75 * l, l), total = d.log_length(18, 60);
  const int top = d.integer(0, 19);  // 0-8 flat, 9-16 pyramid, 17-19 hipped
  const Rect r{0, 0, l, w};
  Blocks blocks;
  double eave = total;
  if (top <= 8) {
    blocks.push_back(flat_block(r, total));
  } else if (top <= 16 || l - w < 0.5) {
    const double rise = std::min(total - 12, 0.5 * w * d.slope(0.8, 3.0));
    eave = total - rise;
    blocks.push_back(pyramid_block(r, eave, rise));
  } else {
    const double s = d.slope(0.5, 1.2);
    eave = total - s * 0.5 * w;
    blocks.push_back(hip_block(r, eave, s, s, true));
  }
  if (d.chance(0.4)) {
    auto margin = [&] {
      const double m = d.length(0, 10);
      return m < 1.5 ? 0.0 : m;
    };
    const Rect podium{-margin(), -margin(), l + margin(), w + margin()};
    if (podium.dx() > l || podium.dy() > w) blocks.push_back(flat_block(podium, d.length(3.5, std::min(12.0, eave - 4))));
  }
  return blocks;
}

// 60-150 m long: flat with rooftop housings, stepped in height along its length, or a low pitched roof.
Blocks large_block(Draw& d) {
  const double l = d.length(60, 150), w = d.length(12, 30), h = d.length(8, 30);
  const int style = d.integer(0, 19);  // 0-10 flat, 11-13 stepped, 14-17 gabled, 18-19 hipped
  const Rect r{0, 0, l, w};
  if (style >= 18) return {hip_block(r, h, d.slope(0.15, 0.6), d.slope(0.6, 1.0), true)};
  if (style >= 14) return {gable_block(r, h, d.slope(0.15, 0.6), true)};
  Blocks blocks;
  if (style >= 11) {
    const int parts = d.integer(2, 3);
    double x = 0, height = h;
    for (int i = 0; i < parts; ++i) {
      const double x1 = i + 1 == parts ? l : x + d.length(0.25, 0.45) * l;
      blocks.push_back(flat_block({x, 0, x1, w}, height));
      height = std::max(4.0, height + (d.chance(0.5) ? 1 : -1) * d.length(2, 8));
      x = x1;
    }
    return blocks;
  }
  blocks.push_back(flat_block(r, h));
  const int housings = d.integer(0, 3);
  for (int i = 0; i < housings; ++i) {
    const double slot = l / housings, bx = d.length(3, 8), by = d.length(3, std::min(6.0, w - 3));
    const double x0 = i * slot + d.length(1.5, slot - bx - 1.5), y0 = d.length(1.5, w - by - 1.5);
    blocks.push_back(flat_block({x0, y0, x0 + bx, y0 + by}, h + d.length(2.5, 4)));
  }
  return blocks;
}

using KindFn = Blocks (*)(Draw&);
constexpr KindFn kKindFns[kLod2KindCount] = {flat,     flat_multi, gabled,    hipped,  pyramid, shed,
                                             mansard,  gambrel,    saw_tooth, multi_part, l_shape, t_shape,
                                             u_shape,  courtyard,  dormers,   row_houses, tower,   large_block};

}  // namespace

void Lod2Options::Check() const {
  kinds.Check();
  if (!(min_vertex_distance_m >= 0 && min_vertex_distance_m <= 1))
    throw std::invalid_argument("Lod2Options.min_vertex_distance_m must be in [0, 1]");
  if (!(max_attempts >= 1 && max_attempts <= 1000)) throw std::invalid_argument("Lod2Options.max_attempts must be in [1, 1000]");
}

std::vector<RoofedBlock> lod2_blocks(Lod2Kind kind, uint64_t seed) {
  Draw d(seed);
  return kKindFns[static_cast<int>(kind)](d);
}

Lod2Kind pick_lod2_kind(uint64_t seed, const Lod2KindWeights& weights) {
  DataRng rng(mix_seed(seed, 0x6B696E64ull));
  return weights.pick(rng.uniform());
}

GeneratedBuilding generate_lod2_building(Lod2Kind kind, uint64_t seed, const Lod2Options& options) {
  options.Check();
  std::string last_problem;
  for (int attempt = 0; attempt < options.max_attempts; ++attempt) {
    PolyMesh mesh;
    try {
      mesh = assemble_blocks(lod2_blocks(kind, mix_seed(seed, static_cast<uint64_t>(attempt))));
    } catch (const std::exception& e) {  // a draw whose pieces do not close: draw again
      last_problem = e.what();
      continue;
    }
    const ClosedMeshReport report = inspect_closed_mesh(mesh);
    if (!report.closed() || report.max_planarity_deviation > 1e-6) {
      last_problem = "the mesh is not closed";
      continue;
    }
    if (report.min_vertex_distance < options.min_vertex_distance_m) {
      last_problem = "corners closer than " + std::to_string(options.min_vertex_distance_m) + " m";
      continue;
    }
    GeneratedBuilding b;
    b.kind = kind;
    b.attempts = attempt + 1;
    Eigen::AlignedBox3d box;
    for (const Vec3& v : mesh.vertices) box.extend(v);
    const Vec3 centre(0.5 * (box.min().x() + box.max().x()), 0.5 * (box.min().y() + box.max().y()), 0.0);
    b.footprint_long_m = std::max(box.sizes().x(), box.sizes().y());
    b.footprint_short_m = std::min(box.sizes().x(), box.sizes().y());
    b.height_m = box.max().z();
    const double angle = options.turn ? 2 * M_PI * DataRng(mix_seed(seed, 0x7475726Eull)).uniform() : 0.0;
    const double c = std::cos(angle), s = std::sin(angle);
    for (Vec3& v : mesh.vertices) {
      const Vec3 p = v - centre;
      v = Vec3(c * p.x() - s * p.y(), s * p.x() + c * p.y(), p.z());
    }
    b.mesh = std::move(mesh);
    return b;
  }
  throw std::runtime_error(std::string("no closed ") + lod2_kind_name(kind) + " building from seed " + std::to_string(seed) +
                           " in " + std::to_string(options.max_attempts) + " draws (" + last_problem + ")");
}

GeneratedBuilding generate_lod2_building(uint64_t seed, const Lod2Options& options) {
  options.Check();
  return generate_lod2_building(pick_lod2_kind(seed, options.kinds), seed, options);
}

}  // namespace lc2wf
