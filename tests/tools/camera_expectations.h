// Checks on rendered cameras shared by the camera-ring and capture tests: one definition of "frames the
// building" (every point in front of the camera and inside the image, away from the border by the margin).
#pragma once

#include <gtest/gtest.h>

#include <vector>

#include "tools/render/camera_ring.h"

namespace lc2wf {

inline void expect_frames_every_point(const Camera& c, const std::vector<Vec3>& points, const CameraRingOptions& o) {
  for (const Vec3& v : points) {
    ASSERT_GT(c.to_camera(v).z(), 0);
    const Vec2 p = c.project(v);
    EXPECT_GE(p.x(), o.margin * o.width - 0.5 - 1e-6);
    EXPECT_LE(p.x(), o.width * (1 - o.margin) - 0.5 + 1e-6);
    EXPECT_GE(p.y(), o.margin * o.height - 0.5 - 1e-6);
    EXPECT_LE(p.y(), o.height * (1 - o.margin) - 0.5 + 1e-6);
  }
}

}  // namespace lc2wf
