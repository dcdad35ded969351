// A small pull parser for the XML of CityGML files (plain or gzip-compressed, read in chunks through
// zlib), bounded in depth, name and subtree size, with an element tree for one subtree at a time so a
// file of thousands of buildings never sits in memory at once. Namespaces are dropped: names are local
// (`bldg:Building` -> `Building`). No DTDs or external entities (a DOCTYPE is skipped); the five
// predefined entities and character references are decoded. Errors are DataError("<file>:<line>: ...").
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace lc2wf {

struct XmlNode {
  std::string name;  // local name
  std::vector<std::pair<std::string, std::string>> attributes;  // local names, decoded values
  std::string text;  // character data directly inside this element
  std::vector<XmlNode> children;
  int line = 0;
  // Value of the attribute with this local name, or nullptr.
  const std::string* attribute(std::string_view local_name) const;
};

struct XmlLimits {
  int max_depth = 512;
  size_t max_name_bytes = 4096;
  size_t max_attributes = 1024;
  size_t max_subtree_bytes = size_t{1} << 30;            // one building's element tree
  std::uint64_t max_document_bytes = std::uint64_t{64} << 30;  // after decompression (a gzip bomb stops here)
};

class XmlReader {
 public:
  enum class Event { kStart, kEnd, kEof };

  explicit XmlReader(const std::filesystem::path& path, XmlLimits limits = {});
  XmlReader(std::string text, std::string source_name, XmlLimits limits = {});
  ~XmlReader();
  XmlReader(const XmlReader&) = delete;
  XmlReader& operator=(const XmlReader&) = delete;

  // The next start or end tag (a self-closing element gives both); character data between tags is skipped.
  Event next();
  const std::string& name() const { return name_; }  // local name of the tag just read
  const std::vector<std::pair<std::string, std::string>>& attributes() const { return attributes_; }
  const std::string* attribute(std::string_view local_name) const;
  int depth() const { return static_cast<int>(open_.size()); }  // open elements after the tag just read
  int line() const { return line_; }

  // After a kStart: that element and everything inside it, read up to and including its end tag.
  XmlNode read_subtree();
  // After a kStart: skips to the element's end tag.
  void skip_subtree();

  [[noreturn]] void fail(const std::string& problem) const;

 private:
  int get();
  int peek();
  void refill();
  void read_tag(bool keep_text, std::string* text);
  void skip_until(std::string_view terminator);
  std::string read_name();
  std::string decode(std::string_view raw) const;

  struct Source;
  std::unique_ptr<Source> src_;
  std::string source_name_;
  XmlLimits limits_;
  std::string buf_;
  size_t pos_ = 0;
  bool eof_ = false;
  std::uint64_t consumed_ = 0;
  int line_ = 1;
  std::string name_;
  std::vector<std::pair<std::string, std::string>> attributes_;
  std::vector<std::string> open_;
  bool pending_end_ = false;  // a self-closing tag's end event is due
  bool last_was_end_ = false;
};

}  // namespace lc2wf
