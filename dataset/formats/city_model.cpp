#include "dataset/formats/city_model.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <regex>

namespace lc2wf {

CitySurface city_surface_of(const std::string& city_type) {
  if (city_type.empty()) return CitySurface::kUnknown;
  if (city_type == "RoofSurface") return CitySurface::kRoof;
  if (city_type == "GroundSurface") return CitySurface::kGround;
  return CitySurface::kWall;
}

std::string normalise_lod2(const std::string& lod) {
  static const std::regex two(R"(\s*2(\.([0-9]))?0*\s*)");
  std::smatch m;
  if (!std::regex_match(lod, m, two)) return {};
  if (!m[2].matched || m[2].str() == "0") return "2";
  return "2." + m[2].str();
}

const CityLodGeometry* select_lod(const CityBuilding& building, const std::string& lod) {
  if (lod.empty()) return building.lods.empty() ? nullptr : &building.lods.front();
  const std::string want = normalise_lod2(lod);
  for (const auto& g : building.lods)
    if (g.lod == want) return &g;
  return nullptr;
}

bool is_geographic_crs(const std::string& crs_name) {
  // Geographic 2D/3D CRSs that city models use: WGS84, ETRS89, JGD2000/2011, NAD83, GDA94/2020, NZGD2000.
  static const int kGeographic[] = {4326, 4979, 4258, 4937, 4612, 6668, 6697, 4269, 4283, 7843, 4167, 4019};
  static const std::regex code(R"((?:EPSG|epsg).*?([0-9]{4,6})\s*$)");
  std::smatch m;
  const std::string s = crs_name.substr(0, 512);
  if (!std::regex_search(s, m, code)) return false;
  const int c = std::stoi(m[1].str());
  return std::find(std::begin(kGeographic), std::end(kGeographic), c) != std::end(kGeographic);
}

namespace {

// Earth-centred coordinates on the GRS80 ellipsoid.
Vec3 ecef(double lat_deg, double lon_deg, double h) {
  constexpr double a = 6378137.0, f = 1.0 / 298.257222101, e2 = f * (2 - f);
  const double lat = lat_deg * M_PI / 180, lon = lon_deg * M_PI / 180;
  const double n = a / std::sqrt(1 - e2 * std::sin(lat) * std::sin(lat));
  return {(n + h) * std::cos(lat) * std::cos(lon), (n + h) * std::cos(lat) * std::sin(lon), (n * (1 - e2) + h) * std::sin(lat)};
}

}  // namespace

Vec3 TangentPlane::to_local(double lat_deg, double lon_deg, double h) const {
  const double lat = lat0_deg * M_PI / 180, lon = lon0_deg * M_PI / 180;
  const Vec3 d = ecef(lat_deg, lon_deg, h) - ecef(lat0_deg, lon0_deg, h0);
  const Vec3 east(-std::sin(lon), std::cos(lon), 0);
  const Vec3 north(-std::sin(lat) * std::cos(lon), -std::sin(lat) * std::sin(lon), std::cos(lat));
  const Vec3 up(std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat));
  return {east.dot(d), north.dot(d), up.dot(d) + h0};
}

}  // namespace lc2wf
