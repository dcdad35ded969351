#include "reconstruct/image_folder.h"

#include <algorithm>
#include <opencv2/imgcodecs.hpp>

#include "reconstruct/stage_error.h"

namespace lc2wf {

namespace fs = std::filesystem;

namespace {

bool is_image(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg";
}

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

}  // namespace

ImageFolder read_image_folder(const fs::path& dir, int min_images) {
  std::error_code ec;
  std::vector<fs::path> found;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (is_image(e.path())) found.push_back(e.path());
  if (ec) throw StageError("images", "cannot list " + dir.string() + ": " + ec.message());
  std::sort(found.begin(), found.end());
  ImageFolder f;
  std::vector<std::string> odd_size;
  for (const fs::path& p : found) {
    f.all_names.push_back(p.filename().string());  // a cameras JSON has one entry per name, readable or not
    std::error_code type_ec;
    if (!fs::is_regular_file(p, type_ec)) {  // a FIFO would block the decoder for ever
      f.unreadable.push_back(p.filename().string() + " (not a regular file)");
      continue;
    }
    cv::Mat image = cv::imread(p.string(), cv::IMREAD_GRAYSCALE);
    if (image.empty()) {
      f.unreadable.push_back(p.filename().string() + " (not a decodable image)");
      continue;
    }
    if (f.images.empty()) f.width = image.cols, f.height = image.rows;
    if (image.cols != f.width || image.rows != f.height) {
      odd_size.push_back(p.filename().string() + " (" + std::to_string(image.cols) + "x" + std::to_string(image.rows) + ")");
      continue;
    }
    f.paths.push_back(p);
    f.images.push_back(std::move(image));
  }
  if (!odd_size.empty())
    throw StageError("images", "one camera expected, but " + joined(odd_size) + " differ from the first image's " +
                                   std::to_string(f.width) + "x" + std::to_string(f.height) + " in " + dir.string());
  if (static_cast<int>(f.images.size()) < min_images)
    throw StageError("images", std::to_string(f.images.size()) + " readable image(s) in " + dir.string() + ", at least " +
                                   std::to_string(min_images) + " needed" +
                                   (f.unreadable.empty() ? std::string() : "; unreadable: " + joined(f.unreadable)));
  return f;
}

}  // namespace lc2wf
