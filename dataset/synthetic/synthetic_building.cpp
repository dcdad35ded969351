#include "dataset/synthetic/synthetic_building.h"

#include "dataset/sampling/rng.h"

#include <cmath>
#include <stdexcept>

namespace lc2wf {
namespace {

void check_common(const char* type, double eave, double slope_deg) {
  if (!(eave > 0)) throw std::invalid_argument(std::string(type) + ".eave_height must be > 0");
  if (!(slope_deg > 0 && slope_deg < 80)) throw std::invalid_argument(std::string(type) + ".slope_deg must be in (0, 80)");
}

// Walls [top_i, bottom_i, bottom_i+1, top_i+1] and the base polygon for an outline whose top vertices are
// ids 0..n-1 and bottom copies ids first_bottom..first_bottom+n-1.
void add_walls_and_base(PolyMesh& m, int n, int first_bottom) {
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    m.faces.push_back({i, first_bottom + i, first_bottom + j, j});
    m.labels.push_back(FaceLabel::Wall);
  }
  std::vector<int> base;
  for (int i = n - 1; i >= 0; --i) base.push_back(first_bottom + i);
  m.faces.push_back(base);
  m.labels.push_back(FaceLabel::Base);
}

Building to_building(const std::string& name, PolyMesh m) {
  for (auto& v : m.vertices) v *= kRawUnitsPerMetre;
  BuildingOptions opt;
  opt.raw_per_metre = kRawUnitsPerMetre;
  return make_building(name, std::move(m), opt);
}

}  // namespace

void RectBuildingSpec::Check() const {
  if (!(width > 0)) throw std::invalid_argument("RectBuildingSpec.width must be > 0");
  if (!(length >= width)) throw std::invalid_argument("RectBuildingSpec.length must be >= width");
  if ((west == RoofEnd::Hip || east == RoofEnd::Hip) && !(length >= width + 0.5)) {
    throw std::invalid_argument("RectBuildingSpec.length must exceed width by >= 0.5 m for a hip end");
  }
  check_common("RectBuildingSpec", eave_height, slope_deg);
}

void LBuildingSpec::Check() const {
  if (!(wing > 0)) throw std::invalid_argument("LBuildingSpec.wing must be > 0");
  if (!(length_x >= wing + 1.0)) throw std::invalid_argument("LBuildingSpec.length_x must be >= wing + 1 m");
  if (!(length_y >= wing + 1.0)) throw std::invalid_argument("LBuildingSpec.length_y must be >= wing + 1 m");
  check_common("LBuildingSpec", eave_height, slope_deg);
}

PolyMesh make_rect_mesh(const RectBuildingSpec& s) {
  s.Check();
  const double L = s.length, W = s.width, H = s.eave_height;
  const double ridge = H + std::tan(s.slope_deg * M_PI / 180.0) * W / 2;
  const double xw = s.west == RoofEnd::Hip ? -L / 2 + W / 2 : -L / 2;
  const double xe = s.east == RoofEnd::Hip ? L / 2 - W / 2 : L / 2;
  PolyMesh m;
  m.vertices = {{-L / 2, -W / 2, H}, {L / 2, -W / 2, H}, {L / 2, W / 2, H}, {-L / 2, W / 2, H},
                {xw, 0, ridge},      {xe, 0, ridge},
                {-L / 2, -W / 2, 0}, {L / 2, -W / 2, 0}, {L / 2, W / 2, 0}, {-L / 2, W / 2, 0}};
  m.faces = {{0, 1, 5, 4}, {1, 2, 5}, {2, 3, 4, 5}, {3, 0, 4}};
  m.labels.assign(4, FaceLabel::Roof);
  add_walls_and_base(m, 4, 6);
  return m;
}

PolyMesh make_l_mesh(const LBuildingSpec& s) {
  s.Check();
  const double a = s.length_x, b = s.length_y, w = s.wing, H = s.eave_height;
  const double ridge = H + std::tan(s.slope_deg * M_PI / 180.0) * w / 2;
  PolyMesh m;
  m.vertices = {{0, 0, H}, {a, 0, H}, {a, w, H}, {w, w, H}, {w, b, H}, {0, b, H},
                {w / 2, w / 2, ridge},
                {s.end_x == RoofEnd::Hip ? a - w / 2 : a, w / 2, ridge},
                {w / 2, s.end_y == RoofEnd::Hip ? b - w / 2 : b, ridge}};
  for (int i = 0; i < 6; ++i) m.vertices.push_back(Vec3(m.vertices[i].x(), m.vertices[i].y(), 0));
  m.faces = {{0, 1, 7, 6}, {1, 2, 7}, {2, 3, 6, 7}, {3, 4, 8, 6}, {4, 5, 8}, {5, 0, 6, 8}};
  m.labels.assign(6, FaceLabel::Roof);
  add_walls_and_base(m, 6, 9);
  return m;
}

Building make_rect_building(const std::string& name, const RectBuildingSpec& spec) {
  return to_building(name, make_rect_mesh(spec));
}

Building make_l_building(const std::string& name, const LBuildingSpec& spec) {
  return to_building(name, make_l_mesh(spec));
}

Building make_random_building(uint64_t seed, const std::string& name) {
  DataRng rng(seed);
  auto uni = [&](double lo, double hi) { return rng.uniform(lo, hi); };
  auto end = [&] { return rng.uniform() < 0.7 ? RoofEnd::Hip : RoofEnd::Gable; };  // Roof-Image is mostly hip
  const double slope = uni(30.0, 46.0);
  if (rng.uniform() < 0.5) {
    RectBuildingSpec s;
    s.width = uni(9.5, 14.0);
    s.length = s.width + uni(1.0, 12.0);
    s.slope_deg = slope;
    s.west = end();
    s.east = end();
    return make_rect_building(name, s);
  }
  LBuildingSpec s;
  s.wing = uni(7.0, 10.0);
  s.length_x = s.wing + uni(4.0, 12.0);
  s.length_y = s.wing + uni(4.0, 10.0);
  s.slope_deg = slope;
  s.end_x = end();
  s.end_y = end();
  return make_l_building(name, s);
}

}  // namespace lc2wf
