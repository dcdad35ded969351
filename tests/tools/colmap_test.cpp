// COLMAP text-model conversion (quaternions, +0.5 pixel origin) and pose alignment; COLMAP itself is
// not run here.
#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "dataset/formats/errors.h"
#include "tools/colmap/colmap_poses.h"
#include "tools/render/camera_ring.h"

namespace lc2wf {
namespace {
namespace fs = std::filesystem;

std::vector<Camera> ring(int n) {
  Eigen::Matrix3d K;
  K << 622.2, 0, 319.5, 0, 622.2, 239.5, 0, 0, 1;
  std::vector<Camera> cams;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    cams.push_back(look_at(Vec3(25 * std::cos(a), 25 * std::sin(a), 8 + i % 3 * 4), Vec3(0, 0, 2), K, 640, 480));
  }
  return cams;
}

// Large photos: SIFT at a bounded size, and the image doubled only where it was not scaled down.
TEST(ColmapPoses, FirstOctaveDoublesOnlyPhotosWithinTheSizeCap) {
  ColmapOptions o;  // max_image_size 1600
  EXPECT_EQ(sift_first_octave(o, 640), -1);
  EXPECT_EQ(sift_first_octave(o, 1600), -1);
  EXPECT_EQ(sift_first_octave(o, 4000), 0);
  o.first_octave = -1;  // asked for: kept
  EXPECT_EQ(sift_first_octave(o, 4000), -1);
  EXPECT_NO_THROW(o.Check());
  o.first_octave = 3;
  EXPECT_THROW(o.Check(), std::invalid_argument);
  o.first_octave.reset();
  o.max_image_size = 50;
  EXPECT_THROW(o.Check(), std::invalid_argument);
}

TEST(ColmapPoses, QuaternionRoundTripIsNotTheConjugate) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Vector4d q = rotation_to_quaternion(R);
  EXPECT_GE(q[0], 0);
  EXPECT_LT((quaternion_to_rotation(q[0], q[1], q[2], q[3]) - R).norm(), 1e-12);
  // The conjugate is the inverse rotation: a wrong sign convention would be caught here.
  EXPECT_GT((quaternion_to_rotation(q[0], -q[1], -q[2], -q[3]) - R).norm(), 0.1);
  // COLMAP's documented example: a 90-degree turn about z.
  EXPECT_LT((quaternion_to_rotation(std::sqrt(0.5), 0, 0, std::sqrt(0.5)) * Vec3(1, 0, 0) - Vec3(0, 1, 0)).norm(), 1e-12);
}

