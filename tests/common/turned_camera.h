// The camera of a photo turned 90 degrees clockwise (cv::ROTATE_90_CLOCKWISE): pixel (u, v) moves to
// (H - 1 - v, u), so K's centre moves the same way and the camera turns about its optical axis. For the tests
// of photos taken upright and sideways in one set.
#pragma once

#include "dataset/geometry/geometry.h"

namespace lc2wf::test {

inline Camera turned_clockwise(const Camera& c) {
  Eigen::Matrix3d turn;
  turn << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  Camera t = c;
  t.K << c.K(1, 1), 0, c.height - 1 - c.K(1, 2), 0, c.K(0, 0), c.K(0, 2), 0, 0, 1;
  t.R = turn * c.R;
  t.t = turn * c.t;
  t.width = c.height;
  t.height = c.width;
  return t;
}

}  // namespace lc2wf::test
