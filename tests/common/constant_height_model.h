// A height model (dataset/photo/line_height.h) that reads every cloud as `height_m` tall: one training cloud,
// one neighbour. For tests of what the callers do with the height read.
#pragma once

#include <cmath>

#include "dataset/photo/line_height.h"

namespace lc2wf::test {

inline HeightModel constant_height_model(double height_m) {
  HeightModel m;
  m.mean.assign(kLineStatisticsSize, 0.0), m.stddev.assign(kLineStatisticsSize, 1.0);
  m.clouds = {std::vector<double>(kLineStatisticsSize, 0.0)};
  m.log_heights = {std::log(height_m)};
  m.k = 1;
  return m;
}

}  // namespace lc2wf::test
