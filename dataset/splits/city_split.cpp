#include "dataset/splits/city_split.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "core/util/parallel_items.h"
#include "dataset/geometry/footprint.h"
#include "dataset/geometry/roof_kind.h"

namespace lc2wf {

namespace fs = std::filesystem;

void CitySplitOptions::Check() const {
  if (inputs.empty()) throw std::invalid_argument("at least one input folder or file is required");
  if (threads < 1) throw std::invalid_argument("threads must be >= 1");
  rule.Check();
  sources.Check();
  for (const std::string& r : source_rules) source_of("", {r});  // throws on a rule without '='
}

namespace {

std::string relative_to(const fs::path& file, const fs::path& root) {
  if (root.empty()) return file.generic_string();
  const fs::path rel = file.lexically_relative(root);
  return rel.empty() || *rel.begin() == ".." ? file.generic_string() : rel.generic_string();
}

// Metres in a frame where tiles are squares: projected frames as they are; a geographic CRS's local tangent
// plane origin as lon/lat scaled to metres at its latitude (tiles only need to be consistent in one file).
Vec3 map_position(const Building& b, const CityLoadInfo& info) {
  if (info.crs == CityCrs::kProjected) return b.units.origin_raw;
  const double lat = info.tangent_plane.lat0_deg * 3.14159265358979323846 / 180.0;
  return Vec3(info.tangent_plane.lon0_deg * 111320.0 * std::cos(lat), info.tangent_plane.lat0_deg * 110574.0, 0.0);
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[static_cast<size_t>(std::floor(q * (v.size() - 1) + 0.5))];
}

}  // namespace

CitySplitResult make_city_split(const CitySplitOptions& o) {
  o.Check();
  CitySplitResult result;
  std::vector<std::unique_ptr<BuildingCatalog>> catalogs;
  for (const fs::path& in : o.inputs) {
    catalogs.push_back(std::make_unique<BuildingCatalog>(in, o.sources));
    for (const SourceFileListing& f : catalogs.back()->files())
      if (!f.error.empty()) result.skipped.emplace_back(f.file.string(), f.error);
  }
  struct Job {
    const BuildingCatalog* catalog;
    const BuildingEntry* entry;
  };
  std::vector<Job> jobs;
  for (const auto& c : catalogs)
    for (const BuildingEntry& e : c->entries()) jobs.push_back({c.get(), &e});
  std::vector<CitySplitBuilding> rows(jobs.size());
  std::vector<std::string> errors(jobs.size());
  for_each_item(static_cast<int64_t>(jobs.size()), o.threads, [&](int64_t k) {
    const size_t i = static_cast<size_t>(k);
    const BuildingEntry& e = *jobs[i].entry;
    CitySplitBuilding& r = rows[i];
    r.name = e.name;
    r.file = relative_to(e.file, o.root);
    r.source = source_of(r.file, o.source_rules);
    if (r.source.empty()) r.source = fs::path(r.file).parent_path().filename().string();
    try {
      CityLoadInfo info;
      const Building b = jobs[i].catalog->load(e.name, BuildingOptions{}, &info);
      const Vec3 at = map_position(b, info);
      r.x = at.x(), r.y = at.y();
      for (const Vec3& v : b.mesh.vertices) r.height_m = std::max(r.height_m, v.z());
      std::tie(r.long_side_m, r.short_side_m) = footprint_sides(b.mesh.vertices);
      r.roof_kind = roof_kind_name(classify_roof(b.mesh));
      r.junctions = static_cast<int>(b.wireframe.junctions.size());
      r.edges = static_cast<int>(b.wireframe.edges.size());
    } catch (const std::exception& ex) {
      errors[i] = ex.what();
    }
  }, 1);

  std::map<std::string, size_t> first_of_name;  // one building listed by two inputs counts once
  std::map<std::string, std::pair<std::string, std::string>> first_of_id;  // id -> name, file: one building in two files counts once
  std::vector<TileSplitEntry> entries;
  for (size_t i = 0; i < rows.size(); ++i) {
    if (!errors[i].empty()) {
      result.skipped.emplace_back(rows[i].name, errors[i]);
      continue;
    }
    const std::string& id = jobs[i].entry->object_id;
    if (!id.empty()) {
      const auto [at, fresh] = first_of_id.emplace(id, std::make_pair(rows[i].name, rows[i].file));
      if (!fresh && at->second.second != rows[i].file) {
        result.skipped.emplace_back(rows[i].name, "the same building (id " + id + ") as " + at->second.first);
        continue;
      }
    }
    if (!first_of_name.emplace(rows[i].name, result.buildings.size()).second) {
      result.skipped.emplace_back(rows[i].name, "listed twice (" + rows[i].file + ")");
      continue;
    }
    result.buildings.push_back(rows[i]);
    entries.push_back({rows[i].name, rows[i].source, rows[i].file, rows[i].x, rows[i].y});
  }
  result.splits = make_tile_splits(entries, o.rule);
  std::map<std::string, std::string> side;
  for (const auto& n : result.splits.train) side[n] = "train";
  for (const auto& n : result.splits.val) side[n] = "val";
  for (const auto& n : result.splits.test) side[n] = "test";
  for (CitySplitBuilding& b : result.buildings) b.split = side[b.name];
  std::sort(result.buildings.begin(), result.buildings.end(),
            [](const CitySplitBuilding& a, const CitySplitBuilding& b) { return a.name < b.name; });
  return result;
}

std::string city_split_statistics_markdown(const CitySplitResult& result) {
  const std::vector<std::string> kinds = {"flat", "flat-multi", "shed", "gabled", "hipped", "mixed", "complex", "unknown"};
  std::map<std::pair<std::string, std::string>, std::vector<const CitySplitBuilding*>> groups;
  for (const CitySplitBuilding& b : result.buildings) {
    groups[{b.source, b.split}].push_back(&b);
    groups[{b.source, "all"}].push_back(&b);
    groups[{"all", b.split}].push_back(&b);
    groups[{"all", "all"}].push_back(&b);
  }
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(1);
  s << "| source | split | buildings | height m p10/50/90 | footprint long m p10/50/90 | footprint short m p10/50/90 | "
       "junctions p50/p90 | edges p50/p90 |";
  for (const auto& k : kinds) s << ' ' << k << " |";
  s << "\n|---|---|---|---|---|---|---|---|";
  for (size_t i = 0; i < kinds.size(); ++i) s << "---|";
  s << '\n';
  for (const auto& [key, members] : groups) {
    std::vector<double> h, lo, sh, j, e;
    std::map<std::string, int> kind_count;
    for (const CitySplitBuilding* b : members) {
      h.push_back(b->height_m), lo.push_back(b->long_side_m), sh.push_back(b->short_side_m);
      j.push_back(b->junctions), e.push_back(b->edges);
      ++kind_count[b->roof_kind];
    }
    auto trio = [&](const std::vector<double>& v) {
      std::ostringstream t;
      t.setf(std::ios::fixed);
      t.precision(1);
      t << percentile(v, 0.1) << " / " << percentile(v, 0.5) << " / " << percentile(v, 0.9);
      return t.str();
    };
    s << "| " << key.first << " | " << key.second << " | " << members.size() << " | " << trio(h) << " | " << trio(lo) << " | "
      << trio(sh) << " | " << static_cast<int>(percentile(j, 0.5)) << " / " << static_cast<int>(percentile(j, 0.9)) << " | "
      << static_cast<int>(percentile(e, 0.5)) << " / " << static_cast<int>(percentile(e, 0.9)) << " |";
    for (const auto& k : kinds) s << ' ' << kind_count[k] << " |";
    s << '\n';
  }
  return s.str();
}

}  // namespace lc2wf
