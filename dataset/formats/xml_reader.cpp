#include "dataset/formats/xml_reader.h"

#include <zlib.h>

#include "core/util/input_file.h"
#include "dataset/formats/errors.h"

namespace lc2wf {

struct XmlReader::Source {
  gzFile gz = nullptr;
  ~Source() {
    if (gz) gzclose(gz);
  }
};

namespace {

constexpr size_t kChunk = 256 * 1024;

bool is_space(int c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
bool is_name_char(int c) {
  return c > 0x7f || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == ':' || c == '-' ||
         c == '.';
}

std::string local(const std::string& qualified) {
  const size_t p = qualified.rfind(':');
  return p == std::string::npos ? qualified : qualified.substr(p + 1);
}

void append_utf8(std::string& out, unsigned long cp) {
  if (cp < 0x80) {
    out += static_cast<char>(cp);
  } else if (cp < 0x800) {
    out += static_cast<char>(0xC0 | (cp >> 6));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else if (cp < 0x10000) {
    out += static_cast<char>(0xE0 | (cp >> 12));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (cp >> 18));
    out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  }
}

// Decodes one entity body (between '&' and ';'); false when it is not one we know.
bool decode_entity(std::string_view e, std::string& out) {
  if (e == "lt") out += '<';
  else if (e == "gt") out += '>';
  else if (e == "amp") out += '&';
  else if (e == "quot") out += '"';
  else if (e == "apos") out += '\'';
  else if (e.size() >= 2 && e[0] == '#') {
    unsigned long cp = 0;
    const bool hex = e[1] == 'x' || e[1] == 'X';
    const std::string_view digits = e.substr(hex ? 2 : 1);
    if (digits.empty() || digits.size() > 8) return false;
    for (char c : digits) {
      int d = -1;
      if (c >= '0' && c <= '9') d = c - '0';
      else if (hex && c >= 'a' && c <= 'f') d = c - 'a' + 10;
      else if (hex && c >= 'A' && c <= 'F') d = c - 'A' + 10;
      if (d < 0) return false;
      cp = cp * (hex ? 16 : 10) + d;
    }
    if (cp == 0 || cp > 0x10FFFF) return false;
    append_utf8(out, cp);
  } else {
    return false;
  }
  return true;
}

}  // namespace

const std::string* XmlNode::attribute(std::string_view local_name) const {
  for (const auto& [k, v] : attributes)
    if (k == local_name) return &v;
  return nullptr;
}

XmlReader::XmlReader(const std::filesystem::path& path, XmlLimits limits)
    : src_(std::make_unique<Source>()), source_name_(path.string()), limits_(limits) {
  if (const std::string problem = input_file_problem(path); !problem.empty()) throw DataError(source_name_, problem);
  src_->gz = gzopen(path.c_str(), "rb");  // reads plain files unchanged
  if (!src_->gz) throw DataError(source_name_, "cannot open file");
  gzbuffer(src_->gz, kChunk);
}

XmlReader::XmlReader(std::string text, std::string source_name, XmlLimits limits)
    : src_(std::make_unique<Source>()), source_name_(std::move(source_name)), limits_(limits), buf_(std::move(text)), eof_(true) {}

XmlReader::~XmlReader() = default;

void XmlReader::fail(const std::string& problem) const { throw DataError(source_name_, line_, problem); }

void XmlReader::refill() {
  if (eof_ || !src_->gz) {
    eof_ = true;
    return;
  }
  buf_.resize(kChunk);
  const int n = gzread(src_->gz, buf_.data(), static_cast<unsigned>(kChunk));
  if (n < 0) {
    int err = 0;
    const char* msg = gzerror(src_->gz, &err);
    fail(std::string("cannot decompress: ") + (msg ? msg : "read error"));
  }
  buf_.resize(static_cast<size_t>(n));
  pos_ = 0;
  if (n == 0) eof_ = true;
}

int XmlReader::peek() {
  if (pos_ >= buf_.size()) {
    if (eof_) return -1;
    refill();
    if (pos_ >= buf_.size()) return -1;
  }
  return static_cast<unsigned char>(buf_[pos_]);
}

int XmlReader::get() {
  const int c = peek();
  if (c < 0) return c;
  ++pos_;
  if (++consumed_ > limits_.max_document_bytes) fail("document larger than " + std::to_string(limits_.max_document_bytes) + " bytes");
  if (c == '\n') ++line_;
  return c;
}

void XmlReader::skip_until(std::string_view terminator) {
  size_t matched = 0;
  while (matched < terminator.size()) {
    const int c = get();
    if (c < 0) fail("unexpected end of file (missing '" + std::string(terminator) + "')");
    if (c == terminator[matched]) {
      ++matched;
      continue;
    }
    // Longest prefix of the terminator that ends here ("--->" still ends a comment).
    std::string seen = std::string(terminator.substr(0, matched)) + static_cast<char>(c);
    matched = 0;
    for (size_t k = seen.size(); k > 0 && matched == 0; --k)
      if (terminator.substr(0, k) == std::string_view(seen).substr(seen.size() - k)) matched = k;
  }
}

std::string XmlReader::read_name() {
  std::string n;
  while (is_name_char(peek())) {
    n += static_cast<char>(get());
    if (n.size() > limits_.max_name_bytes) fail("name longer than " + std::to_string(limits_.max_name_bytes) + " bytes");
  }
  if (n.empty()) fail("expected a name");
  return n;
}

std::string XmlReader::decode(std::string_view raw) const {
  std::string out;
  out.reserve(raw.size());
  for (size_t i = 0; i < raw.size(); ++i) {
    if (raw[i] != '&') {
      out += raw[i];
      continue;
    }
    const size_t semi = raw.find(';', i);
    if (semi == std::string_view::npos || semi - i > 12 || !decode_entity(raw.substr(i + 1, semi - i - 1), out))
      fail("unknown or malformed entity reference");
    i = semi;
  }
  return out;
}

const std::string* XmlReader::attribute(std::string_view local_name) const {
  for (const auto& [k, v] : attributes_)
    if (k == local_name) return &v;
  return nullptr;
}

XmlReader::Event XmlReader::next() {
  std::string* no_text = nullptr;
  read_tag(false, no_text);
  if (name_.empty() && !last_was_end_) return Event::kEof;
  return last_was_end_ ? Event::kEnd : Event::kStart;
}

// Reads up to the next start or end tag; character data goes to `text` when keep_text. Sets name_,
// attributes_, last_was_end_ (name_ empty at the end of the document).
void XmlReader::read_tag(bool keep_text, std::string* text) {
  if (pending_end_) {
    pending_end_ = false;
    name_ = local(open_.back());
    open_.pop_back();
    last_was_end_ = true;
    return;
  }
  std::string raw;
  for (;;) {
    int c = get();
    if (c < 0) {
      if (!open_.empty()) fail("unexpected end of file inside <" + open_.back() + ">");
      name_.clear();
      last_was_end_ = false;
      return;
    }
    if (c != '<') {
      if (keep_text) {
        if (c == '&') {
          std::string ent;
          while ((c = get()) >= 0 && c != ';' && ent.size() < 12) ent += static_cast<char>(c);
          if (c != ';' || !decode_entity(ent, *text)) fail("unknown or malformed entity reference");
        } else {
          *text += static_cast<char>(c);
        }
      }
      continue;
    }
    c = peek();
    if (c == '?') {
      skip_until("?>");
      continue;
    }
    if (c == '!') {
      get();
      if (peek() == '-') {
        get();
        if (get() != '-') fail("malformed comment");
        skip_until("-->");
      } else if (peek() == '[') {
        for (char want : std::string_view("[CDATA["))
          if (get() != want) fail("malformed CDATA section");
        size_t matched = 0;
        std::string data;
        while (matched < 3) {
          const int d = get();
          if (d < 0) fail("unexpected end of file in a CDATA section");
          data += static_cast<char>(d);
          matched = d == "]]>"[matched] ? matched + 1 : (d == ']' ? (matched == 2 ? 2 : 1) : 0);
        }
        if (keep_text) *text += data.substr(0, data.size() - 3);
      } else {
        // <!DOCTYPE ...> with an optional [internal subset]: skipped, its entities are not expanded.
        int depth = 0;
        for (;;) {
          const int d = get();
          if (d < 0) fail("unexpected end of file in a declaration");
          if (d == '[') ++depth;
          else if (d == ']') --depth;
          else if (d == '>' && depth <= 0) break;
        }
      }
      continue;
    }
    if (c == '/') {
      get();
      const std::string n = read_name();
      while (is_space(peek())) get();
      if (get() != '>') fail("malformed end tag </" + n + ">");
      if (open_.empty() || open_.back() != n) fail("end tag </" + n + "> does not match " + (open_.empty() ? std::string("any open element") : "<" + open_.back() + ">"));
      open_.pop_back();
      name_ = local(n);
      last_was_end_ = true;
      return;
    }
    const std::string n = read_name();
    attributes_.clear();
    for (;;) {
      while (is_space(peek())) get();
      c = peek();
      if (c == '>') {
        get();
        break;
      }
      if (c == '/') {
        get();
        if (get() != '>') fail("malformed tag <" + n + ">");
        pending_end_ = true;
        break;
      }
      if (c < 0) fail("unexpected end of file in tag <" + n + ">");
      const std::string an = read_name();
      while (is_space(peek())) get();
      if (get() != '=') fail("attribute " + an + " of <" + n + "> has no value");
      while (is_space(peek())) get();
      const int quote = get();
      if (quote != '"' && quote != '\'') fail("attribute " + an + " of <" + n + "> is not quoted");
      raw.clear();
      int d;
      while ((d = get()) >= 0 && d != quote) {
        raw += static_cast<char>(d);
        if (raw.size() > limits_.max_subtree_bytes) fail("attribute value too long");
      }
      if (d < 0) fail("unexpected end of file in an attribute value");
      if (attributes_.size() >= limits_.max_attributes) fail("more than " + std::to_string(limits_.max_attributes) + " attributes");
      attributes_.emplace_back(local(an), decode(raw));
    }
    open_.push_back(n);
    if (static_cast<int>(open_.size()) > limits_.max_depth) fail("elements nested deeper than " + std::to_string(limits_.max_depth));
    name_ = local(n);
    last_was_end_ = false;
    return;
  }
}

XmlNode XmlReader::read_subtree() {
  const std::uint64_t start = consumed_;
  XmlNode root;
  root.name = name_;
  root.attributes = attributes_;
  root.line = line_;
  // Explicit stack of child indices: vectors of children move as they grow, so no pointers are kept.
  std::vector<size_t> path;
  auto current = [&]() -> XmlNode& {
    XmlNode* n = &root;
    for (size_t i : path) n = &n->children[i];
    return *n;
  };
  for (;;) {
    XmlNode& cur = current();
    read_tag(true, &cur.text);
    if (consumed_ - start > limits_.max_subtree_bytes) fail("element <" + root.name + "> is larger than " + std::to_string(limits_.max_subtree_bytes) + " bytes");
    if (name_.empty() && !last_was_end_) fail("unexpected end of file inside <" + root.name + ">");
    if (last_was_end_) {
      if (path.empty()) return root;
      path.pop_back();
      continue;
    }
    XmlNode child;
    child.name = name_;
    child.attributes = attributes_;
    child.line = line_;
    cur.children.push_back(std::move(child));
    path.push_back(cur.children.size() - 1);
  }
}

void XmlReader::skip_subtree() {
  const size_t target = open_.size() - (pending_end_ ? 1 : 0);
  if (pending_end_) {
    read_tag(false, nullptr);
    return;
  }
  while (open_.size() >= target) {
    read_tag(false, nullptr);
    if (name_.empty() && !last_was_end_) fail("unexpected end of file");
  }
}

}  // namespace lc2wf
