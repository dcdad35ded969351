// Per-face plane, orientation and texture frame of a polygon mesh, plus the triangles that cover each
// face (ear clipping in the face plane). Shared by the rasteriser and the GT visibility test.
#pragma once

#include <array>
#include <vector>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

// How a face is textured: derived from its label and orientation (gable ends are labelled roof but are
// vertical, so they look like walls).
enum class SurfaceKind : uint8_t { SlopedRoof, FlatRoof, Wall, Base };

struct FaceFrame {
  Vec3 normal = Vec3::UnitZ();  // unit, sign arbitrary (callers orient it towards the viewer)
  double offset = 0.0;          // plane: normal . X = offset
  Vec3 origin = Vec3::Zero();   // first vertex; texture coordinates are relative to it
  Vec3 axis_u = Vec3::UnitX();  // in-plane, horizontal where possible
  Vec3 axis_v = Vec3::UnitY();  // in-plane, down the slope for sloped roofs, down (-z) for walls
  SurfaceKind kind = SurfaceKind::Wall;
  // Per-face shift of the texture pattern (metres): symmetric faces must not look identical, or SfM
  // (COLMAP) matches opposite sides of the building.
  Vec2 texture_offset = Vec2::Zero();
};

struct MeshTriangle {
  std::array<int, 3> v{};  // vertex ids
  int face = 0;
};

struct FacedMesh {
  std::vector<Vec3> vertices;
  std::vector<FaceFrame> frames;       // one per face
  std::vector<MeshTriangle> triangles;  // covering every face
  Vec3 box_min = Vec3::Zero();
  Vec3 box_max = Vec3::Zero();
};

// Throws std::invalid_argument when the mesh has no faces, a face with < 3 vertices or a bad vertex id.
FacedMesh build_faced_mesh(const PolyMesh& mesh);

// Triangulates one simple polygon given by 2D points; returns index triples into `poly`.
std::vector<std::array<int, 3>> ear_clip(const std::vector<Vec2>& poly);

}  // namespace lc2wf
