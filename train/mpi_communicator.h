// The MPI implementation of Communicator (Open MPI; built when CMake finds MPI). Every wait polls with a
// deadline, so a rank that stops answering ends the job with a message instead of a hang; a rank that
// dies is reported by the launcher, which then stops the others (they print why they were stopped).
#pragma once

#include <memory>

#include "train/communicator.h"

namespace lc2wf {

// Initialises MPI (thread level FUNNELED: only the compute thread calls MPI).
std::unique_ptr<Communicator> open_mpi_communicator(int* argc, char*** argv, const CommunicatorOptions& options);

}  // namespace lc2wf
