// The processes of a data-parallel training job and the collective operations lc2wf-train needs from
// them. A plain `lc2wf-train` is a job of one process (LocalCommunicator: every operation is the
// identity, so the single-process run is unchanged); under mpirun or srun it is one rank of an MPI job
// (train/mpi_communicator.cpp, built when Open MPI is found). Every collective must be called in the
// same order on every rank; `what` names it in the error raised when the other ranks never answer.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace lc2wf {

class Communicator {
 public:
  virtual ~Communicator() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;

  // Element-wise sums over all ranks, in place; every rank gets the same bits.
  virtual void sum(float* values, int64_t n, const char* what) = 0;
  virtual void sum(double* values, int64_t n, const char* what) = 0;
  virtual uint64_t max(uint64_t value, const char* what) = 0;

  // A sum started now and finished by wait(); test() lets it progress (false while it runs). The buffer
  // must stay untouched until wait() returns.
  class PendingSum {
   public:
    virtual ~PendingSum() = default;
    virtual bool test() = 0;
    virtual void wait() = 0;
  };
  virtual std::unique_ptr<PendingSum> start_sum(float* values, int64_t n, const char* what) = 0;

  // Every rank's bytes, in rank order.
  virtual std::vector<std::string> all_gather(const std::string& bytes, const char* what) = 0;
  // Rank 0's data on every rank.
  virtual void broadcast(std::string& bytes, const char* what) = 0;
  virtual void broadcast(float* values, int64_t n, const char* what) = 0;
  virtual void barrier(const char* what) = 0;

  // Ends every rank of the job after a failure on this one (the launcher reports it). A job of one
  // process has nobody to end: returns.
  virtual void abort_job(int exit_code) = 0;
};

// all_gather of doubles: every rank's values, in rank order.
std::vector<std::vector<double>> gather_doubles(Communicator& comm, const std::vector<double>& values, const char* what);

// The job of one process.
class LocalCommunicator final : public Communicator {
 public:
  int rank() const override { return 0; }
  int size() const override { return 1; }
  void sum(float*, int64_t, const char*) override {}
  void sum(double*, int64_t, const char*) override {}
  uint64_t max(uint64_t value, const char*) override { return value; }
  std::unique_ptr<PendingSum> start_sum(float* values, int64_t n, const char* what) override;
  std::vector<std::string> all_gather(const std::string& bytes, const char*) override { return {bytes}; }
  void broadcast(std::string&, const char*) override {}
  void broadcast(float*, int64_t, const char*) override {}
  void barrier(const char*) override {}
  void abort_job(int) override {}
};

struct CommunicatorOptions {
  // A collective that gets no answer from the other ranks for this long ends the job with a message
  // (a rank stopped without dying, an unreachable node). Seconds; > 0.
  double timeout_s = 1800.0;
  void Check() const;
};

// The MPI job this process was started in by mpirun/srun (MPI is initialised here and finalised when
// the communicator is destroyed), or a LocalCommunicator when no MPI launcher started it. Throws when
// an MPI launcher started it but lc2wf was built without MPI.
std::unique_ptr<Communicator> open_communicator(int* argc, char*** argv, const CommunicatorOptions& options);

// True when the environment shows an MPI launcher (mpirun, srun with PMI/PMIx) started this process.
bool started_by_mpi_launcher();
// True when this build has MPI support.
bool built_with_mpi();

}  // namespace lc2wf
