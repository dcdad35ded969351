#include "dataset/formats/city_json_io.h"

#include <algorithm>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "dataset/formats/errors.h"
#include "dataset/formats/read_file.h"

namespace lc2wf {
namespace {

using Json = nlohmann::json;

struct Transform {
  Vec3 scale = Vec3::Ones();
  Vec3 translate = Vec3::Zero();
};

// Where an error is: file and line, plus the object it concerns.
struct Context {
  const std::string& source;
  int line;
  [[noreturn]] void fail(const std::string& problem) const { throw DataError(source, line, problem); }
};

double number(const Json& j, const Context& cx, const char* what) {
  if (!j.is_number()) cx.fail(std::string(what) + " is not a number");
  return j.get<double>();
}

Transform read_transform(const Json& doc, const Context& cx) {
  Transform t;
  if (!doc.contains("transform")) return t;
  const Json& tr = doc["transform"];
  for (const char* key : {"scale", "translate"}) {
    if (!tr.is_object() || !tr.contains(key) || !tr[key].is_array() || tr[key].size() != 3)
      cx.fail(std::string("transform.") + key + " must be an array of 3 numbers");
    Vec3& v = std::string(key) == "scale" ? t.scale : t.translate;
    for (int k = 0; k < 3; ++k) v[k] = number(tr[key][k], cx, key);
    if (!within_coordinate_limit(v)) cx.fail(std::string("transform.") + key + " is not finite or out of range");
  }
  return t;
}

CityCrs read_crs(const Json& doc) {
  std::string name;
  if (doc.contains("metadata") && doc["metadata"].is_object()) {
    const Json& m = doc["metadata"];
    if (m.contains("referenceSystem") && m["referenceSystem"].is_string()) name = m["referenceSystem"].get<std::string>();
  }
  return is_geographic_crs(name) ? CityCrs::kLonLatHeight : CityCrs::kProjected;
}

std::vector<Vec3> read_vertices(const Json& doc, const Transform& t, const Context& cx) {
  std::vector<Vec3> out;
  if (!doc.contains("vertices")) return out;
  const Json& vs = doc["vertices"];
  if (!vs.is_array()) cx.fail("vertices is not an array");
  out.reserve(vs.size());
  for (size_t i = 0; i < vs.size(); ++i) {
    const Json& v = vs[i];
    if (!v.is_array() || v.size() != 3) cx.fail("vertex " + std::to_string(i) + " is not an array of 3 numbers");
    Vec3 p;
    for (int k = 0; k < 3; ++k) p[k] = number(v[k], cx, "vertex coordinate");
    p = p.cwiseProduct(t.scale) + t.translate;
    if (!within_coordinate_limit(p)) cx.fail("vertex " + std::to_string(i) + " is not finite or out of range");
    out.push_back(p);
  }
  return out;
}

std::string lod_text(const Json& g) {
  if (!g.contains("lod")) return {};
  const Json& l = g["lod"];
  if (l.is_string()) return l.get<std::string>();
  if (l.is_number()) return l.dump();
  return {};
}

// The polygons of one geometry: `depth` array levels above a surface (1 MultiSurface, 2 Solid,
// 3 MultiSolid); semantics.values follow the same nesting down to the surface.
struct GeometryReader {
  const std::vector<Vec3>& vertices;
  const Context& cx;
  const std::string& object_id;
  std::vector<CitySurface> surface_kinds;  // per semantics.surfaces entry
  int part = 0;
  std::vector<CityPolygon>* out = nullptr;
  int labelled = 0;

  std::vector<Vec3> ring(const Json& r) const {
    if (!r.is_array()) cx.fail("object '" + object_id + "': a ring is not an array of vertex ids");
    std::vector<Vec3> pts;
    pts.reserve(r.size());
    for (const Json& id : r) {
      if (!id.is_number_integer()) cx.fail("object '" + object_id + "': a vertex id is not an integer");
      const long long k = id.get<long long>();
      if (k < 0 || k >= static_cast<long long>(vertices.size()))
        cx.fail("object '" + object_id + "': vertex id " + std::to_string(k) + " out of range (" + std::to_string(vertices.size()) +
                " vertices)");
      pts.push_back(vertices[k]);
    }
    return pts;
  }