TEST(ColmapPoses, ReadsTextModelsWithTheHalfPixelShift) {
  const fs::path dir = fs::path(testing::TempDir()) / ("lc2wf_colmap_model_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const auto cams = ring(3);
  {
    std::ofstream c(dir / "cameras.txt");
    c << "# Camera list\n1 PINHOLE 640 480 622.2 622.2 320 240\n";
    std::ofstream im(dir / "images.txt");
    im.precision(17);
    im << "# Image list\n";
    for (int i = 0; i < 3; ++i) {
      const auto q = rotation_to_quaternion(cams[i].R);
      im << i + 1 << " " << q[0] << " " << q[1] << " " << q[2] << " " << q[3] << " " << cams[i].t.x() << " " << cams[i].t.y() << " "
         << cams[i].t.z() << " 1 view_00" << i << ".png\n";
      im << (i == 1 ? "10.5 20.5 -1\n" : "\n");
    }
  }
  const auto model = read_colmap_text_model(dir);
  ASSERT_EQ(model.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(model[i].name, "view_00" + std::to_string(i) + ".png");
    EXPECT_LT((model[i].camera.K - cams[i].K).norm(), 1e-9);
    EXPECT_LT((model[i].camera.R - cams[i].R).norm(), 1e-12);
    EXPECT_LT((model[i].camera.t - cams[i].t).norm(), 1e-12);
  }
  std::ofstream(dir / "cameras.txt") << "1 OPENCV 640 480 1 1 1 1 0.1 0 0 0\n";
  EXPECT_THROW(read_colmap_text_model(dir), DataError);
}

TEST(ColmapPoses, AlignmentUndoesASimilarityAndMeasuresErrors) {
  const auto ref = ring(8);
  // The same cameras in a frame rotated, scaled by 0.1 and shifted, as SfM would return them.
  const Eigen::Matrix3d Q = Eigen::AngleAxisd(1.1, Vec3(0.3, -1, 0.2).normalized()).toRotationMatrix();
  const double s = 0.1;
  const Vec3 shift(3, -2, 5);
  std::vector<std::optional<Camera>> est(ref.size());
  for (size_t i = 0; i < ref.size(); ++i) {
    if (i == 4) continue;  // one view not registered
    Camera c = ref[i];
    const Vec3 C = s * Q * ref[i].center() + shift;
    c.R = ref[i].R * Q.transpose();
    c.t = -c.R * C;
    est[i] = c;
  }
  const PoseComparison pc = align_to_reference(ref, est);
  EXPECT_EQ(pc.registered, 7);
  EXPECT_NEAR(pc.scale, 10.0, 1e-9);
  EXPECT_LT(pc.max_centre_error, 1e-9);
  EXPECT_LT(pc.max_rotation_deg, 1e-6);
  EXPECT_LT((est[0]->R - ref[0].R).norm(), 1e-9);
  std::vector<std::optional<Camera>> too_few(ref.size());
  too_few[0] = ref[0];
  EXPECT_THROW(align_to_reference(ref, too_few), std::invalid_argument);
}

// A walk down a street: the centres lie on one line and leave the turn about it free; the cameras' axes fix it.
TEST(ColmapPoses, AlignmentOfCamerasOnOneLineKeepsTheirTurn) {
  Eigen::Matrix3d K;
  K << 500, 0, 320, 0, 500, 240, 0, 0, 1;
  std::vector<Camera> ref;
  for (int i = 0; i < 8; ++i) ref.push_back(look_at(Vec3(-14.0 + 4.0 * i, -20, 1.7), Vec3(0, 0, 5), K, 640, 480));
  const Eigen::Matrix3d Q = Eigen::AngleAxisd(0.7, Vec3(0.2, 1, -0.4).normalized()).toRotationMatrix();
  std::vector<std::optional<Camera>> est(ref.size());
  for (size_t i = 0; i < ref.size(); ++i) {
    Camera c = ref[i];
    const Vec3 C = 0.3 * Q * ref[i].center() + Vec3(1, 2, 3);
    c.R = ref[i].R * Q.transpose();
    c.t = -c.R * C;
    est[i] = c;
  }
  const PoseComparison pc = align_to_reference(ref, est);
  EXPECT_NEAR(pc.scale, 1.0 / 0.3, 1e-9);
  EXPECT_LT(pc.max_centre_error, 1e-9);
  EXPECT_LT(pc.max_rotation_deg, 1e-6);
}

TEST(ColmapPoses, AimPointAndPerViewErrors) {
  const auto ref = ring(6);
  EXPECT_LT((common_aim_point(ref) - Vec3(0, 0, 2)).norm(), 1e-9);
  std::vector<std::optional<Camera>> est(ref.begin(), ref.end());
  est[1].reset();
  const PoseComparison pc = align_to_reference(ref, est);
  ASSERT_EQ(pc.centre_error.size(), 6u);
  EXPECT_TRUE(std::isnan(pc.centre_error[1]) && std::isnan(pc.rotation_deg[1]));
  EXPECT_LT(pc.centre_error[0], 1e-9);
  // Ring radius 25 at heights 8, 12, 16 around an aim point at height 2.
  EXPECT_NEAR(pc.camera_distance, std::hypot(25.0, 10.0), 1e-9);
}

TEST(ColmapPoses, OutlierRoundsLeaveAFlippedViewOutOfTheFit) {
  const auto ref = ring(10);
  // View 3 placed on the opposite side of the house and turned by 180 degrees, as symmetric scenes do.
  const Eigen::Matrix3d half_turn = Eigen::AngleAxisd(M_PI, Vec3::UnitZ()).toRotationMatrix();
  std::vector<std::optional<Camera>> plain(ref.begin(), ref.end());
  Camera& flipped = *plain[3];
  const Vec3 C = half_turn * ref[3].center();
  flipped.R = ref[3].R * half_turn.transpose();
  flipped.t = -flipped.R * C;
  auto robust = plain;
  const PoseComparison all = align_to_reference(ref, plain);
  EXPECT_EQ(all.inliers, 10);
  EXPECT_GT(all.median_centre_error, 0.5);  // the flipped view drags every other view off
  AlignOptions options;
  options.outlier_factor = 3;
  const PoseComparison pc = align_to_reference(ref, robust, options);
  EXPECT_EQ(pc.inliers, 9);
  EXPECT_EQ(pc.registered, 10);
  EXPECT_LT(pc.median_centre_error, 1e-9);
  EXPECT_NEAR(pc.rotation_deg[3], 180.0, 1e-6);
  EXPECT_NEAR(pc.max_rotation_deg, 180.0, 1e-6);
  EXPECT_GT(pc.centre_error[3], 40.0);
  options.outlier_factor = 0.5;
  EXPECT_THROW(options.Check(), std::invalid_argument);
}

}  // namespace
}  // namespace lc2wf
