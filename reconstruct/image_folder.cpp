#include "reconstruct/image_folder.h"

#include <algorithm>
#include <opencv2/imgcodecs.hpp>

#include "reconstruct/stage_error.h"

namespace lc2wf {

namespace fs = std::filesystem;

namespace {

std::string lower_extension(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// What both OpenCV and COLMAP 3.8 (FreeImage) decode.
bool is_image(const fs::path& p) {
  const std::string ext = lower_extension(p);
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".tif" || ext == ".tiff" || ext == ".bmp";
}

// Photos neither decodes: phones' HEIC/HEIF and cameras' raw files, which users do put in a photo folder.
bool is_unsupported_photo(const fs::path& p) {
  static const char* const kExtensions[] = {".heic", ".heif", ".dng", ".cr2", ".cr3", ".nef", ".arw", ".orf", ".rw2", ".raf"};
  const std::string ext = lower_extension(p);
  return std::find(std::begin(kExtensions), std::end(kExtensions), ext) != std::end(kExtensions);
}

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

}  // namespace

ImageFolder read_image_folder(const fs::path& dir, int min_images) {
  std::error_code ec;
  std::vector<fs::path> found, unsupported;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (is_image(e.path())) found.push_back(e.path());
    else if (is_unsupported_photo(e.path())) unsupported.push_back(e.path());
  }
  if (ec) throw StageError("images", "cannot list " + dir.string() + ": " + ec.message());
  std::sort(found.begin(), found.end());
  std::sort(unsupported.begin(), unsupported.end());
  ImageFolder f;
  for (const fs::path& p : unsupported) f.unsupported.push_back(p.filename().string());
  for (const fs::path& p : found) {
    f.all_names.push_back(p.filename().string());  // a cameras JSON has one entry per name, readable or not
    std::error_code type_ec;
    if (!fs::is_regular_file(p, type_ec)) {  // a FIFO would block the decoder for ever
      f.unreadable.push_back(p.filename().string() + " (not a regular file)");
      continue;
    }
    cv::Mat image = cv::imread(p.string(), cv::IMREAD_GRAYSCALE | cv::IMREAD_IGNORE_ORIENTATION);
    if (image.empty()) {
      f.unreadable.push_back(p.filename().string() + " (not a decodable image)");
      continue;
    }
    f.sizes.push_back(image.size());
    f.paths.push_back(p);
    f.images.push_back(std::move(image));
  }
  if (static_cast<int>(f.images.size()) < min_images)
    throw StageError("images", std::to_string(f.images.size()) + " readable image(s) in " + dir.string() + ", at least " +
                                   std::to_string(min_images) + " needed" +
                                   (f.unreadable.empty() ? std::string() : "; unreadable: " + joined(f.unreadable)) +
                                   (f.unsupported.empty() ? std::string() : "; " + unsupported_text(f.unsupported)));
  return f;
}

std::string unsupported_text(const std::vector<std::string>& names) {
  return "not read (HEIC/HEIF or camera raw: convert them to JPEG first): " + joined(names);
}

std::string describe_sizes(const std::vector<cv::Size>& sizes) {
  std::vector<std::pair<cv::Size, int>> counts;
  for (const cv::Size& s : sizes) {
    auto it = std::find_if(counts.begin(), counts.end(), [&](const auto& c) { return c.first == s; });
    if (it == counts.end()) counts.emplace_back(s, 1);
    else ++it->second;
  }
  std::stable_sort(counts.begin(), counts.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
  auto text = [](const cv::Size& s) { return std::to_string(s.width) + "x" + std::to_string(s.height); };
  if (counts.size() == 1) return text(counts.front().first);
  constexpr size_t kNamed = 3;  // a set of photos from many cameras is not listed size by size
  std::string out;
  for (size_t k = 0; k < std::min(kNamed, counts.size()); ++k)
    out += (k ? ", " : "") + std::to_string(counts[k].second) + " of " + text(counts[k].first);
  if (counts.size() > kNamed) out += " and " + std::to_string(counts.size() - kNamed) + " more sizes";
  return out;
}

}  // namespace lc2wf
