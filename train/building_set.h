// The line clouds of one split, loaded into memory once (a building's cloud is small next to the cost of
// one training step).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "dataset/geometry/line_cloud.h"
#include "train/train_config.h"

namespace lc2wf {

struct BuildingSet {
  std::string split;  // split file it came from
  std::vector<LineCloud> clouds;
  // Listed buildings whose cloud could not be read or has no segments: "<name>: <the reader's message>".
  std::vector<std::string> skipped;
};

// Reads the names of `split_file` and their clouds from data.dir (format data.format), without the clouds'
// 2D observations and cameras (training does not read them). A cloud that cannot be read or has no segments
// is skipped and listed in `skipped` (one bad file must not end a run over thousands). Throws DataError naming
// the file on a building with no file (a typo in the split), an empty split or a split of which no cloud could
// be read, and the config key (`key`, e.g. "data.train_split") when the split file itself does not exist.
BuildingSet load_building_set(const DataConfig& data, const std::filesystem::path& split_file, const std::string& key,
                              bool quiet);

}  // namespace lc2wf
