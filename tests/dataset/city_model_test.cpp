// City-model readers (CityJSON, CityJSONSeq, CityGML 1.0/2.0, gzip), the XML reader and the building
// catalog, on the hand-made files of tests/data/citymodels/ and on ../shared/data/lod2 when present.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "dataset/formats/building_sources.h"
#include "dataset/formats/city_gml_io.h"
#include "dataset/formats/city_json_io.h"
#include "dataset/formats/mesh_io.h"
#include "dataset/formats/xml_reader.h"
#include "test_util.h"

namespace lc2wf {
namespace {

namespace fs = std::filesystem;

fs::path fixtures() { return fs::path(LC2WF_SOURCE_DIR) / "tests" / "data" / "citymodels"; }

std::vector<CityBuilding> read_all(const fs::path& p) {
  std::vector<CityBuilding> out;
  auto visit = [&](CityBuilding&& b) { out.push_back(std::move(b)); };
  const std::string n = p.filename().string();
  if (n.find(".jsonl") != std::string::npos) read_city_json_seq(p, visit);
  else if (n.find(".gml") != std::string::npos) read_city_gml(p, visit);
  else read_city_json(p, visit);
  return out;
}

Vec3 extent(const Building& b) {
  Vec3 lo = b.mesh.vertices[0], hi = lo;
  for (const Vec3& v : b.mesh.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  return hi - lo;
}

int roofs(const Building& b) { return static_cast<int>(std::count(b.mesh.labels.begin(), b.mesh.labels.end(), FaceLabel::Roof)); }

TEST(CityModel, LodNames) {
  EXPECT_EQ(normalise_lod2("2"), "2");
  EXPECT_EQ(normalise_lod2("2.0"), "2");
  EXPECT_EQ(normalise_lod2("2.2"), "2.2");
  EXPECT_EQ(normalise_lod2("1.2"), "");
  EXPECT_EQ(normalise_lod2("3"), "");
  EXPECT_EQ(normalise_lod2("2.2x"), "");
  EXPECT_TRUE(is_geographic_crs("http://www.opengis.net/def/crs/EPSG/0/6697"));
  EXPECT_TRUE(is_geographic_crs("urn:ogc:def:crs:EPSG::4326"));
  EXPECT_FALSE(is_geographic_crs("urn:ogc:def:crs:EPSG::28992"));
  EXPECT_FALSE(is_geographic_crs("urn:adv:crs:ETRS89_UTM32*DE_DHHN2016_NH*GCG2016"));
}

TEST(CityModel, TangentPlaneIsMetric) {
  const TangentPlane tp{35.28, 139.67, 0};
  EXPECT_NEAR(tp.to_local(35.28, 139.67, 7).z(), 7, 1e-6);
  EXPECT_NEAR(tp.to_local(35.28 + 1e-4, 139.67, 0).y(), 11.09, 0.01);  // 0.0001 deg of latitude ~ 11.09 m
  EXPECT_NEAR(tp.to_local(35.28, 139.67 + 1e-4, 0).x(), 9.09, 0.01);   // times cos(35.28 deg)
}

TEST(CityJson, TriangulatedGableWithTransformBecomesSevenPolygons) {
  const auto bs = read_all(fixtures() / "gabled_triangles.city.json");
  ASSERT_EQ(bs.size(), 1u);
  EXPECT_EQ(bs[0].id, "gable");
  EXPECT_EQ(bs[0].parts, 2);
  ASSERT_EQ(bs[0].lods.size(), 1u);  // LoD 1.2 is not kept
  EXPECT_EQ(bs[0].lods[0].lod, "2.2");
  EXPECT_EQ(bs[0].lods[0].polygons.size(), 16u);
  // transform: mm integers + translate
  EXPECT_NEAR(bs[0].lods[0].polygons[0].exterior[0].x(), 85000.0, 1e-9);

  const BuildingCatalog c(fixtures() / "gabled_triangles.city.json");
  CityLoadInfo info;
  const Building b = c.load("gabled_triangles__gable", {}, &info);
  EXPECT_EQ(info.cleanup.faces_merged, 9);
  EXPECT_EQ(b.mesh.faces.size(), 7u);
  EXPECT_EQ(b.wireframe.junctions.size(), 10u);
  EXPECT_EQ(b.wireframe.edges.size(), 15u);
  EXPECT_EQ(roofs(b), 2);
  EXPECT_TRUE(extent(b).isApprox(Vec3(10, 6, 5), 1e-9));
  // Projected CRS: metres as they are, the building's offset in its UnitTransform.
  EXPECT_EQ(b.units.raw_per_metre, 1.0);
  EXPECT_TRUE(b.units.origin_raw.isApprox(Vec3(85005, 445003, 0), 1e-12));
}

TEST(CityJson, EachRepairOnItsOwnBuilding) {
  const BuildingCatalog c(fixtures() / "parts_and_repairs.city.json");
  // lod1only has no LoD 2 geometry: not listed.
  EXPECT_EQ(c.names(), (std::vector<std::string>{"parts_and_repairs__collinear", "parts_and_repairs__innerring", "parts_and_repairs__open",
                                                  "parts_and_repairs__pair", "parts_and_repairs__tjunction"}));
  ASSERT_EQ(c.files().size(), 1u);
  EXPECT_EQ(c.files()[0].without_lod, 1);
  struct Want {
    const char* name;
    size_t vertices, edges, faces;
  };
  for (const Want& w : {Want{"parts_and_repairs__pair", 8, 12, 6}, Want{"parts_and_repairs__collinear", 8, 12, 6},
                        Want{"parts_and_repairs__innerring", 8, 12, 6}, Want{"parts_and_repairs__tjunction", 12, 18, 8}}) {
    CityLoadInfo info;
    const Building b = c.load(w.name, {}, &info);
    EXPECT_EQ(b.wireframe.junctions.size(), w.vertices) << w.name;
    EXPECT_EQ(b.wireframe.edges.size(), w.edges) << w.name;
    EXPECT_EQ(b.mesh.faces.size(), w.faces) << w.name;
    if (std::string(w.name) == "parts_and_repairs__pair") EXPECT_EQ(info.cleanup.coincident_faces_removed, 2);
    if (std::string(w.name) == "parts_and_repairs__collinear") EXPECT_EQ(info.cleanup.collinear_vertices_removed, 1);
    if (std::string(w.name) == "parts_and_repairs__innerring") EXPECT_EQ(info.cleanup.inner_rings_dropped, 1);
  }
  try {
    c.load("parts_and_repairs__open");
    FAIL() << "an open building loaded";
  } catch (const Lod2Skipped& e) {
    EXPECT_EQ(e.reason(), "not_closed");
    EXPECT_NE(std::string(e.what()).find("parts_and_repairs__open"), std::string::npos);
  }
  EXPECT_THROW(c.load("parts_and_repairs__nothing"), DataError);
}

TEST(CityJson, PrefersTheGeometryWithSemanticsAndReadsNumberLods) {
  // CityJSON 1.0 style: lod as a number; two LoD 2 geometries (a MultiSurface with semantics, a Solid without).
  const std::string doc = R"({"type":"CityJSON","version":"1.0","CityObjects":{"b":{"type":"Building","geometry":[
    {"type":"Solid","lod":2,"boundaries":[[[[0,1,2]],[[0,2,3]]]]},
    {"type":"MultiSurface","lod":2,"boundaries":[[[0,1,2]]],"semantics":{"surfaces":[{"type":"RoofSurface"}],"values":[0]}}]}},
    "vertices":[[0,0,0],[1,0,0],[1,1,0],[0,1,0]]})";
  std::vector<CityBuilding> bs;
  parse_city_json(doc, "t.json", [&](CityBuilding&& b) { bs.push_back(std::move(b)); });
  ASSERT_EQ(bs.size(), 1u);
  ASSERT_EQ(bs[0].lods.size(), 1u);
  EXPECT_EQ(bs[0].lods[0].lod, "2");
  ASSERT_EQ(bs[0].lods[0].polygons.size(), 1u);
  EXPECT_EQ(bs[0].lods[0].polygons[0].kind, CitySurface::kRoof);
}

