#include "train/mpi_communicator.h"

#include <mpi.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/util/cli.h"
#include <thread>

namespace lc2wf {

namespace {

using Clock = std::chrono::steady_clock;

// The survivors' side of a failure: the launcher stops them with SIGTERM (or SIGINT on a cancel), and
// the message says why before the default action ends the process. Built once: a handler may not allocate.
char g_stop_message[512];

void on_stop_signal(int sig) {
  const ssize_t ignored = write(STDERR_FILENO, g_stop_message, std::strlen(g_stop_message));
  (void)ignored;
  signal(sig, SIG_DFL);
  raise(sig);
}

int checked_count(int64_t n, const char* what) {
  if (n < 0 || n > std::numeric_limits<int>::max())
    throw std::length_error(std::string(what) + ": " + std::to_string(n) + " elements are too many for one MPI call");
  return static_cast<int>(n);
}

class MpiCommunicator;

class MpiPendingSum final : public Communicator::PendingSum {
 public:
  MpiPendingSum(MpiCommunicator& comm, MPI_Request request, const char* what) : comm_(comm), request_(request), what_(what) {}
  ~MpiPendingSum() override;
  bool test() override;
  void wait() override;

 private:
  MpiCommunicator& comm_;
  MPI_Request request_;
  const char* what_;
};

class MpiCommunicator final : public Communicator {
 public:
  explicit MpiCommunicator(const CommunicatorOptions& options) : options_(options) {
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    // Gradient buckets run on a communicator of their own, so their order never mixes with the others'.
    MPI_Comm_dup(MPI_COMM_WORLD, &grad_comm_);
    if (size_ > 1) {
      std::snprintf(g_stop_message, sizeof g_stop_message,
                    "lc2wf-train: rank %d of %d: stopped by the launcher: another rank failed (its message and the "
                    "launcher's are above) or the job was cancelled. The last checkpoint in OUT/checkpoints is "
                    "complete: start the job again with --resume (any number of ranks).\n",
                    rank_, size_);
      signal(SIGTERM, on_stop_signal);
      signal(SIGINT, on_stop_signal);
    }
  }
  ~MpiCommunicator() override {
    MPI_Comm_free(&grad_comm_);
    int finalized = 0;
    MPI_Finalized(&finalized);
    if (!finalized) MPI_Finalize();
  }

  int rank() const override { return rank_; }
  int size() const override { return size_; }

  void sum(float* values, int64_t n, const char* what) override { all_reduce(values, n, MPI_FLOAT, MPI_SUM, what); }
  void sum(double* values, int64_t n, const char* what) override { all_reduce(values, n, MPI_DOUBLE, MPI_SUM, what); }
  uint64_t max(uint64_t value, const char* what) override {
    all_reduce(&value, 1, MPI_UINT64_T, MPI_MAX, what);
    return value;
  }

  std::unique_ptr<PendingSum> start_sum(float* values, int64_t n, const char* what) override {
    MPI_Request request;
    MPI_Iallreduce(MPI_IN_PLACE, values, checked_count(n, what), MPI_FLOAT, MPI_SUM, grad_comm_, &request);
    return std::make_unique<MpiPendingSum>(*this, request, what);
  }

  std::vector<std::string> all_gather(const std::string& bytes, const char* what) override {
    int mine = checked_count(static_cast<int64_t>(bytes.size()), what);
    std::vector<int> counts(static_cast<size_t>(size_)), offsets(static_cast<size_t>(size_));
    MPI_Request request;
    MPI_Iallgather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD, &request);
    wait(request, what);
    int64_t total = 0;
    for (int r = 0; r < size_; ++r) {
      offsets[static_cast<size_t>(r)] = checked_count(total, what);
      total += counts[static_cast<size_t>(r)];
    }
    std::string all(static_cast<size_t>(checked_count(total, what)), '\0');
    MPI_Iallgatherv(bytes.data(), mine, MPI_BYTE, all.data(), counts.data(), offsets.data(), MPI_BYTE, MPI_COMM_WORLD,
                    &request);
    wait(request, what);
    std::vector<std::string> out;
    for (int r = 0; r < size_; ++r)
      out.push_back(all.substr(static_cast<size_t>(offsets[static_cast<size_t>(r)]),
                               static_cast<size_t>(counts[static_cast<size_t>(r)])));
    return out;
  }

