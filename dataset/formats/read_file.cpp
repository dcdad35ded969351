#include "dataset/formats/read_file.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include "dataset/formats/errors.h"

namespace lc2wf {

std::string read_file(const std::filesystem::path& path) {
  if (const std::string problem = input_file_problem(path); !problem.empty()) throw DataError(path.string(), problem);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw DataError(path.string(), std::string("cannot open file: ") + std::strerror(errno));
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace lc2wf