TEST(CityJson, BadFilesNameFileAndProblem) {
  auto parse = [](const std::string& doc) { parse_city_json(doc, "bad.city.json", [](CityBuilding&&) {}); };
  EXPECT_THROW(parse("{"), DataError);
  EXPECT_THROW(parse(R"({"type":"Other"})"), DataError);
  try {
    parse(R"({"type":"CityJSON","CityObjects":{"b":{"type":"Building","geometry":[{"type":"MultiSurface","lod":"2","boundaries":[[[0,1,7]]]}]}},"vertices":[[0,0,0],[1,0,0]]})");
    FAIL();
  } catch (const DataError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.city.json"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("vertex id 7 out of range"), std::string::npos);
  }
  std::istringstream seq(R"({"type":"CityJSON","version":"2.0","transform":{"scale":[1,1,1],"translate":[0,0,0]}}
{"type":"CityJSONFeature","CityObjects":{"b":{"type":"Building","geometry":[{"type":"MultiSurface","lod":"2","boundaries":"x"}]}},"vertices":[]})");
  try {
    parse_city_json_seq(seq, "bad.jsonl", [](CityBuilding&&) {});
    FAIL();
  } catch (const DataError& e) {
    EXPECT_EQ(e.line(), 2);
  }
}

TEST(CityJsonSeq, TwoFeaturesWithTheHeadersTransformAndALodChoice) {
  const auto bs = read_all(fixtures() / "two_features.city.jsonl");
  ASSERT_EQ(bs.size(), 2u);
  EXPECT_EQ(bs[0].id, "seq-box");
  EXPECT_EQ(bs[0].line, 2);
  EXPECT_EQ(bs[1].id, "seq-gable");
  EXPECT_NEAR(bs[0].lods[0].polygons[0].exterior[0].z(), 20.0, 1e-9);  // translate z

  const BuildingCatalog all(fixtures() / "two_features.city.jsonl");
  EXPECT_EQ(all.names(), (std::vector<std::string>{"two_features__seq-box", "two_features__seq-gable"}));
  const Building box = all.load("two_features__seq-box");
  EXPECT_TRUE(extent(box).isApprox(Vec3(12, 8, 6), 1e-9));
  BuildingSourceOptions o;
  o.lod = "2.2";
  const BuildingCatalog only22(fixtures() / "two_features.city.jsonl", o);
  EXPECT_EQ(only22.names(), std::vector<std::string>{"two_features__seq-gable"});
  o.lod = "2.0";
  EXPECT_EQ(BuildingCatalog(fixtures() / "two_features.city.jsonl", o).names(), std::vector<std::string>{"two_features__seq-box"});
  o.lod = "1.2";
  EXPECT_THROW(BuildingCatalog(fixtures(), o), std::invalid_argument);
}