  void broadcast(std::string& bytes, const char* what) override {
    uint64_t n = bytes.size();
    MPI_Request request;
    MPI_Ibcast(&n, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD, &request);
    wait(request, what);
    bytes.resize(static_cast<size_t>(n));
    MPI_Ibcast(bytes.data(), checked_count(static_cast<int64_t>(n), what), MPI_BYTE, 0, MPI_COMM_WORLD, &request);
    wait(request, what);
  }

  void broadcast(float* values, int64_t n, const char* what) override {
    MPI_Request request;
    MPI_Ibcast(values, checked_count(n, what), MPI_FLOAT, 0, MPI_COMM_WORLD, &request);
    wait(request, what);
  }

  void barrier(const char* what) override {
    MPI_Request request;
    MPI_Ibarrier(MPI_COMM_WORLD, &request);
    wait(request, what);
  }

  void abort_job(int exit_code) override {
    std::fflush(stdout);
    std::fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, exit_code);
  }

  // Polls until the request completes: yields briefly (the other ranks are usually close), then sleeps
  // in short steps so a waiting rank leaves the cores to the loader threads and to ranks still computing.
  void wait(MPI_Request& request, const char* what) {
    const auto start = Clock::now();
    for (int64_t round = 0;; ++round) {
      int done = 0;
      MPI_Test(&request, &done, MPI_STATUS_IGNORE);
      if (done) return;
      if (round < 2000) {
        std::this_thread::yield();
      } else {
        std::this_thread::sleep_for(std::chrono::microseconds(round < 20000 ? 50 : 500));
        if (round % 64 == 0 && std::chrono::duration<double>(Clock::now() - start).count() > options_.timeout_s)
          time_out(what);
      }
    }
  }

  bool test(MPI_Request& request) {
    int done = 0;
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    return done != 0;
  }

 private:
  template <class T>
  void all_reduce(T* values, int64_t n, MPI_Datatype type, MPI_Op op, const char* what) {
    MPI_Request request;
    MPI_Iallreduce(MPI_IN_PLACE, values, checked_count(n, what), type, op, MPI_COMM_WORLD, &request);
    wait(request, what);
  }

  [[noreturn]] void time_out(const char* what) {
    std::fprintf(stderr,
                 "lc2wf-train: rank %d of %d: no answer from the other ranks for %.0f s (--comm-timeout) in the %s; "
                 "a rank is stuck or its node is unreachable. Ending the job; start it again with --resume.\n",
                 rank_, size_, options_.timeout_s, what);
    abort_job(kExitDataError);  // the job's I/O failed: the same code as any other I/O error
    std::abort();
  }

  CommunicatorOptions options_;
  int rank_ = 0, size_ = 1;
  MPI_Comm grad_comm_ = MPI_COMM_NULL;
};

MpiPendingSum::~MpiPendingSum() {
  // A sum abandoned by an exception still owns its buffer in MPI: finish it before the buffer goes.
  if (request_ != MPI_REQUEST_NULL) comm_.wait(request_, what_);
}
bool MpiPendingSum::test() { return request_ == MPI_REQUEST_NULL || comm_.test(request_); }
void MpiPendingSum::wait() {
  if (request_ != MPI_REQUEST_NULL) comm_.wait(request_, what_);
}

}  // namespace

std::unique_ptr<Communicator> open_mpi_communicator(int* argc, char*** argv, const CommunicatorOptions& options) {
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (!initialized) {
    int provided = 0;
    MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
    if (provided < MPI_THREAD_FUNNELED) throw std::runtime_error("MPI does not provide MPI_THREAD_FUNNELED");
  }
  return std::make_unique<MpiCommunicator>(options);
}

}  // namespace lc2wf
