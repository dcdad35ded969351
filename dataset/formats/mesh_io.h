// Readers for Roof-Image `.polyshape` meshes and Wavefront OBJ (meshes and `l` wireframes), and OBJ
// writers. Readers keep the file's own units and axes; conversion to metres happens in building.h.
// Every reader throws DataError("<file>:<line>: <problem>") on malformed input.
#pragma once

#include <array>
#include <filesystem>
#include <istream>
#include <string>
#include <vector>

#include "dataset/geometry/geometry.h"

namespace lc2wf {

// Roof-Image polyshape: "# Number of verts: NV", "# Number of faces: NF", NV lines "x,y,z", NF lines
// "v1,...,vk,label" (1-based ids, label 1 roof / 2 base / 3 wall).
PolyMesh parse_polyshape(std::istream& in, const std::string& source_name);
PolyMesh read_polyshape(const std::filesystem::path& path);

struct ObjReadOptions {
  // Roof-Image `res_obj` files are Y-up (Blender export): (x, y, z)_obj -> (x, -z, y) gives polyshape axes.
  bool y_up = false;
};

// Everything an OBJ holds that we use: `v`, `f` (a, a/b, a/b/c, a//c, negative = relative), `l` polylines.
struct ObjData {
  PolyMesh mesh;                             // vertices + faces (labels empty)
  std::vector<std::array<int, 2>> lines;     // consecutive pairs of every `l` polyline, 0-based, as written
};

ObjData parse_obj(std::istream& in, const std::string& source_name, const ObjReadOptions& options = {});
ObjData read_obj(const std::filesystem::path& path, const ObjReadOptions& options = {});

// Wireframe from an OBJ: all vertices as junctions; edges = `l` segments plus face boundary edges,
// unique, stored (min, max), in first-seen order.
Wireframe read_obj_wireframe(const std::filesystem::path& path, const ObjReadOptions& options = {});

// Writers (atomic). `units`, when given, maps metres back to raw units before writing.
void write_obj_wireframe(const std::filesystem::path& path, const Wireframe& wireframe,
                         const UnitTransform* units = nullptr);
void write_obj_mesh(const std::filesystem::path& path, const PolyMesh& mesh, const UnitTransform* units = nullptr);
std::string obj_wireframe_string(const Wireframe& wireframe, const UnitTransform* units = nullptr);
std::string obj_mesh_string(const PolyMesh& mesh, const UnitTransform* units = nullptr);
// Roof-Image polyshape of a labelled mesh (what parse_polyshape reads); throws std::invalid_argument
// when a face has no label.
std::string polyshape_string(const PolyMesh& mesh, const UnitTransform* units = nullptr);
void write_polyshape(const std::filesystem::path& path, const PolyMesh& mesh, const UnitTransform* units = nullptr);

}  // namespace lc2wf
