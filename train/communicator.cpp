#include "train/communicator.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#ifdef LC2WF_WITH_MPI
#include "train/mpi_communicator.h"
#endif

namespace lc2wf {

namespace {

class DoneSum final : public Communicator::PendingSum {
 public:
  bool test() override { return true; }
  void wait() override {}
};

// The launcher's count of processes, or 0 when none is visible (only a build without MPI asks).
[[maybe_unused]] int launcher_world_size() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"}) {
    if (const char* v = std::getenv(name)) {
      const int n = std::atoi(v);
      if (n > 0) return n;
    }
  }
  return 0;
}

}  // namespace

std::unique_ptr<Communicator::PendingSum> LocalCommunicator::start_sum(float*, int64_t, const char*) {
  return std::make_unique<DoneSum>();
}

std::vector<std::vector<double>> gather_doubles(Communicator& comm, const std::vector<double>& values, const char* what) {
  const std::string mine(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(double));
  std::vector<std::vector<double>> out;
  for (const std::string& bytes : comm.all_gather(mine, what)) {
    std::vector<double> v(bytes.size() / sizeof(double));
    std::memcpy(v.data(), bytes.data(), v.size() * sizeof(double));
    out.push_back(std::move(v));
  }
  return out;
}

void CommunicatorOptions::Check() const {
  if (!(timeout_s > 0) || !std::isfinite(timeout_s)) throw std::invalid_argument("--comm-timeout must be > 0 seconds");
}

bool started_by_mpi_launcher() {
  // Open MPI's mpirun, and srun --mpi=pmix / pmi2 (Slurm); a bare srun task without PMI is no MPI job.
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK"})
    if (std::getenv(name)) return true;
  return false;
}

bool built_with_mpi() {
#ifdef LC2WF_WITH_MPI
  return true;
#else
  return false;
#endif
}

std::unique_ptr<Communicator> open_communicator(int* argc, char*** argv, const CommunicatorOptions& options) {
  options.Check();
  if (!started_by_mpi_launcher()) return std::make_unique<LocalCommunicator>();
#ifdef LC2WF_WITH_MPI
  return open_mpi_communicator(argc, argv, options);
#else
  (void)argc, (void)argv;
  // N copies of a single-process trainer would all write the same output folder.
  if (launcher_world_size() > 1)
    throw std::runtime_error("this lc2wf-train was built without MPI (Open MPI was not found when it was built) but "
                             "was started as one of " + std::to_string(launcher_world_size()) +
                             " MPI processes; install libopenmpi-dev (tools/setup-deps.sh) and rebuild");
  return std::make_unique<LocalCommunicator>();
#endif
}

}  // namespace lc2wf
