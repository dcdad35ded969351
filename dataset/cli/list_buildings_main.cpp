// lc2wf-list-buildings: every building of folders/files of meshes and city models, loaded and cleaned as
// lc2wf-dataset would, with per-building facts (for splits by file) and a summary of what was skipped.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "core/util/atomic_file.h"
#include "core/util/cli.h"
#include "core/util/json_text.h"
#include "core/util/parallel_items.h"
#include "core/util/seconds_since.h"
#include "core/util/thread_count.h"
#include "dataset/formats/building_sources.h"
#include "dataset/geometry/footprint.h"

namespace {

namespace fs = std::filesystem;
using namespace lc2wf;
using Json = nlohmann::json;

const char* kUsage = R"(Usage: lc2wf-list-buildings PATH... [-o FILE.csv] [--lod L] [-j N] [-q]

Lists and loads every building of each PATH (a folder's files, or one file: Roof-Image .polyshape,
CityJSON .city.json/.json, CityJSONSeq .jsonl, CityGML .gml/.gml.gz) through the same listing, LoD choice
and LoD2 clean-up as lc2wf-dataset --meshes, and writes one CSV row per building: name, source file,
status (ok or skipped), skip reason, LoD, height (m), footprint long and short side (m, minimum-area
rectangle of the vertices), vertices and edges before and after the clean-up, faces, roof faces.
A JSON summary goes to stdout: buildings per source folder, skips per reason, median and p90 of the
vertex and edge counts, seconds.

  -o, --out FILE      the per-building CSV (default: none)
  --lod L             city models: the LoD 2.x to use (2.2, 2.1, 2 = 2.0; default: each building's highest)
  -j, --threads N     loading threads (default: all cores)
  -q, --quiet         no summary on stdout
Exit code 1 when a building was skipped or a file could not be read (each named on stderr).
)";

struct Args {
  std::vector<fs::path> inputs;
  fs::path out;
  std::string lod;
  int threads = 0;
  bool quiet = false;
};

Args parse_args(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string f = argv[i];
    auto value = [&] { return flag_value(argc, argv, i); };
    if (f == "-o" || f == "--out") a.out = value();
    else if (f == "--lod") a.lod = value();
    else if (f == "-j" || f == "--threads") a.threads = threads_flag(f, value());
    else if (f == "-q" || f == "--quiet") a.quiet = true;
    else if (!f.empty() && f[0] == '-') throw UsageError("unknown option '" + f + "'");
    else a.inputs.push_back(f);
  }
  if (a.inputs.empty()) throw UsageError("give at least one folder or file");
  BuildingSourceOptions o;
  o.lod = a.lod;
  try {
    o.Check();
  } catch (const std::invalid_argument&) {
    throw UsageError("--lod must be a LoD 2.x such as 2.2, 2.0 or 2, got '" + a.lod + "'");
  }
  return a;
}

struct Row {
  std::string name, file, group, status = "ok", reason, detail, lod;
  double height = 0, long_side = 0, short_side = 0;
  int v_before = 0, e_before = 0, v_after = 0, e_after = 0, faces = 0, roof_faces = 0;
};

std::string csv(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[static_cast<size_t>(std::floor(q * (v.size() - 1) + 0.5))];
}

