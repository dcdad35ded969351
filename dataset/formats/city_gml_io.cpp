#include "dataset/formats/city_gml_io.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <set>
#include <unordered_map>
#include <unordered_set>

#include "dataset/formats/errors.h"
#include "dataset/formats/xml_reader.h"

namespace lc2wf {
namespace {

// One Building subtree: its elements by gml:id, and the polygon ids already taken.
class BuildingGeometry {
 public:
  BuildingGeometry(const XmlNode& building, const std::string& source) : source_(source) { index(building); }

  // Polygons of a geometry subtree (inline or by reference), reversed under OrientableSurface "-".
  void collect(const XmlNode& node, CitySurface kind, int part, bool with_unnamed, std::vector<CityPolygon>& out) {
    std::unordered_set<const XmlNode*> visiting;
    walk(node, kind, part, false, with_unnamed, visiting, out);
  }

 private:
  void index(const XmlNode& n) {
    if (const std::string* id = n.attribute("id")) by_id_.emplace(*id, &n);
    for (const XmlNode& c : n.children) index(c);
  }

  void walk(const XmlNode& n, CitySurface kind, int part, bool reversed, bool with_unnamed,
            std::unordered_set<const XmlNode*>& visiting, std::vector<CityPolygon>& out) {
    if (n.name == "Polygon" || n.name == "Triangle" || n.name == "Rectangle") {
      const std::string* id = n.attribute("id");
      if (id ? !used_.insert(*id).second : !with_unnamed) return;
      CityPolygon p = polygon(n);
      if (p.exterior.size() < 3) return;
      p.kind = kind;
      p.part = part;
      if (reversed) {
        std::reverse(p.exterior.begin(), p.exterior.end());
        for (auto& r : p.interiors) std::reverse(r.begin(), r.end());
      }
      out.push_back(std::move(p));
      return;
    }
    if (n.name == "OrientableSurface") {
      const std::string* o = n.attribute("orientation");
      if (o && *o == "-") reversed = !reversed;
    }
    if (const std::string* href = n.attribute("href"); href && n.children.empty()) {
      const std::string id = !href->empty() && (*href)[0] == '#' ? href->substr(1) : *href;
      const auto it = by_id_.find(id);
      if (it == by_id_.end() || !visiting.insert(it->second).second) return;  // outside the building, or a cycle
      walk(*it->second, kind, part, reversed, with_unnamed, visiting, out);
      visiting.erase(it->second);
      return;
    }
    for (const XmlNode& c : n.children) {
      if (c.name == "interior" && n.name == "Solid") continue;  // inner shells are voids
      walk(c, kind, part, reversed, with_unnamed, visiting, out);
    }
  }

  CityPolygon polygon(const XmlNode& n) const {
    CityPolygon p;
    for (const XmlNode& c : n.children) {
      if (c.name != "exterior" && c.name != "interior" && c.name != "outerBoundaryIs" && c.name != "innerBoundaryIs") continue;
      for (const XmlNode& ring : c.children) {
        if (ring.name != "LinearRing") continue;
        std::vector<Vec3> pts = coordinates(ring);
        if (c.name == "exterior" || c.name == "outerBoundaryIs")
          p.exterior = std::move(pts);
        else
          p.interiors.push_back(std::move(pts));
      }
    }
    return p;
  }

  std::vector<Vec3> coordinates(const XmlNode& ring) const {
    std::vector<double> values;
    int dim = 3;
    for (const XmlNode& c : ring.children) {
      if (c.name == "posList" || c.name == "pos" || c.name == "coordinates") {
        if (const std::string* d = c.attribute("srsDimension"); d && c.name == "posList") dim = parse_dimension(*d, c.line);
        if (const std::string* d = c.attribute("dimension"); d && c.name == "posList") dim = parse_dimension(*d, c.line);
        numbers(c.text, c.name == "coordinates", c.line, values);
      }
    }
    if (values.size() % dim != 0)
      throw DataError(source_, ring.line, "ring has " + std::to_string(values.size()) + " numbers, not a multiple of its dimension " + std::to_string(dim));
    std::vector<Vec3> pts;
    for (size_t k = 0; k + dim <= values.size(); k += dim) {
      const Vec3 p(values[k], values[k + 1], dim == 3 ? values[k + 2] : 0.0);
      if (!within_coordinate_limit(p)) throw DataError(source_, ring.line, "coordinate not finite or out of range");
      pts.push_back(p);
    }
    return pts;
  }

