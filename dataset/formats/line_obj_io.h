// Line clouds as Wavefront OBJ: `v` per endpoint and `l a b` per segment, the layout of Line3D++'s and
// LIMAP's `.obj` outputs (vertices not shared) and of our cloud export for MeshLab. No supports.
#pragma once

#include <filesystem>
#include <istream>
#include <string>

#include "dataset/formats/external_line_map.h"

namespace lc2wf {

// Every `l` segment (a polyline gives its consecutive pairs) becomes one line with one segment, in file
// order. Faces are rejected (a mesh is not a line cloud). Throws DataError naming the file and line.
ExternalLineMap parse_line_obj(std::istream& in, const std::string& source);
ExternalLineMap read_line_obj(const std::filesystem::path& path);

// Metres, 9 significant digits; written atomically.
std::string line_obj_string(const LineCloud& cloud);
void write_line_obj(const std::filesystem::path& path, const LineCloud& cloud);

}  // namespace lc2wf
