// Data-parallel lc2wf-train under mpirun on localhost (2 ranks, --oversubscribe), on a tiny config with
// both stages: the loss curve matches one process with the same global batch, the replicas are equal
// after every step, the same number of ranks gives the same bits, a killed rank ends the job with a
// message from the survivor and the run resumes with one process, and a rank that stops answering ends
// the job after --comm-timeout instead of hanging it.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/common/run_cli.h"
#include "tests/common/tiny_lpt.h"
#include "tests/train/train_log.h"

namespace lc2wf {
namespace {

namespace fs = std::filesystem;
using testing::log_lines;
using testing::step_losses;
using Clock = std::chrono::steady_clock;

// Summation order is the only difference from one process (synchronised BatchNorm in the junction
// stage, per-rank BatchNorm on passes of one building in the edge stage: the same statistics as one
// process's micro-batches), so the step losses agree to this relative tolerance over the whole run
// (measured: at most 3e-7 over 20 steps; per-rank statistics where they differ from one process's: 1e-2).
constexpr double kLossTolerance = 1e-5;

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A started command: its pid, and its output in a file.
struct Started {
  pid_t pid = -1;
  fs::path output;
};

Started start(const std::vector<std::string>& args, const fs::path& output) {
  Started s{fork(), output};
  if (s.pid == 0) {
    const int fd = ::open(output.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, STDOUT_FILENO);
    dup2(fd, STDERR_FILENO);
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execvp(argv[0], argv.data());
    _exit(127);
  }
  return s;
}

// Exit code (-1: killed by a signal), or nothing when it did not end within `limit`.
std::optional<int> wait_for(pid_t pid, std::chrono::seconds limit) {
  const auto end = Clock::now() + limit;
  while (Clock::now() < end) {
    int status = 0;
    if (waitpid(pid, &status, WNOHANG) == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return std::nullopt;
}

// The process of MPI rank `rank` started by mpirun `launcher` (Open MPI runs local ranks as its children).
pid_t rank_pid(pid_t launcher, int rank) {
  const std::string wanted = "OMPI_COMM_WORLD_RANK=" + std::to_string(rank);
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string name = entry.path().filename();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::istringstream stat(read_text(entry.path() / "stat"));
    std::string pid, comm, state;
    pid_t parent = 0;
    stat >> pid >> comm >> state >> parent;
    if (parent != launcher) continue;
    const std::string env = read_text(entry.path() / "environ");
    std::istringstream vars(env);
    for (std::string var; std::getline(vars, var, '\0');)
      if (var == wanted) return static_cast<pid_t>(std::stol(name));
  }
  return -1;
}

// A process that exists and is not a zombie.
bool alive(pid_t pid) {
  const std::string stat = read_text(fs::path("/proc") / std::to_string(pid) / "stat");
  const size_t paren = stat.rfind(')');
  return paren != std::string::npos && paren + 2 < stat.size() && stat[paren + 2] != 'Z';
}

size_t steps_logged(const fs::path& log, const std::string& stage) {
  if (!fs::exists(log)) return 0;
  size_t n = 0;
  std::ifstream in(log);
  for (std::string line; std::getline(in, line);) {
    const nlohmann::json j = nlohmann::json::parse(line, nullptr, false);
    if (!j.is_discarded() && j.value("type", "") == "step" && j.value("stage", "") == stage) ++n;
  }
  return n;
}

using StepLosses = std::vector<std::tuple<std::string, int64_t, double>>;

StepLosses stage_steps(const StepLosses& losses, const std::string& stage) {
  StepLosses out;
  for (const auto& l : losses)
    if (std::get<0>(l) == stage) out.push_back(l);
  return out;
}

class TrainMpi : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // CI runs as root, which mpirun refuses unless told.
    setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
    setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
    dir_ = fs::temp_directory_path() / ("lc2wf_train_mpi_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    // 9 training buildings: junction batches of 4 (drop_last), edge batches of 4, 4 and 1 (a rank
    // without buildings in the last one).
    const auto r = testing::run_cli(std::string(LC2WF_SYNTHETIC_DATA_BIN) + " --quiet --count 12 --val 2 --test 1 --seed 3 --out " +
                                    (dir_ / "data").string());
    ASSERT_EQ(r.code, 0) << r.err;
    const testing::TinyLpt tiny = testing::tiny_lpt();
    const nlohmann::json &junction_lpt = tiny.junction, &edge_lpt = tiny.edge;
    const nlohmann::json config = {
        {"seed", 11},
        {"threads", 1},
        {"data", {{"format", "lc2wf"}, {"dir", (dir_ / "data" / "clouds").string()},
                  {"train_split", (dir_ / "data" / "train.txt").string()}, {"val_split", (dir_ / "data" / "val.txt").string()}}},
        {"junction", {{"net", {{"lpt", junction_lpt}, {"head", {{"dims", {16}}}}}},
                      {"optim", {{"lr", 3e-3}, {"milestones", {100}}}},
                      {"epochs", 4}, {"batch_size", 4}, {"val_every", 2}, {"checkpoint_every_steps", 1},
                      {"batch_norm", "sync"}}},
        {"edge", {{"net", {{"lpt", edge_lpt}, {"head", {{"dims", {16}}}}}},
                  {"optim", {{"lr", 3e-3}, {"milestones", {100}}}}, {"max_static_pairs", 16}, {"top_k", 12},
                  {"epochs", 3}, {"batch_size", 4}, {"micro_batch", 1}, {"val_every", 3}, {"checkpoint_every_steps", 1},
                  {"batch_norm", "per_rank"}}}};
    std::ofstream(dir_ / "tiny.json") << config.dump(2);
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  static std::vector<std::string> train_args(const fs::path& out, int ranks, std::vector<std::string> extra = {}) {
    std::vector<std::string> args;
    if (ranks > 0) args = {LC2WF_MPIEXEC, "--oversubscribe", "--bind-to", "none", "-np", std::to_string(ranks)};
    for (const std::string& a : {std::string(LC2WF_TRAIN_BIN), (dir_ / "tiny.json").string(), std::string("--quiet"),
                                 std::string("--out"), out.string()})
      args.push_back(a);
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  }
  // Runs to the end (ranks 0: plain lc2wf-train, one process); returns the exit code, output kept.
  static int train(const fs::path& out, int ranks, std::vector<std::string> extra = {}) {
    const Started s = start(train_args(out, ranks, std::move(extra)), dir_ / (out.filename().string() + ".out"));
    const std::optional<int> code = wait_for(s.pid, std::chrono::seconds(300));
    if (!code) {
      kill(s.pid, SIGKILL);
      waitpid(s.pid, nullptr, 0);
    }
    return code.value_or(-2);
  }
  static std::string output_of(const fs::path& out) { return read_text(dir_ / (out.filename().string() + ".out")); }

  // The uninterrupted 2-rank run, made once for the tests that compare against it.
  static const fs::path& two_ranks() {
    static const fs::path out = [] {
      const fs::path p = dir_ / "two_ranks";
      EXPECT_EQ(train(p, 2), 0) << output_of(p);
      return p;
    }();
    return out;
  }

  static void expect_close(const std::vector<std::tuple<std::string, int64_t, double>>& got,
                           const std::vector<std::tuple<std::string, int64_t, double>>& want) {
    ASSERT_EQ(got.size(), want.size());
    for (size_t k = 0; k < got.size(); ++k) {
      EXPECT_EQ(std::get<0>(got[k]), std::get<0>(want[k]));
      EXPECT_EQ(std::get<1>(got[k]), std::get<1>(want[k]));
      const double a = std::get<2>(got[k]), b = std::get<2>(want[k]);
      EXPECT_LE(std::abs(a - b), kLossTolerance * std::abs(b)) << std::get<0>(want[k]) << " step " << std::get<1>(want[k]);
    }
  }

  static fs::path dir_;
};
fs::path TrainMpi::dir_;

TEST_F(TrainMpi, TwoRanksMatchOneProcessKeepEqualReplicasAndRepeatBitForBit) {
  const fs::path one = dir_ / "one_process";
  ASSERT_EQ(train(one, 0), 0) << output_of(one);
  const fs::path& two = two_ranks();
  const auto losses_two = step_losses(two / "log.jsonl");
  ASSERT_EQ(losses_two.size(), 8u + 9u);  // 4 epochs x 2 junction steps, 3 epochs x 3 edge steps
  expect_close(stage_steps(losses_two, "junction"), stage_steps(step_losses(one / "log.jsonl"), "junction"));
  // The edge stage trains on the pairs of the junction model's predictions, which select junctions by
  // thresholds: it is compared from the same junction model (the 2-rank run's, trained again by one process).
  const fs::path one_edge = dir_ / "one_process_edge";
  fs::create_directories(one_edge);
  fs::copy_file(two / "junction.safetensors", one_edge / "junction.safetensors");
  ASSERT_EQ(train(one_edge, 0, {"--stage", "edge"}), 0) << output_of(one_edge);
  expect_close(stage_steps(losses_two, "edge"), step_losses(one_edge / "log.jsonl"));

  // Every step checked both replicas: two fingerprints, equal.
  for (const auto& step : log_lines(two / "log.jsonl", "step")) {
    EXPECT_EQ(step["ranks"], 2);
    ASSERT_EQ(step["replicas"].size(), 2u) << step.dump();
    EXPECT_EQ(step["replicas"][0], step["replicas"][1]) << step.dump();
  }
  // Validation was split over the ranks and pooled: the same buildings are scored.
  const auto val_one = log_lines(one / "log.jsonl", "val"), val_two = log_lines(two / "log.jsonl", "val");
  ASSERT_EQ(val_two.size(), val_one.size());
  for (size_t k = 0; k < val_two.size(); ++k) EXPECT_EQ(val_two[k]["buildings"], val_one[k]["buildings"]);

  // The same number of ranks again: the same bits.
  const fs::path again = dir_ / "two_ranks_again";
  ASSERT_EQ(train(again, 2), 0) << output_of(again);
  EXPECT_EQ(step_losses(again / "log.jsonl"), losses_two);
  for (const char* f : {"junction.safetensors", "edge.safetensors"}) EXPECT_EQ(read_text(again / f), read_text(two / f)) << f;
}

TEST_F(TrainMpi, AKilledRankEndsTheJobWithAMessageAndOneProcessResumes) {
  const fs::path out = dir_ / "killed";
  const Started job = start(train_args(out, 2), dir_ / "killed.out");
  const auto deadline = Clock::now() + std::chrono::seconds(120);
  while (steps_logged(out / "log.jsonl", "junction") < 3 && Clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  const pid_t victim = rank_pid(job.pid, 1);
  ASSERT_GT(victim, 0) << "rank 1 of the job not found";
  ASSERT_EQ(kill(victim, SIGKILL), 0);
  const std::optional<int> code = wait_for(job.pid, std::chrono::seconds(60));
  ASSERT_TRUE(code.has_value()) << "the job hung after a rank died";
  EXPECT_NE(*code, 0);
  const std::string output = read_text(job.output);
  EXPECT_NE(output.find("rank 0 of 2: stopped by the launcher: another rank failed"), std::string::npos) << output;
  EXPECT_NE(output.find("--resume"), std::string::npos) << output;
  const size_t done = steps_logged(out / "log.jsonl", "junction");
  EXPECT_LT(done, 8u) << "the job finished before rank 1 was killed";

  // One process carries on from the 2-rank checkpoint: the junction steps before the kill are the
  // 2-rank run's bit for bit, the rest match it within the tolerance (the edge stage, trained on the
  // pairs of a slightly different junction model, only has to complete).
  ASSERT_EQ(train(out, 0, {"--resume"}), 0) << output_of(out);
  const auto resumed = step_losses(out / "log.jsonl"), reference = step_losses(two_ranks() / "log.jsonl");
  ASSERT_EQ(resumed.size(), reference.size());
  for (size_t k = 0; k < done; ++k) EXPECT_EQ(resumed[k], reference[k]) << k;
  expect_close(stage_steps(resumed, "junction"), stage_steps(reference, "junction"));
  EXPECT_EQ(stage_steps(resumed, "edge").size(), 9u);
}

TEST_F(TrainMpi, ARankThatStopsAnsweringEndsTheJobAfterTheTimeout) {
  const fs::path out = dir_ / "stopped";
  const Started job = start(train_args(out, 2, {"--comm-timeout", "2"}), dir_ / "stopped.out");
  const auto deadline = Clock::now() + std::chrono::seconds(120);
  while (steps_logged(out / "log.jsonl", "junction") < 2 && Clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  const pid_t victim = rank_pid(job.pid, 1);
  ASSERT_GT(victim, 0) << "rank 1 of the job not found";
  ASSERT_EQ(kill(victim, SIGSTOP), 0);
  const std::optional<int> code = wait_for(job.pid, std::chrono::seconds(60));
  if (!code) kill(victim, SIGKILL);
  ASSERT_TRUE(code.has_value()) << "the job hung on a stopped rank";
  EXPECT_NE(*code, 0);
  const std::string output = read_text(job.output);
  EXPECT_NE(output.find("rank 0 of 2: no answer from the other ranks for 2 s (--comm-timeout)"), std::string::npos) << output;
  // The launcher's SIGTERM waits until the stopped rank runs again; then it ends.
  kill(victim, SIGCONT);
  const auto gone = Clock::now() + std::chrono::seconds(20);
  while (alive(victim) && Clock::now() < gone) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  if (alive(victim)) {
    kill(victim, SIGKILL);
    ADD_FAILURE() << "the stopped rank outlived the job";
  }
}

}  // namespace
}  // namespace lc2wf
