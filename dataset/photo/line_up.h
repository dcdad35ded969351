// Up from a building's lines alone, for line maps made elsewhere without cameras (Line3D++, LIMAP, OBJ) in an
// arbitrary frame. The candidates are the lines' dominant directions and the normals of each pair of them. With
// a height model (line_height.h) the up is the candidate under which the lines' statistics lie nearest the
// model's metric, z-up training clouds: a map from street photos has more vertical lines than horizontal
// ones and one facade plane, a drone map the reverse, and both look like buildings only the right way up
// (experiments/README.md, "Up from the lines"). Without one, the up is the direction most of the line length is
// perpendicular to (right for whole buildings with many horizontal lines, wrong for facades seen from the
// street). Its sign: the ends of the nearest training clouds say how to tell the ground (LineStatistics::ends:
// a whole building's footprint spreads widest, a street capture's lower storeys hold more lines); without a
// model the end whose structure spreads widest is the ground. Give the up (--up) where the map's frame is known.
#pragma once

#include <vector>

#include "dataset/geometry/geometry.h"
#include "dataset/photo/line_height.h"

namespace lc2wf {

// One direction up_from_lines tried (unsigned: the ground's end is told afterwards).
struct UpCandidate {
  Vec3 direction = Vec3::UnitZ();
  double perpendicular_share = 0;  // share of the line length perpendicular (within 10 deg) to it
  double distance = -1;            // statistics distance to the model's clouds; -1 without a model or a height
};

struct LineUp {
  Vec3 up = Vec3::UnitZ();
  bool by_statistics = false;      // chosen by the height model's clouds, else by the perpendicular share
  double distance = 0;             // by_statistics: mean standardised distance to the model's k nearest clouds
  double runner_up_distance = 0;   // ... of the best other candidate (0 when there is none)
  Vec3 runner_up = Vec3::Zero();   // that candidate's direction (either way up; zero when there is none)
  // by_statistics and the runner-up within kUncertainUpMargin of the chosen distance: another way up looks
  // almost as much like a building (on validation maps 10 of 12 wrong ups and 13 of 113 right ones).
  bool uncertain = false;
  bool sign_by_statistics = false;  // which end is the ground: as the model's nearest clouds' ends say, else
                                    // the end whose structure spreads widest
  double perpendicular_share = 0;  // share of the line length perpendicular (within 10 deg) to up
  double spread_ratio = 1;         // spread of the bottom end's structure over the top end's (>= 1)
  std::vector<UpCandidate> tried;  // every direction tried, in the order found
};

inline constexpr double kUncertainUpMargin = 0.4;

// Throws std::invalid_argument when there is no line with a length. `model` may be null.
LineUp up_from_lines(const std::vector<Segment3>& segments, const HeightModel* model = nullptr);

}  // namespace lc2wf
