// Regressions for hostile input files: FIFOs, devices and directories are refused before opening (a FIFO
// blocked forever, /dev/zero was read until allocation failed), long names still write atomically, and
// mesh coordinates beyond the stated limit are rejected with the file and line.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>

#include <fstream>
#include <string>

#include "dataset/formats/read_file.h"
#include "dataset/formats/errors.h"
#include "dataset/formats/line_cloud_io.h"
#include "dataset/formats/mesh_io.h"
#include "test_util.h"

using ::testing::HasSubstr;

namespace lc2wf {
namespace {

namespace fs = std::filesystem;

template <class Read>
void expect_refused(const fs::path& path, Read read, const std::string& needle) {
  try {
    read(path);
    FAIL() << path << " was read";
  } catch (const DataError& e) {
    EXPECT_THAT(std::string(e.what()), HasSubstr(path.string())) << e.what();
    EXPECT_THAT(std::string(e.what()), HasSubstr(needle)) << e.what();
  }
}

TEST(InputFiles, FifoDeviceAndDirectoryAreRefusedWithoutBlocking) {
  const fs::path dir = test::scratch_dir("input_files");
  const fs::path fifo = dir / "cloud.lcloud";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const auto read_bytes = [](const fs::path& p) { return read_file(p); };
  const auto read_cloud = [](const fs::path& p) { return read_line_cloud(p); };
  const auto read_mesh = [](const fs::path& p) { return read_polyshape(p); };
  const auto read_wire = [](const fs::path& p) { return read_obj(p); };
  for (const fs::path& p : {fifo, fs::path("/dev/zero")}) {
    expect_refused(p, read_bytes, "not a regular file");
    expect_refused(p, read_cloud, "not a regular file");
    expect_refused(p, read_mesh, "not a regular file");
    expect_refused(p, read_wire, "not a regular file");
  }
  expect_refused(dir, read_bytes, "is a directory");
  expect_refused(dir, read_mesh, "is a directory");
  EXPECT_EQ(input_file_problem(dir / "missing"), "");  // left to the open, which names it and says why
  expect_refused(dir / "missing", read_bytes, "cannot open file: No such file or directory");
  expect_refused(dir / "missing", read_mesh, "cannot open file: No such file or directory");
  EXPECT_THAT(input_file_problem(fifo, 1), HasSubstr("not a regular file"));
  fs::remove_all(dir);
}

TEST(InputFiles, SizeLimitIsChecked) {
  const fs::path dir = test::scratch_dir("input_size");
  write_file_atomic(dir / "f.txt", std::string(100, 'x'));
  EXPECT_EQ(input_file_problem(dir / "f.txt", 100), "");
  EXPECT_THAT(input_file_problem(dir / "f.txt", 99), HasSubstr("more than the 99-byte limit"));
  EXPECT_THROW(read_input_file(dir / "f.txt", 99), std::runtime_error);
  fs::remove_all(dir);
}

// Regression: the temporary name (target + ".tmp.PID.N") went over the 255-byte NAME_MAX for targets of
// 240+ bytes, so lc2wf-dataset could not write a status for such a mesh.
TEST(InputFiles, AtomicWriteOfAMaximalFileName) {
  const fs::path dir = test::scratch_dir("long_name");
  const std::string name = std::string(250, 'n') + ".json";
  ASSERT_EQ(name.size(), 255u);
  write_file_atomic(dir / name, "{}");
  EXPECT_EQ(read_file(dir / name), "{}");
  int entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++entries;
  EXPECT_EQ(entries, 1) << "temporary file left behind";
  fs::remove_all(dir);
}

// An output path that is a FIFO or a folder is refused and left as it was: the rename of the temporary
// replaced it (as root, `lc2wf-cloud-convert -o /dev/null` turned the device into a regular file).
TEST(InputFiles, AtomicWriteNeverReplacesAFifoOrAFolder) {
  const fs::path dir = test::scratch_dir("atomic_special");
  const fs::path fifo = dir / "out.txt", folder = dir / "out";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  fs::create_directories(folder);
  for (const fs::path& target : {fifo, folder}) {
    try {
      write_file_atomic(target, "data");
      ADD_FAILURE() << target << " was replaced";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(target.string()), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("not replaced"), std::string::npos) << e.what();
    }
  }
  EXPECT_TRUE(fs::is_fifo(fifo));
  EXPECT_TRUE(fs::is_directory(folder));
  int entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++entries;
  EXPECT_EQ(entries, 2) << "temporary file left behind";
  fs::remove_all(dir);
}

// A full disk (here a file-size limit, EFBIG like ENOSPC) fails the write, keeps the previous file intact
// and leaves no temporary behind: the promise behind every "no partial file after a crash" in RELIABILITY.md.
TEST(InputFiles, AtomicWriteOnAFullDiskKeepsThePreviousFile) {
  const fs::path dir = test::scratch_dir("full_disk");
  write_file_atomic(dir / "status.json", "old");
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{4096, 4096};
    ::setrlimit(RLIMIT_FSIZE, &limit);
    try {
      write_file_atomic(dir / "status.json", std::string(1 << 20, 'x'));
    } catch (const std::runtime_error& e) {
      ::_exit(std::string(e.what()).find("status.json") != std::string::npos ? 0 : 2);
    }
    ::_exit(1);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << "the write did not fail with an error naming the file";
  EXPECT_EQ(read_file(dir / "status.json"), "old");
  int entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++entries;
  EXPECT_EQ(entries, 1) << "temporary file left behind";
  fs::remove_all(dir);
}

// Regression: 1e155 coordinates overflowed squared distances and projections (a segfault in the renderer).
TEST(InputFiles, CoordinatesBeyondTheLimitNameFileAndLine) {
  const fs::path dir = test::scratch_dir("far_coordinates");
  std::ofstream(dir / "far.obj") << "v 0 0 0\nv 1e155 0 0\nl 1 2\n";
  std::ofstream(dir / "far.polyshape") << "# Number of verts: 3\n# Number of faces: 1\n0,0,0\n1,0,0\n0,-2e9,0\n1,2,3,1\n";
  expect_refused(dir / "far.obj", [](const fs::path& p) { return read_obj(p); }, "far.obj:2: vertex coordinate beyond +-1e9");
  expect_refused(dir / "far.polyshape", [](const fs::path& p) { return read_polyshape(p); }, "far.polyshape:5: vertex coordinate beyond");
  fs::remove_all(dir);
}

// Building names come from file names, which need not be UTF-8: writing the cloud's JSON header threw.
TEST(InputFiles, ACloudNamedInNonUtf8BytesIsWrittenAndReadBack) {
  const fs::path dir = test::scratch_dir("non_utf8_name");
  LineCloud cloud;
  cloud.name = "caf\xff\xfe";
  cloud.segments.push_back({Vec3(0, 0, 0), Vec3(1, 0, 0)});
  for (const bool binary : {true, false}) {
    LineCloudWriteOptions o;
    o.binary = binary;
    ASSERT_NO_THROW(write_line_cloud(dir / (cloud.name + ".lcloud"), cloud, o));
    const LineCloud back = read_line_cloud(dir / (cloud.name + ".lcloud"));
    EXPECT_EQ(back.name, "caf\xef\xbf\xbd\xef\xbf\xbd");  // U+FFFD twice
    EXPECT_EQ(back.segments.size(), 1u);
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace lc2wf
