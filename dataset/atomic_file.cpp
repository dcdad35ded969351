#include "dataset/atomic_file.h"

#include <fstream>
#include <sstream>
#include <string>

#include "dataset/errors.h"

namespace lc2wf {

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw DataError(path.string(), "cannot open file");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace lc2wf
