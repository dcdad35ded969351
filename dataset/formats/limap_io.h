// LIMAP line maps (10 decimals, fixed layout): the `finaltracks/` folder, one
// `track_<i>.txt` per track (its 3D line, then the supporting image ids, 2D line ids and 2D segments).
// LIMAP's `.obj` export is read by dataset/formats/line_obj_io.h.
#pragma once

#include <filesystem>
#include <string>

#include "dataset/formats/external_line_map.h"

namespace lc2wf {

// One track file; throws DataError "<source>:<line>: <field> ..." on malformed input. Counts are checked
// against the lines present before anything is allocated.
ExternalLine parse_limap_track(const std::string& text, const std::string& source);

// `dir` is the `finaltracks/` folder or a folder holding one. Reads track_0 ... track_<N-1> in order
// (N = number of track*.txt files); a gap is an error naming the missing file.
ExternalLineMap read_limap_tracks(const std::filesystem::path& dir);

// True for a folder that holds track_0.txt, directly or under finaltracks/.
bool is_limap_tracks_dir(const std::filesystem::path& dir);

}  // namespace lc2wf
