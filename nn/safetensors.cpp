#include "nn/safetensors.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/util/atomic_file.h"
#include "core/util/input_file.h"

namespace lc2wf {

static_assert(std::endian::native == std::endian::little, "safetensors I/O assumes a little-endian host");

namespace {
constexpr uint64_t kMaxHeaderBytes = 100u << 20;

const char* st_dtype(DType d) {
  switch (d) {
    case DType::F32: return "F32";
    case DType::F64: return "F64";
    case DType::I64: return "I64";
    case DType::Bool: return "BOOL";
  }
  return "?";
}

bool parse_dtype(const std::string& s, DType& out) {
  if (s == "F32") out = DType::F32;
  else if (s == "F64") out = DType::F64;
  else if (s == "I64") out = DType::I64;
  else if (s == "BOOL") out = DType::Bool;
  else return false;
  return true;
}

std::vector<char> tensor_bytes(const Tensor& t) {
  std::vector<char> bytes(static_cast<size_t>(t.numel()) * dtype_size(t.dtype()));
  if (bytes.empty()) return bytes;
  switch (t.dtype()) {
    case DType::F32: std::memcpy(bytes.data(), t.data<float>(), bytes.size()); break;
    case DType::F64: std::memcpy(bytes.data(), t.data<double>(), bytes.size()); break;
    case DType::I64: std::memcpy(bytes.data(), t.data<int64_t>(), bytes.size()); break;
    case DType::Bool: {
      const std::vector<double> v = t.to_vector();
      for (size_t i = 0; i < v.size(); ++i) bytes[i] = v[i] != 0.0 ? 1 : 0;
      break;
    }
  }
  return bytes;
}

Tensor tensor_from_bytes(const char* src, DType dtype, const Shape& shape) {
  const int64_t n = shape_numel(shape);
  if (dtype == DType::Bool) {
    std::vector<uint8_t> v(static_cast<size_t>(n));
    for (int64_t i = 0; i < n; ++i) v[i] = src[i] != 0;
    return Tensor::from_mask(v, shape);
  }
  Tensor t = Tensor::empty(shape, dtype);
  const size_t bytes = static_cast<size_t>(n) * dtype_size(dtype);
  if (bytes == 0) return t;
  if (dtype == DType::F32) std::memcpy(t.data<float>(), src, bytes);
  else if (dtype == DType::F64) std::memcpy(t.data<double>(), src, bytes);
  else std::memcpy(t.data<int64_t>(), src, bytes);
  return t;
}
}  // namespace

void write_safetensors(const std::filesystem::path& path, const NamedTensors& tensors,
                       const std::map<std::string, std::string>& metadata) {
  nlohmann::json header = nlohmann::json::object();
  std::vector<std::vector<char>> blobs;
  uint64_t offset = 0;
  for (const auto& [name, t] : tensors) {
    if (name == "__metadata__" || name.empty())
      throw std::invalid_argument(path.string() + ": invalid tensor name '" + name + "'");
    if (header.contains(name)) throw std::invalid_argument(path.string() + ": duplicate tensor name '" + name + "'");
    blobs.push_back(tensor_bytes(t));
    header[name] = {{"dtype", st_dtype(t.dtype())}, {"shape", t.shape()}, {"data_offsets", {offset, offset + blobs.back().size()}}};
    offset += blobs.back().size();
  }
  if (!metadata.empty()) header["__metadata__"] = metadata;
  std::string text = header.dump();
  text.append((8 - text.size() % 8) % 8, ' ');
  write_file_atomically(path, [&](std::ostream& out) {
    const uint64_t n = text.size();
    out.write(reinterpret_cast<const char*>(&n), sizeof n);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    for (const auto& blob : blobs) out.write(blob.data(), static_cast<std::streamsize>(blob.size()));
  });
}

SafetensorsFile read_safetensors(const std::filesystem::path& path) {
  const std::string where = path.string();
  if (const std::string problem = input_file_problem(path); !problem.empty()) throw std::runtime_error(where + ": " + problem);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(where + ": cannot open for reading");
  const std::string file((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return parse_safetensors(file, where);
}

SafetensorsFile parse_safetensors(std::string_view file, const std::string& where) {
  if (file.size() < 8) throw std::runtime_error(where + ": too short for a safetensors file (" + std::to_string(file.size()) + " bytes)");
  uint64_t header_len = 0;
  std::memcpy(&header_len, file.data(), 8);
  if (header_len > kMaxHeaderBytes || header_len > file.size() - 8)
    throw std::runtime_error(where + ": header length " + std::to_string(header_len) + " exceeds the file size " +
                             std::to_string(file.size()) + " (truncated or not a safetensors file)");
  nlohmann::json header;
  try {
    header = nlohmann::json::parse(file.begin() + 8, file.begin() + 8 + static_cast<std::ptrdiff_t>(header_len));
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(where + ": header is not valid JSON: " + e.what());
  }
  if (!header.is_object()) throw std::runtime_error(where + ": header is not a JSON object");
  const char* buffer = file.data() + 8 + header_len;
  const uint64_t buffer_size = file.size() - 8 - header_len;

  SafetensorsFile out;
  std::vector<std::pair<uint64_t, uint64_t>> ranges;
  for (auto it = header.begin(); it != header.end(); ++it) {
    const std::string& name = it.key();
    const nlohmann::json& entry = it.value();
    if (name == "__metadata__") {
      if (!entry.is_object()) throw std::runtime_error(where + ": __metadata__ is not an object");
      for (auto m = entry.begin(); m != entry.end(); ++m) {
        if (!m.value().is_string()) throw std::runtime_error(where + ": metadata '" + m.key() + "' is not a string");
        out.metadata[m.key()] = m.value().get<std::string>();
      }
      continue;
    }
    const std::string what = where + ": tensor '" + name + "'";
    if (!entry.is_object() || !entry.contains("dtype") || !entry.contains("shape") || !entry.contains("data_offsets"))
      throw std::runtime_error(what + " needs dtype, shape and data_offsets");
    DType dtype;
    if (!entry["dtype"].is_string() || !parse_dtype(entry["dtype"].get<std::string>(), dtype))
      throw std::runtime_error(what + " has an unsupported dtype " + entry["dtype"].dump());
    const nlohmann::json& js = entry["shape"];
    if (!js.is_array()) throw std::runtime_error(what + " has a non-array shape");
    Shape shape;
    // Dimensions are bounded by the data section, so numel * dtype size cannot wrap (or go negative).
    uint64_t numel = 1;
    for (const auto& d : js) {
      if (!d.is_number_unsigned() || d.get<uint64_t>() > buffer_size) throw std::runtime_error(what + " has an invalid shape " + js.dump());
      const uint64_t n = d.get<uint64_t>();
      numel = n == 0 || numel == 0 ? 0 : (numel > buffer_size / n ? buffer_size + 1 : numel * n);
      shape.push_back(static_cast<int64_t>(n));
    }
    if (numel > buffer_size) throw std::runtime_error(what + " has a shape " + js.dump() + " larger than the data section");
    const nlohmann::json& jo = entry["data_offsets"];
    if (!jo.is_array() || jo.size() != 2 || !jo[0].is_number_unsigned() || !jo[1].is_number_unsigned())
      throw std::runtime_error(what + " has invalid data_offsets " + jo.dump());
    const uint64_t begin = jo[0].get<uint64_t>(), end = jo[1].get<uint64_t>();
    if (begin > end || end > buffer_size)
      throw std::runtime_error(what + " has data_offsets [" + std::to_string(begin) + ", " + std::to_string(end) +
                               "] outside the " + std::to_string(buffer_size) + "-byte data section (truncated file?)");
    const uint64_t expected = static_cast<uint64_t>(shape_numel(shape)) * dtype_size(dtype);
    if (end - begin != expected)
      throw std::runtime_error(what + " spans " + std::to_string(end - begin) + " bytes but " + dtype_name(dtype) +
                               " " + shape_str(shape) + " needs " + std::to_string(expected));
    ranges.emplace_back(begin, end);
    out.tensors[name] = tensor_from_bytes(buffer + begin, dtype, shape);
  }
  std::sort(ranges.begin(), ranges.end());
  for (size_t i = 1; i < ranges.size(); ++i)
    if (ranges[i].first < ranges[i - 1].second) throw std::runtime_error(where + ": tensor data ranges overlap");
  return out;
}

}  // namespace lc2wf
