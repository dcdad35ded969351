// The `--textures photo` look: deterministic renders, clutter that is never GT, windows on the walls by
// storey whatever the building's size.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <string>
#include <tuple>
#include <vector>
#include <opencv2/core.hpp>

#include "dataset/synthetic/synthetic_building.h"
#include "tools/pipeline/cloud_builder.h"
#include "tools/render/camera_ring.h"
#include "tools/render/face_frames.h"
#include "tools/render/photo_scene.h"
#include "tools/render/raster_renderer.h"

namespace lc2wf {
namespace {

Building house(double length, double width, double eave, const std::string& name = "house") {
  RectBuildingSpec spec;
  spec.length = length;
  spec.width = width;
  spec.eave_height = eave;
  spec.west = RoofEnd::Gable;
  return make_rect_building(name, spec);
}

std::vector<Vec3> centres(const std::vector<Camera>& cams) {
  std::vector<Vec3> out;
  for (const Camera& c : cams) out.push_back(c.center());
  return out;
}

bool inside_polygon(const std::vector<Vec2>& poly, const Vec2& p) {
  bool in = false;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++)
    if ((poly[i].y() > p.y()) != (poly[j].y() > p.y()) &&
        p.x() < (poly[j].x() - poly[i].x()) * (p.y() - poly[i].y()) / (poly[j].y() - poly[i].y()) + poly[i].x())
      in = !in;
  return in;
}

double point_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 d = b - a;
  const double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (p - a - t * d).norm();
}

