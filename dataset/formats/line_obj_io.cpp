#include "dataset/formats/line_obj_io.h"

#include <cstdio>

#include "dataset/formats/read_file.h"
#include "dataset/formats/errors.h"
#include "dataset/formats/mesh_io.h"

namespace lc2wf {

namespace {

ExternalLineMap line_map(const ObjData& obj, const std::string& source) {
  if (!obj.mesh.faces.empty()) throw DataError(source, "has faces ('f'): a line-cloud OBJ holds 'v' and 'l' only");
  if (obj.lines.empty()) throw DataError(source, "no 'l' segment: not a line-cloud OBJ");
  ExternalLineMap map;
  map.lines.reserve(obj.lines.size());
  for (const auto& [i, j] : obj.lines) {
    ExternalLine line;
    line.segments.push_back({obj.mesh.vertices[i], obj.mesh.vertices[j]});
    map.lines.push_back(std::move(line));
  }
  return map;
}

}  // namespace

ExternalLineMap parse_line_obj(std::istream& in, const std::string& source) { return line_map(parse_obj(in, source), source); }

ExternalLineMap read_line_obj(const std::filesystem::path& path) { return line_map(read_obj(path), path.string()); }

std::string line_obj_string(const LineCloud& cloud) {
  std::string s = "# lc2wf line cloud '" + cloud.name + "': " + std::to_string(cloud.segments.size()) + " segments (metres)\n";
  char buf[128];
  for (const Segment3& l : cloud.segments) {
    std::snprintf(buf, sizeof buf, "v %.9g %.9g %.9g\nv %.9g %.9g %.9g\n", l.a.x(), l.a.y(), l.a.z(), l.b.x(), l.b.y(), l.b.z());
    s += buf;
  }
  for (size_t k = 0; k < cloud.segments.size(); ++k) s += "l " + std::to_string(2 * k + 1) + " " + std::to_string(2 * k + 2) + "\n";
  return s;
}

void write_line_obj(const std::filesystem::path& path, const LineCloud& cloud) { write_file_atomic(path, line_obj_string(cloud)); }

}  // namespace lc2wf