TEST(CityGml, Version1SemanticSurfacesAndSolidReferencesCountOnce) {
  const auto bs = read_all(fixtures() / "nrw_like_v1.gml");
  ASSERT_EQ(bs.size(), 2u);
  EXPECT_EQ(bs[0].id, "DENW_gable");
  EXPECT_EQ(bs[0].crs, CityCrs::kProjected);
  ASSERT_EQ(bs[0].lods.size(), 1u);
  ASSERT_EQ(bs[0].lods[0].polygons.size(), 7u);  // the lod2Solid's xlinks add nothing
  int roof = 0;
  for (const auto& p : bs[0].lods[0].polygons) roof += p.kind == CitySurface::kRoof;
  EXPECT_EQ(roof, 2);
  // No semantics: the solid's own polygons, classified by normal and height.
  ASSERT_EQ(bs[1].lods[0].polygons.size(), 6u);
  EXPECT_EQ(bs[1].lods[0].polygons[0].kind, CitySurface::kUnknown);
  const BuildingCatalog c(fixtures() / "nrw_like_v1.gml");
  const Building plain = c.load("nrw_like_v1__DENW_nosemantics");
  EXPECT_EQ(roofs(plain), 1);
  EXPECT_EQ(std::count(plain.mesh.labels.begin(), plain.mesh.labels.end(), FaceLabel::Base), 1);
  const Building gable = c.load("nrw_like_v1__DENW_gable");
  EXPECT_EQ(gable.wireframe.edges.size(), 15u);
}