TEST(PhotoScene, SameSeedSameImageBytes) {
  const Building b = house(12, 9, 6);
  CameraRingOptions ring;
  ring.views = 2;
  const auto cams = make_camera_ring(b.mesh.vertices, ring);
  RasterOptions ro;
  ro.textures = "photo";
  ro.seed = 21;
  auto render = [&](uint64_t seed) {
    ro.seed = seed;
    const PhotoScene scene = make_photo_scene(b.mesh, centres(cams), PhotoOptions{}, seed);
    return RasterRenderer(b.mesh, ro, scene).render(cams[1], 1).image;
  };
  const cv::Mat a = render(21), again = render(21), other = render(22);
  ASSERT_EQ(a.type(), CV_8UC3);
  EXPECT_EQ(cv::norm(a, again, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(a, other, cv::NORM_L1), 0.0);
  // Paper stays the default; photo is a different picture of the same building.
  RasterOptions paper;
  paper.seed = 21;
  EXPECT_GT(cv::norm(a, RasterRenderer(b.mesh, paper).render(cams[1], 1).image, cv::NORM_L1), 0.0);
  ro.seed = 21;
  ro.textures = "oil";
  EXPECT_THROW(RasterRenderer(b.mesh, ro), std::invalid_argument);
}

TEST(PhotoScene, WindowsByStoreyOnTheFacadesOfAShedAndATower) {
  for (const auto& [eave, min_storeys, max_storeys] : {std::tuple{3.0, 1, 1}, std::tuple{40.0, 12, 14}}) {
    const Building b = house(eave > 10 ? 20 : 4, eave > 10 ? 16 : 3.5, eave, "b");
    const FacedMesh fm = build_faced_mesh(b.mesh);
    const auto layouts = layout_facades(b.mesh, fm.frames, FacadeOptions{}, 5);
    int walls_with_windows = 0;
    for (size_t f = 0; f < layouts.size(); ++f) {
      const FacadeLayout& L = layouts[f];
      if (!L.wall) continue;
      EXPECT_GE(L.storeys, min_storeys) << eave;
      EXPECT_LE(L.storeys, max_storeys) << eave;
      EXPECT_NEAR(L.storey_height, 3.0, 0.5) << eave;
      if (!L.windows.empty()) ++walls_with_windows;
      std::vector<int> per_storey(L.storeys, 0);
      for (int s : L.window_storey) ++per_storey[s];
      for (int s = 1; s < L.storeys; ++s) EXPECT_GT(per_storey[s], 0) << "eave " << eave << " storey " << s;  // ground floor may be a door
      // Every window corner lies on the face: in its plane and inside its polygon.
      const FaceFrame& fr = fm.frames[f];
      std::vector<Vec2> poly;
      for (int v : b.mesh.faces[f]) poly.emplace_back((b.mesh.vertices[v] - fr.origin).dot(fr.axis_u), b.mesh.vertices[v].z());
      for (const FacadeRect& r : L.windows)
        for (double u : {r.u0, r.u1})
          for (double z : {r.z0, r.z1}) {
            EXPECT_TRUE(inside_polygon(poly, Vec2(u, z))) << u << " " << z;
            const Vec3 X = fr.origin + u * fr.axis_u + (z - fr.origin.z()) / fr.axis_v.z() * fr.axis_v;
            EXPECT_NEAR(fr.normal.dot(X), fr.offset, 1e-9);
          }
    }
    EXPECT_GE(walls_with_windows, 2) << eave;
  }
}

TEST(PhotoScene, ClutterKeepsClearOfCamerasAndIsNeverGt) {
  const Building b = house(12, 9, 6);
  CameraRingOptions ring;
  ring.views = 16;
  ring.width = 480;
  ring.height = 360;
  ring.seed = 4;
  const auto cams = make_camera_ring(b.mesh.vertices, ring);
  PhotoOptions po;
  po.trees = false;  // trees may hide most of a small test's lines
  PhotoScene scene;
  for (uint64_t seed = 1; seed < 40; ++seed) {  // a scene with a chimney: roof clutter right beside GT edges
    scene = make_photo_scene(b.mesh, centres(cams), po, seed);
    if (std::count(scene.kinds.begin(), scene.kinds.end(), ClutterKind::Chimney) > 0) break;
  }
  ASSERT_GT(std::count(scene.kinds.begin(), scene.kinds.end(), ClutterKind::Chimney), 0);
  ASSERT_GT(scene.clutter.faces.size(), 20u);
  // Object bounds, and no camera inside any object.
  std::map<uint32_t, std::pair<Vec3, Vec3>> boxes;
  for (size_t f = 0; f < scene.clutter.faces.size(); ++f)
    for (int v : scene.clutter.faces[f]) {
      auto [it, fresh] = boxes.try_emplace(scene.objects[f], scene.clutter.vertices[v], scene.clutter.vertices[v]);
      it->second.first = it->second.first.cwiseMin(scene.clutter.vertices[v]);
      it->second.second = it->second.second.cwiseMax(scene.clutter.vertices[v]);
    }
  for (const Vec3& c : centres(cams))
    for (const auto& [id, box] : boxes) EXPECT_FALSE((c.array() >= box.first.array()).all() && (c.array() <= box.second.array()).all());

  RasterOptions ro;
  ro.textures = "photo";
  ro.seed = 7;
  const RasterRenderer renderer(b.mesh, ro, scene);
  std::vector<RenderedView> views;
  for (size_t v = 0; v < cams.size(); ++v) views.push_back({renderer.render(cams[v], v).image, cams[v]});
  const PolyMesh occluders = scene_mesh(b.mesh, scene);
  const LineCloud cloud = build_line_cloud(b, views, CloudBuilderOptions{}, nullptr, &occluders);
  int on_clutter = 0, positives = 0;
  for (size_t i = 0; i < cloud.segments.size(); ++i) {
    positives += cloud.labels[i].f;
    const Segment3& s = cloud.segments[i];
    double to_gt = 1e300;
    for (const auto& e : cloud.wireframe.edges) {
      const Vec3 &a = cloud.wireframe.junctions[e[0]], &c = cloud.wireframe.junctions[e[1]];
      to_gt = std::min(to_gt, std::max(point_segment(s.a, a, c), point_segment(s.b, a, c)));
    }
    bool inside = false;
    for (const auto& [id, box] : boxes)
      inside |= (s.a.array() >= box.first.array() - 0.1).all() && (s.a.array() <= box.second.array() + 0.1).all() &&
                (s.b.array() >= box.first.array() - 0.1).all() && (s.b.array() <= box.second.array() + 0.1).all();
    if (!inside || to_gt < 0.3) continue;
    ++on_clutter;
    EXPECT_EQ(cloud.labels[i].f, 0) << "a clutter line labelled GT, " << to_gt << " m from the wireframe";
  }
  EXPECT_GT(on_clutter, 10);
  EXPECT_GT(positives, 20);
}

TEST(PhotoScene, OptionChecksNameTheField) {
  PhotoOptions o;
  o.facades.storey_height_m = 0;
  try {
    o.Check();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("FacadeOptions.storey_height_m"), std::string::npos);
  }
  o = PhotoOptions{};
  o.exposure_stops = -1;
  EXPECT_THROW(o.Check(), std::invalid_argument);
  o = PhotoOptions{};
  o.noise_gain = 0.5;
  EXPECT_THROW(o.Check(), std::invalid_argument);
}

}  // namespace
}  // namespace lc2wf
