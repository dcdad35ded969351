#include "dataset/formats/limap_io.h"

#include "dataset/formats/read_file.h"
#include "dataset/formats/errors.h"
#include "dataset/formats/text_parse.h"

namespace lc2wf {

namespace fs = std::filesystem;

namespace {

struct NumberedLine {
  int number = 0;
  std::vector<std::string_view> tokens;
};

// Non-empty lines with their 1-based numbers, tokens split on any whitespace.
std::vector<NumberedLine> tokenised_lines(const std::string& text) {
  std::vector<NumberedLine> out;
  size_t pos = 0;
  int n = 0;
  while (pos < text.size()) {
    const size_t end = std::min(text.find('\n', pos), text.size());
    ++n;
    auto tokens = split_tokens(std::string_view(text).substr(pos, end - pos), " \t\r");
    if (!tokens.empty()) out.push_back({n, std::move(tokens)});
    pos = end + 1;
  }
  return out;
}

class TrackParser {
 public:
  TrackParser(const std::string& text, const std::string& source) : lines_(tokenised_lines(text)), source_(source) {}

  ExternalLine parse() {
    ExternalLine track;
    const NumberedLine& first = next("the 3D line 'sx sy sz ex ey ez'");
    expect_size(first, 6, "the 3D line");
    Segment3 s;
    for (int d = 0; d < 3; ++d) s.a[d] = number(first, d, "start coordinate");
    for (int d = 0; d < 3; ++d) s.b[d] = number(first, 3 + d, "end coordinate");
    track.segments.push_back(s);

    const NumberedLine& counts = next("'n_lines n_images'");
    expect_size(counts, 2, "the counts line");
    const long long n = integer(counts, 0, "n_lines", 0);
    integer(counts, 1, "n_images", 0);
    // One 2D segment row per supporting line must follow: bound n by the lines left before allocating.
    if (n > static_cast<long long>(lines_.size() - next_))
      fail(counts, "n_lines = " + std::to_string(n) + " exceeds the lines left in the file");

    const NumberedLine& images = keyword_line("image_id_list", n);
    const NumberedLine& ids = keyword_line("line_id_list", n);
    const NumberedLine& header = next("'line2d_list'");
    if (header.tokens[0] != "line2d_list" || header.tokens.size() != 1) fail(header, "expected the keyword 'line2d_list'");
    track.supports.resize(static_cast<size_t>(n));
    for (long long k = 0; k < n; ++k) {
      ExternalSupport& sup = track.supports[k];
      sup.image_id = integer(images, 1 + k, "image id", 0);
      sup.segment_id = integer(ids, 1 + k, "line id", 0);
      const NumberedLine& row = next("2D segment row " + std::to_string(k + 1));
      expect_size(row, 4, "a 2D segment row 'x1 y1 x2 y2'");
      sup.seg.a = Vec2(number(row, 0, "x1"), number(row, 1, "y1"));
      sup.seg.b = Vec2(number(row, 2, "x2"), number(row, 3, "y2"));
    }
    // node_id_list, score_list, line3d_list (+ rows) and END carry nothing the cloud needs.
    return track;
  }

 private:
  const NumberedLine& next(const std::string& what) {
    if (next_ >= lines_.size()) throw DataError(source_, "file ends before " + what);
    return lines_[next_++];
  }
  [[noreturn]] void fail(const NumberedLine& l, const std::string& problem) const { throw DataError(source_, l.number, problem); }
  void expect_size(const NumberedLine& l, size_t n, const std::string& what) const {
    if (l.tokens.size() != n) fail(l, what + " needs " + std::to_string(n) + " values, found " + std::to_string(l.tokens.size()));
  }
  const NumberedLine& keyword_line(const std::string& keyword, long long n) {
    const NumberedLine& l = next("'" + keyword + "'");
    if (l.tokens[0] != keyword) fail(l, "expected the keyword '" + keyword + "'");
    if (static_cast<long long>(l.tokens.size()) != n + 1)
      fail(l, keyword + " needs n_lines = " + std::to_string(n) + " ids, found " + std::to_string(l.tokens.size() - 1));
    return l;
  }
  double number(const NumberedLine& l, size_t k, const std::string& field) const {
    const auto v = parse_finite_double(l.tokens[k]);
    if (!v) fail(l, field + " '" + std::string(l.tokens[k]) + "' is not a finite number");
    return *v;
  }
  long long integer(const NumberedLine& l, size_t k, const std::string& field, long long min_value) const {
    const auto v = parse_int(l.tokens[k]);
    if (!v || *v < min_value) fail(l, field + " '" + std::string(l.tokens[k]) + "' is not an integer >= " + std::to_string(min_value));
    return *v;
  }

  std::vector<NumberedLine> lines_;
  size_t next_ = 0;
  const std::string& source_;
};

fs::path tracks_folder(const fs::path& dir) {
  return fs::exists(dir / "track_0.txt") || !fs::is_directory(dir / "finaltracks") ? dir : dir / "finaltracks";
}

}  // namespace

ExternalLine parse_limap_track(const std::string& text, const std::string& source) { return TrackParser(text, source).parse(); }

bool is_limap_tracks_dir(const fs::path& dir) {
  std::error_code ec;
  return fs::is_directory(dir, ec) && fs::is_regular_file(tracks_folder(dir) / "track_0.txt", ec);
}

ExternalLineMap read_limap_tracks(const fs::path& dir) {
  const fs::path folder = tracks_folder(dir);
  std::error_code ec;
  size_t files = 0;
  for (const auto& e : fs::directory_iterator(folder, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("track", 0) == 0 && e.path().extension() == ".txt") ++files;
  }
  if (ec) throw DataError(folder.string(), "cannot list folder: " + ec.message());
  if (files == 0) throw DataError(folder.string(), "no track_<i>.txt file (not a LIMAP finaltracks folder)");
  ExternalLineMap map;
  map.lines.reserve(files);
  for (size_t i = 0; i < files; ++i) {
    const fs::path p = folder / ("track_" + std::to_string(i) + ".txt");
    if (!fs::is_regular_file(p, ec))
      throw DataError(p.string(), "missing: " + std::to_string(files) + " track files but no track_" + std::to_string(i) + ".txt");
    map.lines.push_back(parse_limap_track(read_file(p), p.string()));
  }
  return map;
}

}  // namespace lc2wf
