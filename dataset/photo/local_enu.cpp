#include "dataset/photo/local_enu.h"

#include <cmath>

namespace lc2wf {
namespace {

constexpr double kA = 6378137.0;              // WGS84 semi-major axis (m)
constexpr double kE2 = 6.69437999014e-3;      // first eccentricity squared

Vec3 ecef(double lat_deg, double lon_deg, double h) {
  const double lat = lat_deg * M_PI / 180, lon = lon_deg * M_PI / 180;
  const double n = kA / std::sqrt(1 - kE2 * std::sin(lat) * std::sin(lat));
  return {(n + h) * std::cos(lat) * std::cos(lon), (n + h) * std::cos(lat) * std::sin(lon), (n * (1 - kE2) + h) * std::sin(lat)};
}

}  // namespace

std::vector<Vec3> local_enu(const std::vector<GpsFix>& fixes) {
  if (fixes.empty()) return {};
  double lat = 0, lon = 0, alt = 0;
  int with_alt = 0;
  for (const GpsFix& f : fixes) {
    lat += f.latitude_deg, lon += f.longitude_deg;
    if (f.has_altitude) alt += f.altitude_m, ++with_alt;
  }
  lat /= fixes.size(), lon /= fixes.size();
  alt = with_alt ? alt / with_alt : 0.0;
  const Vec3 origin = ecef(lat, lon, alt);
  const double phi = lat * M_PI / 180, lambda = lon * M_PI / 180;
  Eigen::Matrix3d to_enu;  // rows: east, north, up at the origin
  to_enu << -std::sin(lambda), std::cos(lambda), 0,                                          //
      -std::sin(phi) * std::cos(lambda), -std::sin(phi) * std::sin(lambda), std::cos(phi),  //
      std::cos(phi) * std::cos(lambda), std::cos(phi) * std::sin(lambda), std::sin(phi);
  std::vector<Vec3> out;
  for (const GpsFix& f : fixes) out.push_back(to_enu * (ecef(f.latitude_deg, f.longitude_deg, f.has_altitude ? f.altitude_m : alt) - origin));
  return out;
}

}  // namespace lc2wf
