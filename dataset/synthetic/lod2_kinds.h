// The kinds of procedural LoD2 building (lod2_generator.h) and how often each is drawn. Roof-Image has only
// complex / mixed / hipped roofs of one height band; these cover the roof forms, sizes and layouts it lacks.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace lc2wf {

enum class Lod2Kind {
  Flat,        // one flat block
  FlatMulti,   // flat roofs at several levels (stepped blocks)
  Gabled,
  Hipped,
  Pyramid,
  Shed,        // mono-pitch
  Mansard,
  Gambrel,
  SawTooth,
  MultiPart,   // a main house with lower or taller parts of other roofs sharing its walls
  LShape,
  TShape,
  UShape,
  Courtyard,
  Dormers,     // a pitched house with gable or shed dormers
  RowHouses,   // units in a row, differing heights and roofs
  Tower,       // tall, small footprint, up to 60 m
  LargeBlock,  // long blocks up to 150 m
};
inline constexpr int kLod2KindCount = 18;

const char* lod2_kind_name(Lod2Kind kind);  // "flat", "flat_multi", ... (file names use it)
std::optional<Lod2Kind> parse_lod2_kind(std::string_view name);

// Relative weight per kind; a kind of weight 0 is never drawn.
struct Lod2KindWeights {
  std::array<double, kLod2KindCount> weight;
  Lod2KindWeights() { weight.fill(1.0); }
  double& operator[](Lod2Kind k) { return weight[static_cast<int>(k)]; }
  double operator[](Lod2Kind k) const { return weight[static_cast<int>(k)]; }
  void Check() const;  // finite, >= 0, some > 0
  // The kind at u in [0, 1) of the cumulative weights.
  Lod2Kind pick(double u) const;
};

// "gabled,shed" (weight 1 each, others 0) or "gabled:3,flat:1"; "all" = every kind at weight 1.
// Throws std::invalid_argument naming the bad entry.
Lod2KindWeights parse_lod2_kind_weights(const std::string& spec);

}  // namespace lc2wf
