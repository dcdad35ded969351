// The command-line contract of every lc2wf command (README.md, "Commands"), checked by
// running each binary: --help and --version, -o/--out, -j/--threads, -q/--quiet, the exit codes, errors on
// stderr naming what the user wrote, the environment variables listed in --help, and nothing written
// when the arguments or inputs are bad. The list of binaries comes from CMake (lc2wf_add_command), so a new
// command is covered, or fails here until its expectations are added to kExpectations.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/util/version.h"
#include "tests/common/run_cli.h"

namespace lc2wf {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::Not;
using testing::CliResult;
using testing::run_argv;

struct Expectation {
  bool threads = true;                // has -j/--threads
  std::vector<std::string> env;       // environment variables its --help must list
  // Arguments that name a missing input (MISSING) and an output (OUT): exit 3, OUT never created.
  std::vector<std::string> missing_input;
};

const std::string kMissing = "MISSING", kOut = "OUT";

const std::map<std::string, Expectation> kExpectations = {
    {"lc2wf-dataset", {true, {"OMP_NUM_THREADS", "LC2WF_BLENDER_SCRIPT"}, {"--meshes", kMissing, "-o", kOut}}},
    {"lc2wf-colmap-poses", {true, {}, {kMissing, "--intrinsics", "500,500,319.5,239.5", "-o", kOut}}},
    {"lc2wf-make-splits", {true, {}, {"--meshes", kMissing, "-o", kOut}}},
    {"lc2wf-make-buildings", {false, {}, {"--augment", kMissing, "-o", kOut}}},
    {"lc2wf-cloud-convert", {false, {}, {kMissing, "-o", kOut}}},
    {"lc2wf-list-buildings", {true, {}, {kMissing, "-o", kOut}}},
    {"lc2wf-cloud-styles", {false, {}, {"--data", kMissing, "--split", kMissing, "-o", kOut}}},
    {"lc2wf-synthetic-data", {false, {}, {"--count", "3", "--val", "1", "--test", "1", "-o", kOut}}},
    {"lc2wf-fit-height", {true, {}, {kMissing, "-o", kOut}}},
    {"lc2wf-train", {true, {"LC2WF_STORAGE_CACHE_MB", "LC2WF_GEMM"}, {kMissing, "-o", kOut}}},
    {"lc2wf-infer", {true, {"OMP_NUM_THREADS", "LC2WF_STORAGE_CACHE_MB", "LC2WF_GEMM"}, {"--weights", kMissing, kMissing, "-o", kOut}}},
    {"lc2wf-eval",
     {true, {"OMP_NUM_THREADS", "LC2WF_STORAGE_CACHE_MB", "LC2WF_GEMM", "LC2WF_THREE_JS_DIR"}, {"--pred", kMissing, "--gt", kMissing, "-o", kOut}}},
    {"lc2wf-reconstruct",
     {true, {"OMP_NUM_THREADS", "LC2WF_STORAGE_CACHE_MB", "LC2WF_GEMM"}, {kMissing, "--weights", kMissing, "-o", kOut}}},
};

// "name=path|name=path" from CMake: every binary added with lc2wf_add_command.
std::map<std::string, std::string> commands() {
  std::map<std::string, std::string> out;
  std::stringstream ss(LC2WF_COMMANDS);
  for (std::string entry; std::getline(ss, entry, '|');) {
    const size_t eq = entry.find('=');
    if (eq != std::string::npos) out[entry.substr(0, eq)] = entry.substr(eq + 1);
  }
  return out;
}

class CliContract : public ::testing::TestWithParam<std::string> {
 protected:
  std::string name() const { return GetParam(); }
  std::string path() const { return commands().at(GetParam()); }
  const Expectation& expected() const { return kExpectations.at(GetParam()); }
};

TEST(CliContractList, EveryCommandHasExpectations) {
  ASSERT_FALSE(commands().empty());
  for (const auto& [name, path] : commands()) EXPECT_TRUE(kExpectations.count(name)) << name << " has no entry in kExpectations";
}

// Every environment variable the sources read is listed by some command's --help.
TEST(CliContractList, EveryEnvironmentVariableIsDocumented) {
  std::set<std::string> documented = {"PATH"};
  for (const auto& [name, e] : kExpectations) documented.insert(e.env.begin(), e.env.end());
  const std::regex getenv_call("getenv\\(\"([A-Z_0-9]+)\"\\)");
  for (const char* module : {"core", "nn", "dataset", "tools", "infer", "reconstruct", "train"}) {
    for (const auto& f : fs::recursive_directory_iterator(fs::path(LC2WF_SOURCE_DIR) / module)) {
      if (f.path().extension() != ".cpp" && f.path().extension() != ".h") continue;
      std::ifstream in(f.path());
      const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      for (std::sregex_iterator m(text.begin(), text.end(), getenv_call), end; m != end; ++m)
        EXPECT_TRUE(documented.count((*m)[1])) << f.path() << " reads " << (*m)[1] << ", which no --help lists";
    }
  }
}

TEST_P(CliContract, HelpListsTheCommonOptionsExitCodesAndEnvironment) {
  const CliResult r = run_argv({path(), "--help"});
  EXPECT_EQ(r.code, 0);
  EXPECT_THAT(r.err, IsEmpty());
  EXPECT_THAT(r.out, HasSubstr("Usage: " + name()));
  for (const char* option : {"-h, --help", "--version", "-o, --out", "-q, --quiet"}) EXPECT_THAT(r.out, HasSubstr(option));
  if (expected().threads) EXPECT_THAT(r.out, HasSubstr("-j, --threads"));
  EXPECT_THAT(r.out, HasSubstr("Exit codes: 0 done, 1 partly failed"));
  EXPECT_THAT(r.out, HasSubstr("2 bad command line, 3 data or I/O error"));
  for (const std::string& var : expected().env) EXPECT_THAT(r.out, HasSubstr(var));
}

TEST_P(CliContract, VersionNamesTheReleaseAndTheCommit) {
  const CliResult r = run_argv({path(), "--version"});
  EXPECT_EQ(r.code, 0);
  EXPECT_EQ(r.out, name() + " " + lc2wf_version() + " (commit " + lc2wf_git_commit() + ")\n");
}

TEST_P(CliContract, UnknownOptionIsAUsageErrorNamingIt) {
  const CliResult r = run_argv({path(), "--frobnicate"});
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.out, IsEmpty());
  EXPECT_THAT(r.err, HasSubstr("--frobnicate"));
  EXPECT_THAT(r.err, HasSubstr(name() + " --help"));
}

