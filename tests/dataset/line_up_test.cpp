// Up from a map's lines alone (dataset/photo/line_up.h): a box's outline by the perpendicular share of its
// lines, facades seen from the street (more vertical lines than horizontal, one plane) only with a height
// model's clouds, the ground at the bottom, in any frame.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "dataset/photo/line_height.h"
#include "dataset/photo/line_up.h"
#include "tests/common/windowed_box.h"

namespace lc2wf {
namespace {

using test::street_facade;
using test::street_facade_model;

std::vector<Segment3> turned(const std::vector<Segment3>& s, const Eigen::Matrix3d& R, double scale) {
  std::vector<Segment3> out;
  for (const Segment3& x : s) out.push_back({scale * (R * x.a) + Vec3(40, -7, 3), scale * (R * x.b) + Vec3(40, -7, 3)});
  return out;
}

// A few frames a map may come in: z up, y down (photogrammetry), and two oblique ones.
std::vector<Eigen::Matrix3d> frames() {
  return {Eigen::Matrix3d::Identity(), Eigen::Matrix3d(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX())),
          Eigen::Matrix3d(Eigen::AngleAxisd(2.1, Vec3(0.3, -0.5, 0.8).normalized())),
          Eigen::Matrix3d(Eigen::AngleAxisd(-0.9, Vec3(1, 2, -0.5).normalized()))};
}

double degrees_between(const Vec3& a, const Vec3& b) { return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180 / M_PI; }

// A box's outline (eaves, base, corners): most of its length is horizontal.
std::vector<Segment3> box_outline(double w, double d, double h) {
  const Vec3 c[4] = {{0, 0, 0}, {w, 0, 0}, {w, d, 0}, {0, d, 0}};
  std::vector<Segment3> s;
  for (int k = 0; k < 4; ++k) {
    s.push_back({c[k], c[(k + 1) % 4]});
    s.push_back({c[k] + Vec3(0, 0, h), c[(k + 1) % 4] + Vec3(0, 0, h)});
    s.push_back({c[k], c[k] + Vec3(0, 0, h)});
    s.push_back({c[k] + Vec3(0.3 * w, 0, 0), c[k] + Vec3(0.3 * w, 0, 0)});  // a zero-length line is ignored
  }
  for (int g = 0; g < 8; ++g) s.push_back({Vec3(-3.0 - g, -2, 0), Vec3(w + 3.0 + g, -2 - g, 0)});  // ground lines
  return s;
}

// Without a height model the vertical is what most of the line length is perpendicular to (right for a box's
// outline, where the eaves, base and ground lines outweigh the corners).
TEST(LineUp, WithoutAModelByThePerpendicularShare) {
  const std::vector<Segment3> box = box_outline(20, 12, 9);
  for (const Eigen::Matrix3d& R : frames()) {
    const LineUp u = up_from_lines(turned(box, R, 0.3));
    EXPECT_LT(degrees_between(u.up, R * Vec3::UnitZ()), 3.0);  // the sign too: the ground lines at the bottom
    EXPECT_FALSE(u.by_statistics);
    EXPECT_GE(u.tried.size(), 3u);
    EXPECT_GT(u.perpendicular_share, 0.6);
  }
}

// From the street the facade's normal is what most lines are perpendicular to; the statistics of a building
// seen the right way up tell the vertical apart from it and from the street's direction.
TEST(LineUp, FacadesFromTheStreetByTheHeightModelsClouds) {
  const HeightModel model = street_facade_model();
  for (const auto& [storeys, w] : {std::pair{4, 22.0}, std::pair{2, 13.0}, std::pair{6, 40.0}}) {
    const std::vector<Segment3> facade = street_facade(storeys, 3.2, w, 99 + storeys);
    for (const Eigen::Matrix3d& R : frames()) {
      const std::vector<Segment3> map = turned(facade, R, 2.5);
      const LineUp u = up_from_lines(map, &model);
      EXPECT_LT(degrees_between(u.up, R * Vec3::UnitZ()), 3.0) << storeys << " storeys, " << w << " m";
      EXPECT_TRUE(u.by_statistics);
      EXPECT_LT(u.distance, u.runner_up_distance);
      // Without the model the rule of whole buildings takes the facade's normal: why the model is asked.
      EXPECT_GT(degrees_between(up_from_lines(map).up, R * Vec3::UnitZ()), 45.0);
    }
  }
}

// A map of the facade alone (no street in front, as Line3D++ maps of one facade come) is thinnest along the
// facade's normal: that way up is the lowest, and must still not win.
TEST(LineUp, AFacadeWithoutTheStreetStandsUp) {
  const HeightModel model = street_facade_model();
  const std::vector<Segment3> facade = street_facade(3, 3.1, 26, 41, false);
  for (const Eigen::Matrix3d& R : frames()) {
    const LineUp u = up_from_lines(turned(facade, R, 0.7), &model);
    EXPECT_LT(degrees_between(u.up, R * Vec3::UnitZ()), 3.0);
  }
}

// A square lattice of equal lines looks the same stood on either side: the up is flagged as uncertain; a
// street facade's is not.
TEST(LineUp, ALatticeIsUncertainAFacadeIsNot) {
  const HeightModel model = street_facade_model();
  std::vector<Segment3> lattice;
  for (int k = 0; k <= 12; ++k) {
    lattice.push_back({Vec3(k * 1.5, 0, 0), Vec3(k * 1.5, 0, 18)});
    lattice.push_back({Vec3(0, 0, k * 1.5), Vec3(18, 0, k * 1.5)});
  }
  const LineUp square = up_from_lines(lattice, &model);
  EXPECT_TRUE(square.by_statistics);
  EXPECT_TRUE(square.uncertain);
  EXPECT_LT(square.runner_up_distance - square.distance, kUncertainUpMargin * square.distance);
  // Every candidate is kept with its distance; the runner-up is the other axis of the lattice's plane.
  ASSERT_GE(square.tried.size(), 2u);
  int at_best = 0, at_runner_up = 0;
  for (const UpCandidate& c : square.tried) {
    at_best += c.distance == square.distance && std::abs(c.direction.dot(square.up)) > 0.999;
    at_runner_up += c.distance == square.runner_up_distance && std::abs(c.direction.dot(square.runner_up)) > 0.999;
  }
  EXPECT_EQ(at_best, 1);
  EXPECT_EQ(at_runner_up, 1);
  EXPECT_LT(std::abs(square.runner_up.dot(square.up)), 0.2);
  EXPECT_LT(std::abs(square.runner_up.y()), 0.05);
  const LineUp facade = up_from_lines(street_facade(4, 3.0, 20, 8), &model);
  EXPECT_FALSE(facade.uncertain);
  EXPECT_FALSE(up_from_lines(lattice).uncertain);  // without a model nothing is compared
}

TEST(LineUp, NoLineIsAnError) {
  EXPECT_THROW(up_from_lines({}), std::invalid_argument);
  EXPECT_THROW(up_from_lines({{Vec3(1, 2, 3), Vec3(1, 2, 3)}}), std::invalid_argument);
}

}  // namespace
}  // namespace lc2wf
