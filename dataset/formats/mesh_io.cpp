#include "dataset/formats/mesh_io.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "dataset/formats/read_file.h"
#include "dataset/formats/errors.h"
#include "dataset/formats/text_parse.h"

namespace lc2wf {
namespace {

int parse_header_count(std::string_view line, std::string_view key, const std::string& src, int line_no) {
  const std::string_view t = trim(line);
  const auto colon = t.find(':');
  if (t.empty() || t.front() != '#' || colon == std::string_view::npos ||
      t.find(key) == std::string_view::npos) {
    throw DataError(src, line_no, "expected header '# Number of " + std::string(key) + ": N'");
  }
  const auto n = parse_int(trim(t.substr(colon + 1)));
  if (!n || *n < 0 || *n > 10'000'000) throw DataError(src, line_no, "bad count in header");
  return static_cast<int>(*n);
}

}  // namespace

PolyMesh parse_polyshape(std::istream& in, const std::string& src) {
  std::string line;
  int line_no = 0;
  auto next_line = [&](const char* what) {
    if (!std::getline(in, line)) {
      throw DataError(src, line_no + 1, std::string("unexpected end of file, expected ") + what);
    }
    ++line_no;
  };
  next_line("vertex count header");
  const int nv = parse_header_count(line, "verts", src, line_no);
  next_line("face count header");
  const int nf = parse_header_count(line, "faces", src, line_no);

  PolyMesh mesh;
  for (int i = 0; i < nv; ++i) {
    next_line("a vertex line 'x,y,z'");
    const auto tok = split_tokens(line, ",");
    if (tok.size() != 3) throw DataError(src, line_no, "vertex line needs 3 comma-separated values");
    Vec3 v;
    for (int k = 0; k < 3; ++k) {
      const auto d = parse_finite_double(tok[k]);
      if (!d) throw DataError(src, line_no, "vertex coordinate '" + std::string(tok[k]) + "' is not a finite number");
      v[k] = *d;
    }
    if (!within_coordinate_limit(v)) throw DataError(src, line_no, "vertex coordinate beyond +-1e9");
    mesh.vertices.push_back(v);
  }
  // No reserve() from the header counts: a 100-byte file may claim 10^7 faces.
  for (int i = 0; i < nf; ++i) {
    next_line("a face line 'v1,...,vk,label'");
    const auto tok = split_tokens(line, ",");
    if (tok.size() < 4) throw DataError(src, line_no, "face line needs at least 3 vertex ids and a label");
    std::vector<int> face;
    for (size_t k = 0; k + 1 < tok.size(); ++k) {
      const auto id = parse_int(tok[k]);
      if (!id) throw DataError(src, line_no, "vertex id '" + std::string(tok[k]) + "' is not an integer");
      if (*id < 1 || *id > nv) {
        throw DataError(src, line_no, "vertex id " + std::to_string(*id) + " out of range 1.." + std::to_string(nv));
      }
      face.push_back(static_cast<int>(*id - 1));
    }
    const auto label = parse_int(tok.back());
    if (!label || *label < 1 || *label > 3) {
      throw DataError(src, line_no, "face label '" + std::string(tok.back()) + "' must be 1 (roof), 2 (base) or 3 (wall)");
    }
    mesh.faces.push_back(std::move(face));
    mesh.labels.push_back(static_cast<FaceLabel>(*label));
  }
  while (std::getline(in, line)) {
    ++line_no;
    if (!trim(line).empty()) throw DataError(src, line_no, "unexpected content after the last face");
  }
  return mesh;
}

PolyMesh read_polyshape(const std::filesystem::path& path) {
  if (const std::string problem = input_file_problem(path); !problem.empty()) throw DataError(path.string(), problem);
  std::ifstream in(path);
  if (!in) throw DataError(path.string(), std::string("cannot open file: ") + std::strerror(errno));
  return parse_polyshape(in, path.string());
}

ObjData parse_obj(std::istream& in, const std::string& src, const ObjReadOptions& options) {
  ObjData out;
  std::string line;
  int line_no = 0;
  // OBJ ids are 1-based, negative = relative to the vertices read so far.
  auto resolve = [&](std::string_view tok) {
    const std::string_view head = tok.substr(0, tok.find('/'));
    const auto id = parse_int(head);
    if (!id) throw DataError(src, line_no, "vertex reference '" + std::string(tok) + "' is not an integer");
    const long long n = static_cast<long long>(out.mesh.vertices.size());
    const long long idx = *id > 0 ? *id - 1 : n + *id;
    if (*id == 0 || idx < 0 || idx >= n) {
      throw DataError(src, line_no, "vertex reference " + std::to_string(*id) + " out of range (" +
                                        std::to_string(n) + " vertices so far)");
    }
    return static_cast<int>(idx);
  };
  while (std::getline(in, line)) {
    ++line_no;
    const std::string_view t = trim(line);
    if (t.empty() || t.front() == '#') continue;
    const auto tok = split_tokens(t, " \t");
    if (tok[0] == "v") {
      if (tok.size() != 4 && tok.size() != 5) throw DataError(src, line_no, "'v' needs 3 coordinates");
      Vec3 v;
      for (int k = 0; k < 3; ++k) {
        const auto d = parse_finite_double(tok[k + 1]);
        if (!d) throw DataError(src, line_no, "vertex coordinate '" + std::string(tok[k + 1]) + "' is not a finite number");
        v[k] = *d;
      }
      if (!within_coordinate_limit(v)) throw DataError(src, line_no, "vertex coordinate beyond +-1e9");
      out.mesh.vertices.push_back(options.y_up ? Vec3(v.x(), -v.z(), v.y()) : v);
    } else if (tok[0] == "f") {
      if (tok.size() < 4) throw DataError(src, line_no, "'f' needs at least 3 vertices");
      std::vector<int> face;
      for (size_t k = 1; k < tok.size(); ++k) face.push_back(resolve(tok[k]));
      out.mesh.faces.push_back(std::move(face));
    } else if (tok[0] == "l") {
      if (tok.size() < 3) throw DataError(src, line_no, "'l' needs at least 2 vertices");
      int prev = resolve(tok[1]);
      for (size_t k = 2; k < tok.size(); ++k) {
        const int cur = resolve(tok[k]);
        if (cur == prev) throw DataError(src, line_no, "'l' repeats a vertex (zero-length edge)");
        out.lines.push_back({prev, cur});
        prev = cur;
      }
    }
    // vt, vn, o, g, s, usemtl, mtllib and other statements carry nothing we use.
  }
  if (in.bad()) throw DataError(src, line_no, "read error");
  return out;
}

ObjData read_obj(const std::filesystem::path& path, const ObjReadOptions& options) {
  if (const std::string problem = input_file_problem(path); !problem.empty()) throw DataError(path.string(), problem);
  std::ifstream in(path);
  if (!in) throw DataError(path.string(), std::string("cannot open file: ") + std::strerror(errno));
  return parse_obj(in, path.string(), options);
}

Wireframe read_obj_wireframe(const std::filesystem::path& path, const ObjReadOptions& options) {
  const ObjData obj = read_obj(path, options);
  Wireframe wf;
  wf.junctions = obj.mesh.vertices;
  std::set<std::pair<int, int>> seen;
  auto add = [&](int a, int b) {
    if (a == b) return;
    const std::pair<int, int> key{std::min(a, b), std::max(a, b)};
    if (seen.insert(key).second) wf.edges.push_back({key.first, key.second});
  };
  for (const auto& l : obj.lines) add(l[0], l[1]);
  for (const auto& f : obj.mesh.faces) {
    for (size_t k = 0; k < f.size(); ++k) add(f[k], f[(k + 1) % f.size()]);
  }
  return wf;
}

namespace {

void append_vertex(std::string& s, const Vec3& m, const UnitTransform* units) {
  const Vec3 p = units ? units->to_raw(m) : m;
  char buf[128];
  std::snprintf(buf, sizeof buf, "v %.9g %.9g %.9g\n", p.x(), p.y(), p.z());
  s += buf;
}

}  // namespace

std::string obj_wireframe_string(const Wireframe& wf, const UnitTransform* units) {
  std::string s = "# lc2wf wireframe: " + std::to_string(wf.junctions.size()) + " junctions, " +
                  std::to_string(wf.edges.size()) + " edges" + (units ? " (raw units)\n" : " (metres)\n");
  for (const auto& j : wf.junctions) append_vertex(s, j, units);
  for (const auto& e : wf.edges) s += "l " + std::to_string(e[0] + 1) + " " + std::to_string(e[1] + 1) + "\n";
  return s;
}

std::string obj_mesh_string(const PolyMesh& mesh, const UnitTransform* units) {
  std::string s = std::string("# lc2wf mesh") + (units ? " (raw units)\n" : " (metres)\n");
  for (const auto& v : mesh.vertices) append_vertex(s, v, units);
  for (const auto& f : mesh.faces) {
    s += "f";
    for (int id : f) s += " " + std::to_string(id + 1);
    s += "\n";
  }
  return s;
}

std::string polyshape_string(const PolyMesh& mesh, const UnitTransform* units) {
  if (mesh.labels.size() != mesh.faces.size()) throw std::invalid_argument("polyshape_string: every face needs a label");
  std::string s = "# Number of verts: " + std::to_string(mesh.vertices.size()) + "\n# Number of faces: " +
                  std::to_string(mesh.faces.size()) + "\n";
  for (const auto& v : mesh.vertices) {
    const Vec3 p = units ? units->to_raw(v) : v;
    char buf[96];
    std::snprintf(buf, sizeof buf, "%.9g,%.9g,%.9g\n", p.x(), p.y(), p.z());
    s += buf;
  }
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    for (int id : mesh.faces[f]) s += std::to_string(id + 1) + ",";
    s += std::to_string(static_cast<int>(mesh.labels[f])) + "\n";
  }
  return s;
}

void write_polyshape(const std::filesystem::path& path, const PolyMesh& mesh, const UnitTransform* units) {
  write_file_atomic(path, polyshape_string(mesh, units));
}

void write_obj_wireframe(const std::filesystem::path& path, const Wireframe& wf, const UnitTransform* units) {
  write_file_atomic(path, obj_wireframe_string(wf, units));
}

void write_obj_mesh(const std::filesystem::path& path, const PolyMesh& mesh, const UnitTransform* units) {
  write_file_atomic(path, obj_mesh_string(mesh, units));
}

}  // namespace lc2wf