TEST_P(CliContract, MissingInputIsADataErrorAndWritesNothing) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("lc2wf_contract_" + name() + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "file") << "a regular file\n";
  // An input that does not exist, or (commands without inputs) an output below a regular file.
  const fs::path missing = dir / "no such input", out = name() == "lc2wf-synthetic-data" ? dir / "file" / "out" : dir / "out";
  std::vector<std::string> argv = {path()};
  for (const std::string& a : expected().missing_input) argv.push_back(a == kMissing ? missing.string() : a == kOut ? out.string() : a);
  argv.push_back("-q");
  if (expected().threads) argv.insert(argv.end(), {"-j", "1"});
  const CliResult r = run_argv(argv);
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_THAT(r.out, IsEmpty());
  EXPECT_THAT(r.err, HasSubstr(name() == "lc2wf-synthetic-data" ? out.parent_path().string() : missing.string()));
  EXPECT_FALSE(fs::exists(out)) << out << " was written before the inputs were checked";
  fs::remove_all(dir);
}

// --help says what a flag does, never what it scored: no metric with a number ("sAP +0.9", "vAP 93.1"), no
// signed gain, no percentage and no measured speed-up or time (those belong in the READMEs, with their setting).
TEST_P(CliContract, HelpStatesNoMeasuredScore) {
  const CliResult r = run_argv({path(), "--help"});
  ASSERT_EQ(r.code, 0);
  const std::vector<std::pair<std::string, std::regex>> rules = {
      {"a metric with a number", std::regex(R"(\b(vAP|sAP|mAP|AP|WED|nWED|vRecall|sRecall|recall|precision|accuracy|ACO|CF1|EF1|F1)\s*[:=]?\s*[+-]?[0-9])",
                                            std::regex::icase)},
      {"a signed gain", std::regex(R"((^|[\s(])[+][0-9])")},
      {"a percentage", std::regex(R"([0-9]\s?%)")},
      {"a measured speed", std::regex(R"([0-9.]+\s?x\s+(faster|slower)|[0-9.]+\s?m?s per (building|cloud|image|step))")},
  };
  std::istringstream lines(r.out);
  for (std::string line; std::getline(lines, line);)
    for (const auto& [what, rule] : rules) EXPECT_FALSE(std::regex_search(line, rule)) << name() << " --help states " << what << ": " << line;
}

// -j takes a whole count; a command that runs on one thread refuses -j rather than ignoring it.
TEST_P(CliContract, ThreadsFlagIsACountOrRefused) {
  const CliResult r = run_argv({path(), "-j", "2x"});
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.err, HasSubstr("-j"));
  EXPECT_THAT(r.err, HasSubstr(expected().threads ? "needs a non-negative integer, got '2x'" : "unknown option '-j'"));
}

std::vector<std::string> command_names() {
  std::vector<std::string> names;
  for (const auto& [name, path] : commands()) names.push_back(name);
  return names;
}

INSTANTIATE_TEST_SUITE_P(AllCommands, CliContract, ::testing::ValuesIn(command_names()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string n = info.param;
                           for (char& c : n)
                             if (c == '-') c = '_';
                           return n;
                         });

}  // namespace
}  // namespace lc2wf