  void surface(const Json& s, const Json* value) {
    if (!s.is_array() || s.empty()) cx.fail("object '" + object_id + "': a surface is not a non-empty array of rings");
    CityPolygon p;
    p.part = part;
    p.exterior = ring(s[0]);
    for (size_t k = 1; k < s.size(); ++k) p.interiors.push_back(ring(s[k]));
    if (value && value->is_number_integer()) {
      const long long v = value->get<long long>();
      if (v < 0 || v >= static_cast<long long>(surface_kinds.size()))
        cx.fail("object '" + object_id + "': semantics value " + std::to_string(v) + " out of range");
      p.kind = surface_kinds[v];
      labelled += p.kind != CitySurface::kUnknown;
    }
    out->push_back(std::move(p));
  }

  void walk(const Json& b, const Json* values, int depth) {
    if (!b.is_array()) cx.fail("object '" + object_id + "': geometry boundaries are not nested arrays");
    if (values && !values->is_array()) values = nullptr;  // null: no semantics below this level
    for (size_t i = 0; i < b.size(); ++i) {
      const Json* v = values && i < values->size() ? &(*values)[i] : nullptr;
      if (depth == 1)
        surface(b[i], v);
      else
        walk(b[i], v, depth - 1);
    }
  }
};

int surface_depth(const std::string& type) {
  if (type == "MultiSurface" || type == "CompositeSurface") return 1;
  if (type == "Solid") return 2;
  if (type == "MultiSolid" || type == "CompositeSolid") return 3;
  return 0;  // points, lines, GeometryInstance: not a surface model
}

double lod_value(const std::string& lod) { return lod == "2" ? 2.0 : std::stod(lod); }

// Adds an object's LoD 2.x geometries to `lods` (per LoD the one with the most labelled polygons).
void add_object_geometry(const Json& obj, const std::string& id, int part, const std::vector<Vec3>& vertices, const Context& cx,
                         std::map<std::string, std::vector<CityPolygon>>& lods) {
  if (!obj.contains("geometry")) return;
  const Json& geoms = obj["geometry"];
  if (!geoms.is_array()) cx.fail("object '" + id + "': geometry is not an array");
  std::map<std::string, std::pair<int, std::vector<CityPolygon>>> best;
  for (const Json& g : geoms) {
    if (!g.is_object()) cx.fail("object '" + id + "': a geometry is not an object");
    const std::string lod = normalise_lod2(lod_text(g));
    const int depth = surface_depth(g.value("type", std::string()));
    if (lod.empty() || depth == 0 || !g.contains("boundaries")) continue;
    GeometryReader r{vertices, cx, id};
    r.part = part;
    const Json* values = nullptr;
    if (g.contains("semantics") && g["semantics"].is_object()) {
      const Json& sem = g["semantics"];
      if (sem.contains("surfaces") && sem["surfaces"].is_array())
        for (const Json& s : sem["surfaces"])
          r.surface_kinds.push_back(s.is_object() && s.contains("type") && s["type"].is_string() ? city_surface_of(s["type"].get<std::string>())
                                                                                                : CitySurface::kUnknown);
      if (sem.contains("values")) values = &sem["values"];
    }
    std::vector<CityPolygon> polys;
    r.out = &polys;
    r.walk(g["boundaries"], values, depth);
    auto it = best.find(lod);
    if (it == best.end() || r.labelled > it->second.first) best[lod] = {r.labelled, std::move(polys)};
  }
  for (auto& [lod, entry] : best) {
    auto& dst = lods[lod];
    dst.insert(dst.end(), std::make_move_iterator(entry.second.begin()), std::make_move_iterator(entry.second.end()));
  }
}

bool is_building(const Json& obj) { return obj.is_object() && obj.value("type", std::string()) == "Building"; }
bool is_part(const Json& obj) { return obj.is_object() && obj.value("type", std::string()) == "BuildingPart"; }

// Every root Building (or a BuildingPart whose parent is not in `objects`) with its parts, in the
// order of their ids.
void visit_buildings(const Json& objects, const std::vector<Vec3>& vertices, CityCrs crs,
                     const Context& cx, int line, const CityBuildingVisitor& visit) {
  for (auto oit = objects.begin(); oit != objects.end(); ++oit) {
    const std::string& id = oit.key();
    const Json& obj = oit.value();
    if (!is_building(obj) && !is_part(obj)) continue;
    bool has_parent = false;
    if (obj.contains("parents") && obj["parents"].is_array())
      for (const Json& p : obj["parents"])
        if (p.is_string() && objects.contains(p.get<std::string>()) &&
            (is_building(objects[p.get<std::string>()]) || is_part(objects[p.get<std::string>()])))
          has_parent = true;
    if (has_parent) continue;
    CityBuilding b;
    b.id = id;
    b.line = line;
    b.crs = crs;
    std::map<std::string, std::vector<CityPolygon>> lods;
    std::set<std::string> seen{id};
    std::vector<std::string> stack{id};
    int part = 0;
    // Depth-first over BuildingPart children; a cycle or repeated child is visited once.
    while (!stack.empty()) {
      const std::string cur = stack.back();
      stack.pop_back();
      const Json& o = objects[cur];
      add_object_geometry(o, cur, part++, vertices, cx, lods);
      if (!o.contains("children") || !o["children"].is_array()) continue;
      const Json& ch = o["children"];
      for (auto it = ch.rbegin(); it != ch.rend(); ++it) {
        if (!it->is_string()) continue;
        const std::string c = it->get<std::string>();
        if (objects.contains(c) && is_part(objects[c]) && seen.insert(c).second) stack.push_back(c);
      }
    }
    b.parts = part;
    for (auto& [lod, polys] : lods) b.lods.push_back({lod, std::move(polys)});
    std::sort(b.lods.begin(), b.lods.end(), [](const auto& x, const auto& y) { return lod_value(x.lod) > lod_value(y.lod); });
    visit(std::move(b));
  }
}

// Keys whose values no reader here needs: dropped while parsing, so a large file's DOM stays smaller.
bool keep_key(int /*depth*/, Json::parse_event_t event, Json& parsed) {
  if (event != Json::parse_event_t::key) return true;
  const std::string& k = parsed.get_ref<const std::string&>();
  return k != "attributes" && k != "appearance" && k != "address" && k != "geographicalExtent" && k != "textures" &&
         k != "materials" && k != "geometry-templates" && k != "extensions";
}

Json parse_json(const std::string& text, const std::string& source, int line) {
  try {
    return Json::parse(text, keep_key);
  } catch (const Json::exception& e) {
    throw DataError(source, line, std::string("not valid JSON: ") + e.what());
  }
}

void check_type(const Json& doc, const char* want, const Context& cx) {
  if (!doc.is_object() || !doc.contains("type") || doc["type"] != want) cx.fail(std::string("not a ") + want + " object (\"type\" is not \"" + want + "\")");
}

}  // namespace

void parse_city_json(const std::string& text, const std::string& source, const CityBuildingVisitor& visit) {
  const Context cx{source, 0};
  Json doc = parse_json(text, source, 0);
  check_type(doc, "CityJSON", cx);
  const Transform t = read_transform(doc, cx);
  const std::vector<Vec3> vertices = read_vertices(doc, t, cx);
  doc.erase("vertices");
  if (!doc.contains("CityObjects") || !doc["CityObjects"].is_object()) cx.fail("CityObjects is missing or not an object");
  const Json& objects = doc["CityObjects"];
  visit_buildings(objects, vertices, read_crs(doc), cx, 0, visit);
}

void read_city_json(const std::filesystem::path& path, const CityBuildingVisitor& visit) {
  parse_city_json(read_file(path), path.string(), visit);
}

void parse_city_json_seq(std::istream& in, const std::string& source, const CityBuildingVisitor& visit) {
  std::string text;
  int line = 0;
  bool have_header = false;
  Transform t;
  CityCrs crs = CityCrs::kProjected;
  while (std::getline(in, text)) {
    ++line;
    if (text.find_first_not_of(" \t\r") == std::string::npos) continue;
    const Context cx{source, line};
    Json doc = parse_json(text, source, line);
    if (!have_header) {
      check_type(doc, "CityJSON", cx);
      t = read_transform(doc, cx);
      crs = read_crs(doc);
      have_header = true;
      continue;
    }
    check_type(doc, "CityJSONFeature", cx);
    const std::vector<Vec3> vertices = read_vertices(doc, t, cx);
    if (!doc.contains("CityObjects") || !doc["CityObjects"].is_object()) cx.fail("CityObjects is missing or not an object");
    const Json& objects = doc["CityObjects"];
    visit_buildings(objects, vertices, crs, cx, line, visit);
  }
  if (in.bad()) throw DataError(source, line, "read error");
  if (!have_header) throw DataError(source, "empty CityJSONSeq file (no CityJSON header line)");
}

void read_city_json_seq(const std::filesystem::path& path, const CityBuildingVisitor& visit) {
  if (const std::string problem = input_file_problem(path); !problem.empty()) throw DataError(path.string(), problem);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw DataError(path.string(), "cannot open file");
  parse_city_json_seq(in, path.string(), visit);
}

bool looks_like_city_json(const std::filesystem::path& path) {
  if (!input_file_problem(path).empty()) return true;  // refused later by the reader, naming the problem
  std::ifstream in(path, std::ios::binary);
  std::string head(64 * 1024, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  return head.find("\"CityJSON\"") != std::string::npos;
}

}  // namespace lc2wf
