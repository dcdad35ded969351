// Line3D++ output (its `Line3D++__*.txt` files): the `.txt` file, one text line per final 3D line
// "n P1 Q1 ... Pn Qn m cam1 seg1 p1x p1y q1x q1y ... ", and a writer of the same layout for our clouds
// (one 3D segment per line, its supports as (view + 1, segment id, p, q)). `.obj` files: dataset/formats/line_obj_io.h.
#pragma once

#include <filesystem>
#include <string>

#include "dataset/formats/external_line_map.h"

namespace lc2wf {

// Throws DataError "<source>:<line>: <field> ..." naming the text line and the bad field. Counts are
// checked against the tokens present before anything is allocated.
ExternalLineMap parse_line3dpp_txt(const std::string& text, const std::string& source);
ExternalLineMap read_line3dpp_txt(const std::filesystem::path& path);

// True when the first data line looks like a Line3D++ line ("n" then 6n numbers then "m" ...).
bool looks_like_line3dpp_txt(const std::string& text);

// Our cloud in Line3D++'s `.txt` layout: image id = view + 1 (COLMAP's 1-based ids), segment id = the
// 2D segment's index among the distinct supports of that view (first seen), 9 significant digits.
std::string line3dpp_txt_string(const LineCloud& cloud);
void write_line3dpp_txt(const std::filesystem::path& path, const LineCloud& cloud);

}  // namespace lc2wf
