#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "nn/safetensors.h"

using ::testing::HasSubstr;

namespace lc2wf {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("lc2wf_nn_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string read_error(const fs::path& path) {
  try {
    read_safetensors(path);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

void write_raw(const fs::path& path, const std::string& header, const std::string& data) {
  std::ofstream out(path, std::ios::binary);
  const uint64_t n = header.size();
  out.write(reinterpret_cast<const char*>(&n), 8);
  out << header << data;
}

TEST(Safetensors, RoundTripsEveryDtypeAndMetadata) {
  const fs::path dir = temp_dir("roundtrip");
  const NamedTensors tensors{
      {"a.f32", Tensor::from_vector(std::vector<float>{1.5f, -2.25f, 3e-8f, 7}, {2, 2})},
      {"b.f64", Tensor::from_vector(std::vector<double>{0.1, 1e300}, {2})},
      {"c.i64", Tensor::from_vector(std::vector<int64_t>{-3, 1LL << 40, 5}, {3, 1})},
      {"d.mask", Tensor::from_mask({1, 0, 0, 1, 1}, {5})},
      {"e.scalar", Tensor::scalar(4.0)},
      {"f.empty", Tensor::zeros({0, 3})}};
  write_safetensors(dir / "t.safetensors", tensors, {{"note", "hello"}, {"n", "3"}});
  const SafetensorsFile f = read_safetensors(dir / "t.safetensors");
  ASSERT_EQ(f.tensors.size(), tensors.size());
  for (const auto& [name, t] : tensors) {
    const Tensor& r = f.tensors.at(name);
    EXPECT_EQ(r.dtype(), t.dtype()) << name;
    EXPECT_EQ(r.shape(), t.shape()) << name;
    EXPECT_EQ(r.to_vector(), t.to_vector()) << name;
  }
  EXPECT_EQ(f.metadata.at("note"), "hello");
  // The header is padded to 8 bytes so the data section is aligned, as the reference writer does.
  std::ifstream in(dir / "t.safetensors", std::ios::binary);
  uint64_t n = 0;
  in.read(reinterpret_cast<char*>(&n), 8);
  EXPECT_EQ(n % 8, 0u);
  for (const auto& entry : fs::directory_iterator(dir))
    EXPECT_EQ(entry.path().filename(), "t.safetensors") << "temporary file left behind";
  fs::remove_all(dir);
}

TEST(Safetensors, ReadsFilesWrittenByThePythonFixtureTool) {
  const SafetensorsFile f =
      read_safetensors(std::string(LC2WF_SOURCE_DIR) + "/tests/data/nn/optimizers.safetensors");
  EXPECT_EQ(f.tensors.at("init.layer.weight").shape(), (Shape{3, 4}));
  EXPECT_EQ(f.tensors.at("init.layer.weight").dtype(), DType::F32);
  EXPECT_THAT(f.metadata.at("settings"), HasSubstr("AdamW"));
}

TEST(Safetensors, MalformedFilesGiveClearErrors) {
  const fs::path dir = temp_dir("bad");
  const fs::path p = dir / "x.safetensors";
  EXPECT_THAT(read_error(dir / "missing.safetensors"), HasSubstr("cannot open"));

  { std::ofstream(p) << "abc"; }
  EXPECT_THAT(read_error(p), HasSubstr("too short"));

  write_raw(p, "{not json", "");
  EXPECT_THAT(read_error(p), HasSubstr("not valid JSON"));

  write_raw(p, R"({"w":{"dtype":"F32","shape":[2],"data_offsets":[0,8]}})", "1234");
  EXPECT_THAT(read_error(p), HasSubstr("tensor 'w'"));
  EXPECT_THAT(read_error(p), HasSubstr("truncated"));

  write_raw(p, R"({"w":{"dtype":"F32","shape":[3],"data_offsets":[0,8]}})", "12345678");
  EXPECT_THAT(read_error(p), HasSubstr("needs 12"));

  write_raw(p, R"({"w":{"dtype":"BF16","shape":[2],"data_offsets":[0,4]}})", "1234");
  EXPECT_THAT(read_error(p), HasSubstr("unsupported dtype"));

  write_raw(p, R"({"a":{"dtype":"F32","shape":[2],"data_offsets":[0,8]},"b":{"dtype":"F32","shape":[1],"data_offsets":[4,8]}})",
            "12345678");
  EXPECT_THAT(read_error(p), HasSubstr("overlap"));

  {  // header length pointing past the end of the file
    std::ofstream out(p, std::ios::binary);
    const uint64_t n = 1000;
    out.write(reinterpret_cast<const char*>(&n), 8);
    out << "{}";
  }
  EXPECT_THAT(read_error(p), HasSubstr("exceeds the file size"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace lc2wf
