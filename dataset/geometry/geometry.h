// Geometry types shared by the dataset layer, the dataset tools and inference. All coordinates are in
// metres unless a name says otherwise (Roof-Image raw units: 20 raw = 1 m).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

namespace lc2wf {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;

// Largest coordinate magnitude the readers accept (metres or raw units alike): far beyond any building or
// geo-referenced frame, small enough that differences, squared distances and projections never overflow.
constexpr double kMaxCoordinate = 1e9;
inline bool within_coordinate_limit(const Vec3& p) { return p.allFinite() && p.cwiseAbs().maxCoeff() <= kMaxCoordinate; }

// "X,Y,Z" as three finite numbers (a vector given on a command line); empty for anything else. sscanf reads
// "nan" and "inf": refused here like every other number.
inline std::optional<Vec3> parse_xyz(const std::string& text) {
  double x, y, z;
  char tail;
  if (std::sscanf(text.c_str(), "%lf,%lf,%lf%c", &x, &y, &z, &tail) != 3 || !Vec3(x, y, z).allFinite()) return std::nullopt;
  return Vec3(x, y, z);
}

// Pinhole camera in the OpenCV convention: x_cam = R * X_world + t, pixel = K * x_cam / z, with pixel
// (0,0) at the *centre* of the top-left pixel, x right, y down, z forward.
struct Camera {
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  int width = 0;
  int height = 0;

  Vec3 to_camera(const Vec3& world) const { return R * world + t; }
  Vec3 center() const { return -R.transpose() * t; }
  // Pixel of a point in front of the camera (z > 0); callers check depth with to_camera().
  Vec2 project(const Vec3& world) const {
    const Vec3 c = K * to_camera(world);
    return c.head<2>() / c.z();
  }
};

// Face labels of Roof-Image polyshapes.
enum class FaceLabel : uint8_t { Roof = 1, Base = 2, Wall = 3 };

// A closed polygon mesh (n-gon faces, 0-based vertex ids) with a label per face.
struct PolyMesh {
  std::vector<Vec3> vertices;
  std::vector<std::vector<int>> faces;
  std::vector<FaceLabel> labels;  // one per face; empty when the source has none (plain OBJ)
};

// Roof-Image meshes and the LC2WF release's line clouds: 20 raw units = 1 m (the release's thresholds, e.g.
// 5 raw = 0.25 m, follow from it). The one place this number is written.
inline constexpr double kRawUnitsPerMetre = 20.0;

// metres = (raw - origin_raw) / raw_per_metre; raw = metres * raw_per_metre + origin_raw.
struct UnitTransform {
  double raw_per_metre = 1.0;
  Vec3 origin_raw = Vec3::Zero();

  Vec3 to_metres(const Vec3& raw) const { return (raw - origin_raw) / raw_per_metre; }
  Vec3 to_raw(const Vec3& metres) const { return metres * raw_per_metre + origin_raw; }
};

// Junctions + undirected edges (index pairs, stored with a < b, unique).
struct Wireframe {
  std::vector<Vec3> junctions;
  std::vector<std::array<int, 2>> edges;
};

struct Segment3 {
  Vec3 a = Vec3::Zero();
  Vec3 b = Vec3::Zero();
  double length() const { return (b - a).norm(); }
};

struct Segment2 {
  Vec2 a = Vec2::Zero();
  Vec2 b = Vec2::Zero();
  double length() const { return (b - a).norm(); }
};

}  // namespace lc2wf