int run(const Args& a) {
  const auto start = std::chrono::steady_clock::now();
  BuildingSourceOptions so;
  so.lod = a.lod;
  std::vector<Row> rows;
  Json files = Json::array();
  bool partly = false;
  for (const fs::path& input : a.inputs) {
    const BuildingCatalog catalog(input, so);
    for (const auto& f : catalog.files()) {
      files.push_back({{"file", f.file.string()}, {"buildings", f.buildings}, {"without_lod", f.without_lod}, {"error", f.error}});
      if (!f.error.empty()) {
        std::fprintf(stderr, "lc2wf-list-buildings: %s\n", f.error.c_str());
        partly = true;
      }
    }
    const auto& entries = catalog.entries();
    std::vector<Row> part(entries.size());
    for_each_item(static_cast<int64_t>(entries.size()), resolve_thread_count(a.threads), [&](int64_t k) {
      const size_t i = static_cast<size_t>(k);
      Row& r = part[i];
      r.name = entries[i].name;
      r.file = entries[i].file.string();
      r.group = entries[i].file.parent_path().filename().string();
      CityLoadInfo info;
      try {
        const Building b = catalog.load(r.name, {}, &info);
        double zmax = 0;
        for (const Vec3& v : b.mesh.vertices) zmax = std::max(zmax, v.z());
        r.height = zmax;
        std::tie(r.long_side, r.short_side) = footprint_sides(b.mesh.vertices);
        r.faces = static_cast<int>(b.mesh.faces.size());
        r.roof_faces = static_cast<int>(std::count(b.mesh.labels.begin(), b.mesh.labels.end(), FaceLabel::Roof));
        r.v_after = static_cast<int>(b.wireframe.junctions.size());
        r.e_after = static_cast<int>(b.wireframe.edges.size());
      } catch (const Lod2Skipped& e) {
        r.status = "skipped";
        r.reason = e.reason();
        r.detail = e.what();
      } catch (const std::exception& e) {
        r.status = "skipped";
        r.reason = "error";
        r.detail = e.what();
      }
      r.lod = info.lod;
      r.v_before = info.cleanup.vertices_before;
      r.e_before = info.cleanup.edges_before;
      if (entries[i].format == BuildingFormat::kPolyshape) {
        r.v_before = r.v_after;
        r.e_before = r.e_after;
      }
    }, 1);
    rows.insert(rows.end(), part.begin(), part.end());
  }
  std::map<std::string, std::map<std::string, int>> per_group;
  std::map<std::string, int> reasons;
  std::vector<double> vb, eb, va, ea;
  for (const Row& r : rows) {
    ++per_group[r.group][r.status];
    if (r.status != "ok") {
      ++reasons[r.reason];
      partly = true;
      std::fprintf(stderr, "lc2wf-list-buildings: skipped %s\n", r.detail.c_str());
      continue;
    }
    vb.push_back(r.v_before), eb.push_back(r.e_before), va.push_back(r.v_after), ea.push_back(r.e_after);
  }
  if (!a.out.empty()) {
    std::ostringstream s;
    s << "name,source_file,status,skip_reason,lod,height_m,footprint_long_m,footprint_short_m,vertices_before,edges_before,"
         "vertices_after,edges_after,faces,roof_faces\n";
    for (const Row& r : rows) {
      char nums[256];
      std::snprintf(nums, sizeof nums, "%.3f,%.3f,%.3f,%d,%d,%d,%d,%d,%d", r.height, r.long_side, r.short_side, r.v_before, r.e_before,
                    r.v_after, r.e_after, r.faces, r.roof_faces);
      s << csv(r.name) << ',' << csv(r.file) << ',' << r.status << ',' << r.reason << ',' << r.lod << ',' << nums << '\n';
    }
    write_file_atomic(a.out, s.str());
  }
  if (!a.quiet) {
    Json summary;
    summary["buildings"] = rows.size();
    summary["per_folder"] = per_group;
    summary["skipped_by_reason"] = reasons;
    auto stats = [](const std::vector<double>& v) { return Json{{"median", quantile(v, 0.5)}, {"p90", quantile(v, 0.9)}}; };
    summary["loaded"] = {{"vertices_before", stats(vb)}, {"edges_before", stats(eb)}, {"vertices_after", stats(va)}, {"edges_after", stats(ea)}};
    summary["files"] = files;
    summary["seconds"] = seconds_since(start);
    std::printf("%s\n", json_text(summary, 2).c_str());
  }
  return partly ? kExitPartly : kExitDone;
}

}  // namespace

int main(int argc, char** argv) { return cli_main({"lc2wf-list-buildings", kUsage, {}}, argc, argv, parse_args, run); }
