// The safetensors format, so Python users can open our weights with the `safetensors` package:
// 8-byte little-endian header length, a JSON header {name: {dtype, shape, data_offsets}, "__metadata__":
// {string: string}} padded with spaces to 8 bytes, then the raw little-endian tensor bytes.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <string_view>

#include "core/tensor.h"
#include "nn/module.h"

namespace lc2wf {

struct SafetensorsFile {
  std::map<std::string, Tensor> tensors;
  std::map<std::string, std::string> metadata;
};

// Writes atomically (temp file + rename). Supports F32, F64, I64 and Bool tensors.
void write_safetensors(const std::filesystem::path& path, const NamedTensors& tensors,
                       const std::map<std::string, std::string>& metadata = {});

// Throws std::runtime_error naming the file and the problem for any malformed or truncated file.
SafetensorsFile read_safetensors(const std::filesystem::path& path);
// The same from the file's bytes; `where` names the source in errors (tests, fuzzing).
SafetensorsFile parse_safetensors(std::string_view bytes, const std::string& where);

}  // namespace lc2wf
