#include "train/building_set.h"

#include <memory>

#include "core/util/progress.h"
#include "dataset/formats/errors.h"
#include "dataset/formats/cloud_input.h"
#include "dataset/splits/splits.h"

namespace lc2wf {

BuildingSet load_building_set(const DataConfig& data, const std::filesystem::path& split_file, const std::string& key,
                              bool quiet) {
  std::error_code ec;
  if (!std::filesystem::exists(split_file, ec)) throw DataError(split_file.string(), "no such split file (named by " + key + ")");
  BuildingSet set;
  set.split = split_file.string();
  const std::vector<std::string> names = read_name_list(split_file);
  if (names.empty()) throw DataError(split_file.string(), "split lists no building");
  const CloudFormat format = parse_cloud_format(data.format, "data.format");
  std::unique_ptr<Progress> progress;
  if (!quiet) progress = std::make_unique<Progress>("loading " + split_file.filename().string(), names.size());
  for (const std::string& name : names) {
    std::filesystem::path file;
    try {
      file = find_cloud_file(data.dir, name);
    } catch (const DataError& e) {  // a typo in the split is found through the split file
      throw DataError(split_file.string(), "lists '" + name + "', but " + e.what());
    }
    LineCloud cloud;
    try {
      cloud = load_line_cloud(file, format, data.raw_per_metre);
      if (cloud.segments.empty()) throw DataError(file.string(), "line cloud has no segments (cannot be trained on)");
    } catch (const std::exception& e) {  // the reader's message names the file and the problem
      set.skipped.push_back(name + ": " + e.what());
      if (progress) progress->step();
      continue;
    }
    cloud.name = name;
    // Training reads segments, labels and the wireframe only; a rendered cloud's 2D observations are most of
    // its memory (1.1 of 1.4 GB for the 2,626 training clouds rendered from 30 views). The cameras (a few kB)
    // stay: validation's edge-support rule asks them, as lc2wf-eval's does (model/edge_support.h).
    cloud.support = std::vector<std::vector<Observation>>();
    set.clouds.push_back(std::move(cloud));
    if (progress) progress->step();
  }
  if (set.clouds.empty())
    throw DataError(split_file.string(), "none of its " + std::to_string(names.size()) + " buildings could be read; the first: " + set.skipped.front());
  return set;
}

}  // namespace lc2wf
