#include "infer/surfaces/surface_writers.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "core/util/atomic_file.h"
#include "core/util/version.h"

namespace lc2wf {
namespace {

const char* semantic_type(SurfaceLabel label) {
  switch (label) {
    case SurfaceLabel::kRoof: return "RoofSurface";
    case SurfaceLabel::kWall: return "WallSurface";
    case SurfaceLabel::kGround: return "GroundSurface";
  }
  return "RoofSurface";
}

Vec3 output_point(const Vec3& metres, const SurfaceOutputOptions& o) { return o.raw_units ? o.source_units.to_raw(metres) : metres; }

bool identity(const UnitTransform& t) { return t.raw_per_metre == 1.0 && t.origin_raw.isZero(); }

}  // namespace

std::string cityjson_string(const SurfaceModel& m, const std::string& name, const SurfaceOutputOptions& o) {
  if (!(o.scale > 0) || !std::isfinite(o.scale)) throw std::invalid_argument("CityJSON scale must be > 0");
  if (!o.reference_system.empty() && o.reference_system.rfind("http://www.opengis.net/def/crs/", 0) != 0 &&
      o.reference_system.rfind("https://www.opengis.net/def/crs/", 0) != 0)
    throw std::invalid_argument("reference system '" + o.reference_system + "' is not an OGC CRS URL");
  // Integer vertices relative to the lower corner; vertices that round to one point are stored once.
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  std::vector<bool> used(m.vertices.size(), false);
  for (const SurfaceFace& f : m.faces)
    for (int v : f.ring) used[v] = true;
  for (size_t v = 0; v < m.vertices.size(); ++v)
    if (used[v]) {
      const Vec3 p = output_point(m.vertices[v], o);
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  if (!lo.allFinite()) lo = hi = Vec3::Zero();
  const Vec3 translate = (lo / o.scale).array().floor() * o.scale;
  nlohmann::json vertices = nlohmann::json::array();
  std::map<std::array<long long, 3>, int> index;
  std::vector<int> id(m.vertices.size(), -1);
  for (size_t v = 0; v < m.vertices.size(); ++v) {
    if (!used[v]) continue;
    const Vec3 q = ((output_point(m.vertices[v], o) - translate) / o.scale).array().round();
    const std::array<long long, 3> key{static_cast<long long>(q.x()), static_cast<long long>(q.y()), static_cast<long long>(q.z())};
    const auto [it, fresh] = index.emplace(key, static_cast<int>(vertices.size()));
    if (fresh) vertices.push_back({key[0], key[1], key[2]});
    id[v] = it->second;
  }
  // One semantic surface object per label present; faces point at theirs.
  nlohmann::json surfaces = nlohmann::json::array(), values = nlohmann::json::array(), rings = nlohmann::json::array();
  std::map<SurfaceLabel, int> semantic;
  for (const SurfaceFace& f : m.faces) {
    nlohmann::json ring = nlohmann::json::array();
    for (int v : f.ring) ring.push_back(id[v]);
    rings.push_back(nlohmann::json::array({ring}));
    const auto [it, fresh] = semantic.emplace(f.label, static_cast<int>(surfaces.size()));
    if (fresh) surfaces.push_back({{"type", semantic_type(f.label)}});
    values.push_back(it->second);
  }
  nlohmann::json geometry = nlohmann::json::array();
  if (!m.faces.empty()) {
    nlohmann::json g = {{"lod", "2.2"}};
    if (m.closed_solid()) {
      g["type"] = "Solid";
      g["boundaries"] = nlohmann::json::array({rings});
      g["semantics"] = {{"surfaces", surfaces}, {"values", nlohmann::json::array({values})}};
    } else {
      g["type"] = "MultiSurface";
      g["boundaries"] = rings;
      g["semantics"] = {{"surfaces", surfaces}, {"values", values}};
    }
    geometry.push_back(std::move(g));
  }
  nlohmann::json attributes = {{"lc2wf_shell", to_string(m.status)}};
  if (!m.reasons.empty()) {
    std::string text;
    for (const std::string& r : m.reasons) text += (text.empty() ? "" : "; ") + r;
    attributes["lc2wf_shell_reasons"] = text;
  }
  nlohmann::json metadata = {{"title", "LoD2 surfaces of " + name + " from its lc2wf wireframe"},
                             {"geographicalExtent", {lo.x(), lo.y(), lo.z(), hi.x(), hi.y(), hi.z()}}};
  if (!o.reference_system.empty()) metadata["referenceSystem"] = o.reference_system;
  // Extra metadata members start with '+' (CityJSON extension convention): the frame the coordinates are in.
  nlohmann::json frame = {{"units", o.raw_units ? "source raw units" : "metres"}, {"generator", "lc2wf " + version_line()}};
  if (!identity(o.source_units))
    frame["source"] = {{"raw_per_metre", o.source_units.raw_per_metre},
                       {"origin_raw", {o.source_units.origin_raw.x(), o.source_units.origin_raw.y(), o.source_units.origin_raw.z()}},
                       {"metres_from_raw", "(raw - origin_raw) / raw_per_metre"}};
  metadata["+lc2wf-frame"] = std::move(frame);
  nlohmann::json building = {{"type", "Building"}, {"attributes", std::move(attributes)}, {"geometry", std::move(geometry)}};
  nlohmann::json doc = {{"type", "CityJSON"},
                        {"version", "2.0"},
                        {"transform", {{"scale", {o.scale, o.scale, o.scale}}, {"translate", {translate.x(), translate.y(), translate.z()}}}},
                        {"metadata", std::move(metadata)},
                        {"CityObjects", {{name, std::move(building)}}},
                        {"vertices", std::move(vertices)}};
  return doc.dump() + "\n";
}

std::string faces_obj_string(const SurfaceModel& m, const SurfaceOutputOptions& o) {
  std::string s = "# lc2wf surfaces: " + std::to_string(m.faces.size()) + " faces, " + to_string(m.status) +
                  (o.raw_units ? " (raw units)\n" : " (metres)\n");
  for (const std::string& r : m.reasons) s += "# " + r + "\n";
  char buf[128];
  for (const Vec3& v : m.vertices) {
    const Vec3 p = output_point(v, o);
    std::snprintf(buf, sizeof buf, "v %.9g %.9g %.9g\n", p.x(), p.y(), p.z());
    s += buf;
  }
  for (SurfaceLabel label : {SurfaceLabel::kRoof, SurfaceLabel::kWall, SurfaceLabel::kGround}) {
    if (m.count(label) == 0) continue;
    s += std::string("g ") + to_string(label) + "\n";
    for (const SurfaceFace& f : m.faces) {
      if (f.label != label) continue;
      s += "f";
      for (int v : f.ring) s += " " + std::to_string(v + 1);
      s += "\n";
    }
  }
  return s;
}

void write_surface_outputs(const std::filesystem::path& dir, const std::string& name, const SurfaceModel& model,
                           const SurfaceOutputOptions& o) {
  // The outputs must stay inside `dir`: no separators, not "." or "..".
  if (name.empty() || name == "." || name == ".." || name.find_first_of(std::string("/\0", 2)) != std::string::npos) throw std::invalid_argument("surface model name '" + name + "' is not a plain file name");
  const std::string city = cityjson_string(model, name, o);
  const std::string faces = faces_obj_string(model, o);
  write_file_atomic(dir / (name + ".city.json"), city);
  write_file_atomic(dir / (name + ".faces.obj"), faces);
}

}  // namespace lc2wf
