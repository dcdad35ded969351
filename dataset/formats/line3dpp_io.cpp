#include "dataset/formats/line3dpp_io.h"

#include <cstdio>
#include <map>
#include <tuple>

#include "dataset/formats/read_file.h"
#include "dataset/formats/errors.h"
#include "dataset/formats/text_parse.h"

namespace lc2wf {

namespace {

// Reads the tokens of one text line in order, naming the field and line of the first bad one.
class TokenCursor {
 public:
  TokenCursor(std::vector<std::string_view> tokens, const std::string& source, int line)
      : tokens_(std::move(tokens)), source_(source), line_(line) {}

  size_t remaining() const { return tokens_.size() - next_; }
  double number(const std::string& field) {
    const auto v = parse_finite_double(take(field));
    if (!v) fail(field + " '" + std::string(tokens_[next_ - 1]) + "' is not a finite number");
    return *v;
  }
  long long count(const std::string& field, long long min_value) {
    const auto v = parse_int(take(field));
    if (!v || *v < min_value)
      fail(field + " '" + std::string(tokens_[next_ - 1]) + "' is not an integer >= " + std::to_string(min_value));
    return *v;
  }
  [[noreturn]] void fail(const std::string& problem) const { throw DataError(source_, line_, problem); }

 private:
  std::string_view take(const std::string& field) {
    if (next_ >= tokens_.size()) fail("line ends before " + field);
    return tokens_[next_++];
  }
  std::vector<std::string_view> tokens_;
  size_t next_ = 0;
  const std::string& source_;
  int line_;
};

ExternalLine parse_line(TokenCursor& c) {
  ExternalLine line;
  const long long n = c.count("segment count n", 1);
  // Each segment needs 6 numbers, plus the support count after them: bound n before allocating.
  if (n > static_cast<long long>(c.remaining() / 6)) c.fail("segment count n = " + std::to_string(n) + " exceeds the numbers on the line");
  line.segments.resize(static_cast<size_t>(n));
  for (long long k = 0; k < n; ++k) {
    const std::string at = " of segment " + std::to_string(k + 1);
    Segment3& s = line.segments[k];
    for (int d = 0; d < 3; ++d) s.a[d] = c.number(std::string("P") + "xyz"[d] + at);
    for (int d = 0; d < 3; ++d) s.b[d] = c.number(std::string("Q") + "xyz"[d] + at);
  }
  const long long m = c.count("support count m", 0);
  if (m != static_cast<long long>(c.remaining() / 6) || c.remaining() % 6 != 0)
    c.fail("support count m = " + std::to_string(m) + " does not match the " + std::to_string(c.remaining()) +
           " values after it (6 per support)");
  line.supports.resize(static_cast<size_t>(m));
  for (long long k = 0; k < m; ++k) {
    const std::string at = " of support " + std::to_string(k + 1);
    ExternalSupport& s = line.supports[k];
    s.image_id = c.count("camera id" + at, 0);
    s.segment_id = c.count("segment id" + at, 0);
    s.seg.a.x() = c.number("p.x" + at);
    s.seg.a.y() = c.number("p.y" + at);
    s.seg.b.x() = c.number("q.x" + at);
    s.seg.b.y() = c.number("q.y" + at);
  }
  return line;
}

}  // namespace

ExternalLineMap parse_line3dpp_txt(const std::string& text, const std::string& source) {
  ExternalLineMap map;
  int line_no = 0;
  size_t pos = 0;
  while (pos < text.size()) {
    const size_t end = std::min(text.find('\n', pos), text.size());
    const std::string_view raw(text.data() + pos, end - pos);
    pos = end + 1;
    ++line_no;
    const std::string_view t = trim(raw);
    if (t.empty() || t.front() == '#') continue;
    TokenCursor cursor(split_tokens(t, " \t\r"), source, line_no);
    map.lines.push_back(parse_line(cursor));
  }
  if (map.lines.empty()) throw DataError(source, "no 3D line (empty Line3D++ file)");
  return map;
}

ExternalLineMap read_line3dpp_txt(const std::filesystem::path& path) { return parse_line3dpp_txt(read_file(path), path.string()); }

bool looks_like_line3dpp_txt(const std::string& text) {
  const size_t start = text.find_first_not_of(" \t\r\n");
  if (start == std::string::npos) return false;
  const size_t end = std::min(text.find('\n', start), text.size());
  const auto tokens = split_tokens(std::string_view(text).substr(start, end - start), " \t\r");
  if (tokens.empty()) return false;
  const auto n = parse_int(tokens[0]);
  if (!n || *n < 1 || static_cast<size_t>(*n) * 6 + 2 > tokens.size()) return false;
  const auto m = parse_int(tokens[static_cast<size_t>(*n) * 6 + 1]);
  return m && *m >= 0 && tokens.size() == static_cast<size_t>(*n) * 6 + 2 + static_cast<size_t>(*m) * 6;
}

std::string line3dpp_txt_string(const LineCloud& cloud) {
  // Segment ids per view: the index of each distinct 2D segment in first-seen order.
  std::map<std::tuple<int, double, double, double, double>, long long> segment_id;
  std::map<int, long long> next_id;
  std::string s;
  char buf[160];
  for (size_t k = 0; k < cloud.segments.size(); ++k) {
    const Segment3& l = cloud.segments[k];
    std::snprintf(buf, sizeof buf, "1 %.9g %.9g %.9g %.9g %.9g %.9g", l.a.x(), l.a.y(), l.a.z(), l.b.x(), l.b.y(), l.b.z());
    s += buf;
    const auto& obs = cloud.support.empty() ? std::vector<Observation>{} : cloud.support[k];
    s += " " + std::to_string(obs.size());
    for (const Observation& o : obs) {
      const auto key = std::make_tuple(o.view, o.seg.a.x(), o.seg.a.y(), o.seg.b.x(), o.seg.b.y());
      auto [it, fresh] = segment_id.emplace(key, next_id[o.view]);
      if (fresh) ++next_id[o.view];
      std::snprintf(buf, sizeof buf, " %d %lld %.9g %.9g %.9g %.9g", o.view + 1, it->second, o.seg.a.x(), o.seg.a.y(),
                    o.seg.b.x(), o.seg.b.y());
      s += buf;
    }
    s += "\n";
  }
  return s;
}

void write_line3dpp_txt(const std::filesystem::path& path, const LineCloud& cloud) {
  write_file_atomic(path, line3dpp_txt_string(cloud));
}

}  // namespace lc2wf