TEST(CityGml, Version2GeographicWithPartsIsAMetricBox) {
  const auto bs = read_all(fixtures() / "plateau_like_v2.gml");
  ASSERT_EQ(bs.size(), 2u);
  EXPECT_TRUE(bs[0].lods.empty());  // LoD 1 only
  EXPECT_EQ(bs[1].crs, CityCrs::kLatLonHeight);
  EXPECT_EQ(bs[1].parts, 3);
  const BuildingCatalog c(fixtures() / "plateau_like_v2.gml");
  EXPECT_EQ(c.names(), std::vector<std::string>{"plateau_like_v2__bldg_two_parts"});
  CityLoadInfo info;
  const Building b = c.load("plateau_like_v2__bldg_two_parts", {}, &info);
  EXPECT_EQ(info.crs, CityCrs::kLatLonHeight);
  EXPECT_NEAR(info.tangent_plane.lat0_deg, 35.28, 1e-3);
  EXPECT_EQ(b.mesh.faces.size(), 6u);  // the wall between the parts is gone
  EXPECT_EQ(b.wireframe.edges.size(), 12u);
  const Vec3 e = extent(b);
  EXPECT_NEAR(e.x(), 16, 0.01);
  EXPECT_NEAR(e.y(), 6, 0.01);
  EXPECT_NEAR(e.z(), 3, 0.01);
}

