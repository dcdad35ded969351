// Exact two-view geometry of the line triangulator: epipolar lines, ray-plane intersection, orientation filter.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "tools/render/camera_ring.h"
#include "tools/triangulation/epipolar.h"
#include "tools/triangulation/view_neighbours.h"

namespace lc2wf {
namespace {

Eigen::Matrix3d test_k() {
  Eigen::Matrix3d K;
  K << 800, 0, 511.5, 0, 800, 383.5, 0, 0, 1;
  return K;
}

Camera cam_at(const Vec3& c) { return look_at(c, Vec3(0, 0, 2), test_k(), 1024, 768); }

Vec3 homog(const Vec2& p) { return Vec3(p.x(), p.y(), 1.0); }

TEST(Epipolar, FundamentalMatrixMapsProjectionsOntoEpipolarLines) {
  const Camera a = cam_at(Vec3(20, -5, 10)), b = cam_at(Vec3(12, 15, 14));
  const Eigen::Matrix3d F = fundamental_matrix(a, b);
  for (int i = 0; i < 20; ++i) {
    const Vec3 X(std::sin(i) * 4, std::cos(3 * i) * 4, 2 + std::sin(7 * i));
    const Vec3 xa = homog(a.project(X)), xb = homog(b.project(X));
    EXPECT_LT(std::abs(xb.dot(F * xa)) / ((F * xa).head<2>().norm() * xb.norm()), 1e-9);
  }
}

TEST(Epipolar, OverlapIsIntersectionOverUnionAlongTheTargetLine) {
  // Identity-like geometry: a pure horizontal baseline makes epipolar lines horizontal, so the source
  // endpoints at rows y1, y2 cut a vertical target segment at exactly those rows.
  Camera a, b;
  a.K = b.K = test_k();
  b.t = Vec3(-1, 0, 0);
  const Eigen::Matrix3d F = fundamental_matrix(a, b);
  auto seg = [](double y0, double y1) { return Segment2{Vec2(100, y0), Vec2(130, y1)}; };
  const Segment2 target{Vec2(400, 0), Vec2(400, 10)};
  EXPECT_NEAR(epipolar_overlap(F, seg(0, 10), target), 1.0, 1e-12);
  EXPECT_NEAR(epipolar_overlap(F, seg(20, 30), target), 0.0, 1e-12);
  EXPECT_NEAR(epipolar_overlap(F, seg(2, 4), target), 0.2, 1e-12);
  EXPECT_NEAR(epipolar_overlap(F, seg(5, 15), target), 1.0 / 3.0, 1e-12);
  EXPECT_NEAR(epipolar_overlap(F, seg(15, 5), target), 1.0 / 3.0, 1e-12);
  EXPECT_NEAR(epipolar_overlap(F, seg(0.1, 0.5), Segment2{Vec2(400, 0), Vec2(400, 0.6)}), 0.0, 1e-12);
  // A target parallel to the epipolar lines has no finite intersection.
  EXPECT_EQ(epipolar_overlap(F, seg(0, 10), Segment2{Vec2(300, 5), Vec2(400, 5)}), 0.0);
}

TEST(Epipolar, RayPlaneDepthsReproduceTheEndpointsAndRespectTheAngleLimit) {
  const Camera a = cam_at(Vec3(20, -5, 10)), b = cam_at(Vec3(12, 15, 14));
  const Vec3 P(1, -2, 3.5), Q(-3, 2, 2.2);
  const Vec3 ra1 = pixel_ray(a, a.project(P)), ra2 = pixel_ray(a, a.project(Q));
  const Vec3 n = pixel_ray(b, b.project(P)).cross(pixel_ray(b, b.project(Q))).normalized();
  const auto d = ray_plane_depths(a.center(), ra1, ra2, b.center(), n, std::sin(1.0 * M_PI / 180));
  ASSERT_TRUE(d.has_value());
  EXPECT_LT((a.center() + (*d)[0] * ra1 - P).norm(), 1e-9 * P.norm());
  EXPECT_LT((a.center() + (*d)[1] * ra2 - Q).norm(), 1e-9 * Q.norm());
  EXPECT_NEAR((*d)[0], (P - a.center()).norm(), 1e-9);
  // A ray lying in the plane gives no depth.
  const Vec3 in_plane = n.unitOrthogonal();
  EXPECT_FALSE(ray_plane_depths(b.center(), in_plane, in_plane, b.center(), n, 0.01).has_value());
}

// A line parallel to the baseline (both cameras walk along it): the planes coincide, the endpoints pair up by
// their order along the line, whichever way round the target segment was detected.
TEST(Epipolar, EndpointDepthsPairTheEndpointsAlongALineInTheEpipolarPlane) {
  const Vec3 ca(-4, -20, 1.7), cb(3, -20, 1.7);
  const Vec3 P(-6, 0, 1.7 + 4), Q(5, 0, 1.7 + 4);  // in the plane of both centres, parallel to the walk
  auto ray = [](const Vec3& c, const Vec3& p) { return Vec3((p - c).normalized()); };
  for (bool reversed : {false, true}) {
    const Vec3 t1 = ray(cb, reversed ? Q : P), t2 = ray(cb, reversed ? P : Q);
    const auto d = endpoint_depths(ca, ray(ca, P), ray(ca, Q), cb, t1, t2, std::sin(1.0 * M_PI / 180));
    ASSERT_TRUE(d.has_value()) << reversed;
    EXPECT_NEAR((*d)[0], (P - ca).norm(), 1e-9) << reversed;
    EXPECT_NEAR((*d)[1], (Q - ca).norm(), 1e-9) << reversed;
  }
  // Rays within the angle limit of their partner give no depth; so does a point behind a camera.
  const Vec3 far_p = P + Vec3(0, 1e5, 0), far_q = Q + Vec3(0, 1e5, 0);
  EXPECT_FALSE(endpoint_depths(ca, ray(ca, far_p), ray(ca, far_q), cb, ray(cb, far_p), ray(cb, far_q), std::sin(1.0 * M_PI / 180)));
  EXPECT_FALSE(endpoint_depths(ca, ray(ca, P), ray(ca, Q), cb, -ray(cb, P), -ray(cb, Q), 0.0));
}

TEST(ViewNeighbours, PreferTheTargetAngleInsideTheBand) {
  std::vector<Camera> cams;
  for (int i = 0; i < 12; ++i) {
    const double az = i * 30.0 * M_PI / 180;
    cams.push_back(cam_at(Vec3(30 * std::cos(az), 30 * std::sin(az), 15)));
  }
  const Vec3 centre = optical_axes_centre(cams);
  EXPECT_NEAR(centre.x(), 0, 1e-6);
  EXPECT_NEAR(centre.y(), 0, 1e-6);
  NeighbourOptions o;
  o.count = 4;
  const auto nb = select_neighbours(cams, Vec3(0, 0, 2), o);
  // 30 degrees of azimuth is ~24 degrees at the scene centre: the two ring neighbours come first, then
  // the next two (~48 degrees); 90 degrees away is outside the 60-degree band.
  ASSERT_EQ(nb[0].size(), 4u);
  EXPECT_EQ((std::vector<int>{nb[0][0], nb[0][1]}), (std::vector<int>{1, 11}));
  EXPECT_EQ((std::vector<int>{nb[0][2], nb[0][3]}), (std::vector<int>{2, 10}));
  o.min_angle_deg = 70;
  EXPECT_THROW(o.Check(), std::invalid_argument);
}

}  // namespace
}  // namespace lc2wf