  int parse_dimension(const std::string& s, int line) const {
    if (s == "2") return 2;
    if (s == "3") return 3;
    throw DataError(source_, line, "srsDimension '" + s.substr(0, 20) + "' is not 2 or 3");
  }

  void numbers(const std::string& text, bool commas, int line, std::vector<double>& out) const {
    const char* p = text.data();
    const char* end = p + text.size();
    auto sep = [&](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || (commas && c == ','); };
    while (p < end) {
      while (p < end && sep(*p)) ++p;
      if (p >= end) break;
      const char* q = p;
      while (q < end && !sep(*q)) ++q;
      double v = 0;
      const char* s = *p == '+' ? p + 1 : p;
      const auto r = std::from_chars(s, q, v);
      if (r.ec != std::errc() || r.ptr != q || !std::isfinite(v))
        throw DataError(source_, line, "'" + std::string(p, std::min<size_t>(q - p, 40)) + "' is not a number");
      out.push_back(v);
      p = q;
    }
  }

  const std::string& source_;
  std::unordered_map<std::string, const XmlNode*> by_id_;
  std::unordered_set<std::string> used_;
};

bool is_boundary(const std::string& name) { return name == "boundedBy" || name == "boundary"; }

// The Building and its BuildingParts, depth first.
void objects_of(const XmlNode& n, std::vector<const XmlNode*>& out) {
  out.push_back(&n);
  for (const XmlNode& c : n.children)
    if (c.name == "consistsOfBuildingPart")
      for (const XmlNode& part : c.children)
        if (part.name == "BuildingPart") objects_of(part, out);
}

const std::string* first_srs(const XmlNode& n) {
  if (const std::string* s = n.attribute("srsName")) return s;
  for (const XmlNode& c : n.children)
    if (const std::string* s = first_srs(c)) return s;
  return nullptr;
}

CityBuilding building_of(const XmlNode& b, const std::string& doc_srs, const std::string& source) {
  CityBuilding out;
  const std::string* id = b.attribute("id");
  out.id = id && !id->empty() ? *id : "building_line_" + std::to_string(b.line);
  out.line = b.line;
  const std::string* srs = first_srs(b);
  out.crs = is_geographic_crs(srs ? *srs : doc_srs) ? CityCrs::kLatLonHeight : CityCrs::kProjected;
  std::vector<const XmlNode*> objects;
  objects_of(b, objects);
  out.parts = static_cast<int>(objects.size());
  BuildingGeometry geometry(b, source);
  std::vector<CityPolygon> polys;
  for (size_t part = 0; part < objects.size(); ++part) {
    const size_t before = polys.size();
    for (const XmlNode& c : objects[part]->children) {
      if (!is_boundary(c.name)) continue;
      for (const XmlNode& surface : c.children)
        for (const XmlNode& g : surface.children)
          if (g.name == "lod2MultiSurface" || g.name == "lod2Geometry")
            geometry.collect(g, city_surface_of(surface.name), static_cast<int>(part), true, polys);
    }
    const bool semantic = polys.size() > before;
    for (const XmlNode& c : objects[part]->children)
      if (c.name == "lod2Solid" || c.name == "lod2MultiSurface")
        geometry.collect(c, CitySurface::kUnknown, static_cast<int>(part), !semantic, polys);
  }
  if (!polys.empty()) out.lods.push_back({"2", std::move(polys)});
  return out;
}

void read_all(XmlReader& r, const std::string& source, const CityBuildingVisitor& visit) {
  std::string doc_srs;
  for (XmlReader::Event ev; (ev = r.next()) != XmlReader::Event::kEof;) {
    if (ev != XmlReader::Event::kStart) continue;
    if (doc_srs.empty())
      if (const std::string* s = r.attribute("srsName")) doc_srs = *s;
    if (r.name() == "Building") {
      const XmlNode b = r.read_subtree();
      visit(building_of(b, doc_srs, source));
    } else if (r.name() == "appearanceMember" || r.name() == "Appearance") {
      r.skip_subtree();
    }
  }
}

}  // namespace

void read_city_gml(const std::filesystem::path& path, const CityBuildingVisitor& visit) {
  XmlReader r(path);
  read_all(r, path.string(), visit);
}

void parse_city_gml(std::string text, const std::string& source_name, const CityBuildingVisitor& visit) {
  XmlReader r(std::move(text), source_name);
  read_all(r, source_name, visit);
}

}  // namespace lc2wf