TEST(CityGml, GzipGivesTheSameBuilding) {
  const BuildingCatalog gz(fixtures() / "nrw_like_gz.gml.gz");
  const BuildingCatalog plain(fixtures() / "nrw_like_v1.gml");
  const Building a = gz.load("nrw_like_gz__DENW_gzipped");
  const Building b = plain.load("nrw_like_v1__DENW_gable");
  EXPECT_EQ(a.mesh.vertices, b.mesh.vertices);
  EXPECT_EQ(a.wireframe.edges, b.wireframe.edges);
  // A truncated gzip stream is an error naming the file, not a hang or a crash.
  const fs::path dir = test::scratch_dir("city_gz");
  std::ifstream in(fixtures() / "nrw_like_gz.gml.gz", std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::ofstream(dir / "cut.gml.gz", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  const BuildingCatalog cut(dir / "cut.gml.gz");
  ASSERT_EQ(cut.files().size(), 1u);
  EXPECT_NE(cut.files()[0].error.find("cut.gml.gz"), std::string::npos);
  EXPECT_TRUE(cut.names().empty());
  fs::remove_all(dir);
}

TEST(XmlReader, EntitiesCdataCommentsAndErrors) {
  XmlReader r(R"(<?xml version="1.0"?><!DOCTYPE a [<!ENTITY x "y">]><a:root xmlns:a="u"><!-- a -- b ---><b id="1 &amp; 2"/><c>x &lt; <![CDATA[<y>]]> &#65;</c></a:root>)",
              "t.xml");
  ASSERT_EQ(r.next(), XmlReader::Event::kStart);
  EXPECT_EQ(r.name(), "root");
  ASSERT_EQ(r.next(), XmlReader::Event::kStart);
  EXPECT_EQ(*r.attribute("id"), "1 & 2");
  ASSERT_EQ(r.next(), XmlReader::Event::kEnd);
  ASSERT_EQ(r.next(), XmlReader::Event::kStart);
  const XmlNode c = r.read_subtree();
  EXPECT_EQ(c.text, "x < <y> A");
  EXPECT_EQ(r.next(), XmlReader::Event::kEnd);
  EXPECT_EQ(r.next(), XmlReader::Event::kEof);

  auto drain = [](std::string text, XmlLimits limits = {}) {
    XmlReader x(std::move(text), "bad.gml", limits);
    while (x.next() != XmlReader::Event::kEof) {
    }
  };
  EXPECT_THROW(drain("<a><b></a>"), DataError);
  EXPECT_THROW(drain("<a>"), DataError);
  EXPECT_THROW(drain("<a x=1/>"), DataError);
  XmlReader bogus("<a>&bogus;</a>", "bad.gml");  // text is decoded (and checked) inside subtrees only
  ASSERT_EQ(bogus.next(), XmlReader::Event::kStart);
  EXPECT_THROW(bogus.read_subtree(), DataError);
  XmlLimits shallow;
  shallow.max_depth = 3;
  EXPECT_THROW(drain("<a><a><a><a></a></a></a></a>", shallow), DataError);
  try {
    drain("<a>\n\n<b></c></a>");
    FAIL();
  } catch (const DataError& e) {
    EXPECT_EQ(e.line(), 3);
  }
}

TEST(BuildingCatalog, NamesAreSanitisedUniqueAndSorted) {
  EXPECT_EQ(sanitise_building_name("f__a/b c:d"), "f__a_b_c_d");
  EXPECT_EQ(sanitise_building_name(".hidden"), "_.hidden");
  EXPECT_EQ(sanitise_building_name(std::string(400, 'x')).size(), 150u);
  EXPECT_NE(sanitise_building_name(std::string(400, 'x')), sanitise_building_name(std::string(401, 'x')));
  const fs::path dir = test::scratch_dir("city_names");
  std::ofstream(dir / "m.city.json") << R"({"type":"CityJSON","version":"2.0","CityObjects":{
    "a/b":{"type":"Building","geometry":[{"type":"MultiSurface","lod":"2","boundaries":[[[0,1,2]]]}]},
    "a b":{"type":"Building","geometry":[{"type":"MultiSurface","lod":"2","boundaries":[[[0,1,2]]]}]}},
    "vertices":[[0,0,0],[1,0,0],[1,1,0]]})";
  std::ofstream(dir / "notes.json") << R"({"type":"something else"})";  // not a city model: ignored
  // A Roof-Image mesh beside them keeps its plain stem and loads exactly as before.
  std::ofstream(dir / "CG10_1.polyshape") << "# Number of verts: 4\n# Number of faces: 4\n0,0,0\n20,0,0\n0,20,0\n0,0,20\n1,3,2,2\n1,2,4,3\n2,3,4,1\n3,1,4,3\n";
  const BuildingCatalog c(dir);
  EXPECT_EQ(c.names(), (std::vector<std::string>{"CG10_1", "m__a_b", "m__a_b__2"}));
  const Building poly = c.load("CG10_1");
  const Building direct = load_roof_image_building(dir / "CG10_1.polyshape");
  EXPECT_EQ(poly.mesh.vertices, direct.mesh.vertices);
  EXPECT_EQ(poly.wireframe.edges, direct.wireframe.edges);
  EXPECT_EQ(poly.units.raw_per_metre, kRawUnitsPerMetre);
  EXPECT_THROW(c.load("m__a_b"), Lod2Skipped);  // a lone triangle does not close
  EXPECT_THROW(BuildingCatalog(dir / "missing.gml"), DataError);
  fs::remove_all(dir);
}

// Every building of ../shared/data/lod2 is listed; a sample loads with few skips.
TEST(BuildingCatalog, SharedLod2Data) {
  const fs::path root = test::shared_data_dir() / "lod2";
  if (!fs::is_directory(root)) GTEST_SKIP() << "LoD2 data not found at " << root;
  size_t listed = 0, tried = 0, skipped = 0;
  for (const char* sub : {"cityjson", "citygml/nrw", "citygml/plateau"}) {
    const BuildingCatalog c(root / sub);
    for (const auto& f : c.files()) EXPECT_EQ(f.error, "") << f.file;
    listed += c.entries().size();
    for (size_t i = 0; i < c.entries().size(); i += 25) {
      ++tried;
      try {
        const Building b = c.load(c.entries()[i].name);
        EXPECT_GE(b.mesh.faces.size(), 4u);
      } catch (const Lod2Skipped&) {
        ++skipped;
      }
    }
  }
  EXPECT_EQ(listed, 7491u);  // 7490 buildings, one of them in two files
  EXPECT_LE(skipped * 50, tried) << skipped << " of " << tried;  // under 2 %
}

}  // namespace
}  // namespace lc2wf
