#include "dataset/formats/building_sources.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <stdexcept>

#include "core/util/fnv1a.h"
#include "dataset/formats/city_gml_io.h"
#include "dataset/formats/city_json_io.h"

namespace lc2wf {
namespace fs = std::filesystem;

namespace {

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// The file name without its city-model suffix ("a.city.json" -> "a", "t.gml.gz" -> "t").
std::string model_stem(const fs::path& p) {
  const std::string n = p.filename().string();
  for (const char* suffix : {".city.jsonl", ".city.json", ".jsonl", ".json", ".gml.gz", ".gml"})
    if (ends_with(n, suffix)) return n.substr(0, n.size() - std::string(suffix).size());
  return p.stem().string();
}

BuildingFormat format_of(const fs::path& p) {
  const std::string n = p.filename().string();
  if (ends_with(n, ".jsonl")) return BuildingFormat::kCityJsonSeq;
  if (ends_with(n, ".json")) return BuildingFormat::kCityJson;
  if (ends_with(n, ".gml") || ends_with(n, ".gml.gz")) return BuildingFormat::kCityGml;
  return BuildingFormat::kPolyshape;
}

void read_city_model(const fs::path& file, BuildingFormat format, const CityBuildingVisitor& visit) {
  switch (format) {
    case BuildingFormat::kCityJson: read_city_json(file, visit); break;
    case BuildingFormat::kCityJsonSeq: read_city_json_seq(file, visit); break;
    case BuildingFormat::kCityGml: read_city_gml(file, visit); break;
    case BuildingFormat::kPolyshape: break;
  }
}

}  // namespace

struct BuildingCatalog::ParsedFile {
  std::vector<CityBuilding> buildings;  // the listed ones, in listing order (BuildingEntry::ordinal)
};

void BuildingSourceOptions::Check() const {
  if (!lod.empty() && normalise_lod2(lod).empty())
    throw std::invalid_argument("BuildingSourceOptions.lod must be a LoD 2.x such as 2.2, 2.0 or 2 (got '" + lod.substr(0, 20) + "')");
  if (cached_files < 1) throw std::invalid_argument("BuildingSourceOptions.cached_files must be >= 1");
  cleanup.Check();
}

bool is_city_model_file_name(const fs::path& path) { return format_of(path) != BuildingFormat::kPolyshape; }

std::string sanitise_building_name(const std::string& name) {
  std::string out;
  for (char c : name) {
    const bool safe = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' || c == '_' || c == '-';
    out += safe ? c : '_';
  }
  if (out.empty() || out[0] == '.') out = "_" + out;
  if (out.size() > 150) {
    char hash[24];
    std::snprintf(hash, sizeof hash, "_%016llx", static_cast<unsigned long long>(fnv1a64(name)));
    out = out.substr(0, 150 - 17) + hash;
  }
  return out;
}

BuildingCatalog::BuildingCatalog(const fs::path& folder_or_file, BuildingSourceOptions options) : options_(std::move(options)) {
  options_.Check();
  std::vector<fs::path> paths;
  std::error_code ec;
  if (fs::is_directory(folder_or_file, ec)) {
    fs::directory_iterator it(folder_or_file, ec);
    if (ec) throw DataError(folder_or_file.string(), "cannot list folder");
    for (const auto& entry : it) paths.push_back(entry.path());
  } else {
    if (!fs::exists(fs::symlink_status(folder_or_file, ec))) throw DataError(folder_or_file.string(), "does not exist");
    if (folder_or_file.extension() != ".polyshape" && !is_city_model_file_name(folder_or_file))
      throw DataError(folder_or_file.string(), "not a building file (.polyshape, .city.json, .json, .jsonl, .gml, .gml.gz)");
    paths.push_back(folder_or_file);
  }
  std::sort(paths.begin(), paths.end());
  std::vector<BuildingEntry> listed;
  for (const fs::path& p : paths) {
    if (p.extension() == ".polyshape") {
      listed.push_back({p.stem().string(), p, BuildingFormat::kPolyshape, {}, 0});
      continue;
    }
    const BuildingFormat format = format_of(p);
    if (format == BuildingFormat::kPolyshape) continue;
    if (format == BuildingFormat::kCityJson && !ends_with(p.filename().string(), ".city.json") && !looks_like_city_json(p)) continue;
    SourceFileListing file{p, format};
    std::vector<BuildingEntry> found;
    const std::string stem = model_stem(p);
    try {
      read_city_model(p, format, [&](CityBuilding&& b) {
        if (!select_lod(b, options_.lod)) {
          ++file.without_lod;
          return;
        }
        found.push_back({sanitise_building_name(stem + "__" + b.id), p, format, b.id, static_cast<int>(found.size())});
      });
    } catch (const std::exception& e) {
      file.error = e.what();
      found.clear();
    }
    file.buildings = static_cast<int>(found.size());
    files_.push_back(file);
    listed.insert(listed.end(), found.begin(), found.end());
  }
  // Repeated names (an id twice in a file, or ids that sanitise alike) get __2, __3, ... in listing order.
  std::map<std::string, int> seen;
  for (auto& e : listed) {
    const int n = ++seen[e.name];
    if (n > 1) {
      std::string candidate;
      for (int k = n;; ++k) {
        candidate = e.name + "__" + std::to_string(k);
        if (!seen.count(candidate)) break;
      }
      e.name = candidate;
      ++seen[candidate];
    }
  }
  entries_ = std::move(listed);
  std::sort(entries_.begin(), entries_.end(), [](const BuildingEntry& a, const BuildingEntry& b) { return a.name < b.name; });
}

std::vector<std::string> BuildingCatalog::names() const {
  std::vector<std::string> out;
  out.reserve(entries_.size());
  for (const auto& e : entries_) out.push_back(e.name);
  return out;
}

const BuildingEntry* BuildingCatalog::find(const std::string& name) const {
  const auto it = std::lower_bound(entries_.begin(), entries_.end(), name, [](const BuildingEntry& e, const std::string& n) { return e.name < n; });
  return it != entries_.end() && it->name == name ? &*it : nullptr;
}

std::shared_ptr<const BuildingCatalog::ParsedFile> BuildingCatalog::parsed(const BuildingEntry& entry) const {
  std::lock_guard<std::mutex> lock(mu_);
  for (size_t k = 0; k < cache_.size(); ++k)
    if (cache_[k].first == entry.file) {
      auto hit = cache_[k];
      cache_.erase(cache_.begin() + static_cast<long>(k));
      cache_.push_back(hit);
      return hit.second;
    }
  auto file = std::make_shared<ParsedFile>();
  read_city_model(entry.file, entry.format, [&](CityBuilding&& b) {
    if (select_lod(b, options_.lod)) file->buildings.push_back(std::move(b));
  });
  if (static_cast<int>(cache_.size()) >= options_.cached_files) cache_.erase(cache_.begin());
  cache_.emplace_back(entry.file, file);
  return file;
}

Building BuildingCatalog::load(const std::string& name, const BuildingOptions& options, CityLoadInfo* info) const {
  const BuildingEntry* entry = find(name);
  if (!entry) throw DataError(name, "no such building in the listed sources");
  if (entry->format == BuildingFormat::kPolyshape) return load_roof_image_building(entry->file, options);
  const auto file = parsed(*entry);
  if (entry->ordinal >= static_cast<int>(file->buildings.size()) || file->buildings[entry->ordinal].id != entry->object_id)
    throw DataError(entry->file.string(), "building '" + entry->object_id + "' is no longer in the file (changed since it was listed?)");
  const CityBuilding& b = file->buildings[entry->ordinal];
  const CityLodGeometry* g = select_lod(b, options_.lod);
  std::vector<CityPolygon> polygons = g->polygons;
  CityLoadInfo local_info;
  CityLoadInfo& li = info ? *info : local_info;
  li.lod = g->lod;
  li.crs = b.crs;
  // A local frame for the clean-up's geometry: large CRS coordinates would cost digits in cross products.
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& p : polygons)
    for (const Vec3& v : p.exterior) {
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
    }
  Vec3 offset = Vec3::Zero();
  if (polygons.empty()) {
  } else if (b.crs == CityCrs::kProjected) {
    offset = Vec3(0.5 * (lo.x() + hi.x()), 0.5 * (lo.y() + hi.y()), lo.z());
    for (auto& p : polygons) {
      for (Vec3& v : p.exterior) v -= offset;
      for (auto& r : p.interiors)
        for (Vec3& v : r) v -= offset;
    }
  } else {
    const bool lat_first = b.crs == CityCrs::kLatLonHeight;
    TangentPlane& tp = li.tangent_plane;
    tp.lat0_deg = 0.5 * (lat_first ? lo.x() + hi.x() : lo.y() + hi.y());
    tp.lon0_deg = 0.5 * (lat_first ? lo.y() + hi.y() : lo.x() + hi.x());
    tp.h0 = 0;
    if (std::abs(tp.lat0_deg) > 90 || std::abs(tp.lon0_deg) > 360)
      throw DataError(entry->file.string(), "building '" + b.id + "': geographic coordinates out of range");
    auto convert = [&](Vec3& v) { v = lat_first ? tp.to_local(v.x(), v.y(), v.z()) : tp.to_local(v.y(), v.x(), v.z()); };
    for (auto& p : polygons) {
      for (Vec3& v : p.exterior) convert(v);
      for (auto& r : p.interiors)
        for (Vec3& v : r) convert(v);
    }
  }
  Lod2CleanupResult res = cleanup_lod2(std::move(polygons), options_.cleanup);
  li.cleanup = res.report;
  if (!res.skip_reason.empty()) throw Lod2Skipped(name, res.skip_detail, res.skip_reason);
  for (Vec3& v : res.mesh.vertices) v += offset;
  BuildingOptions bo = options;
  bo.raw_per_metre = 1.0;  // city models are in metres (CRS or tangent plane)
  return make_building(name, std::move(res.mesh), bo);
}

}  // namespace lc2wf
