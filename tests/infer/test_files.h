// Scratch folders and small files for the infer I/O and CLI tests.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace lc2wf::testing {

// A fresh folder under the system temp dir, removed when the object goes out of scope.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& tag)
      : path_(std::filesystem::temp_directory_path() /
              ("lc2wf_infer_" + tag + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() { std::filesystem::remove_all(path_); }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

inline void write_text(const std::filesystem::path& p, const std::string& text) {
  std::filesystem::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

inline std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A 10 x 6 x 4 raw-unit box building (Roof-Image polyshape format, 20 raw = 1 m): 8 vertices, 12 edges.
inline std::string box_polyshape(double x0) {
  std::string s = "# Number of verts: 8\n# Number of faces: 6\n";
  for (int z : {4, 0})
    for (auto [x, y] : {std::pair{0, 0}, {10, 0}, {10, 6}, {0, 6}})
      s += std::to_string(x0 + x) + "," + std::to_string(y) + "," + std::to_string(z) + "\n";
  s += "1,2,3,4,1\n8,7,6,5,2\n1,5,6,2,3\n2,6,7,3,3\n3,7,8,4,3\n4,8,5,1,3\n";
  return s;
}

}  // namespace lc2wf::testing
