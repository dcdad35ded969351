// Whole-file reads for the dataset layer; atomic writes come from core/util/atomic_file.h.
#pragma once

#include <filesystem>
#include <string>

#include "core/util/atomic_file.h"  // write_file_atomic (header-only: no link dependency on core)
#include "core/util/input_file.h"   // input_file_problem

namespace lc2wf {

// Reads a whole regular file; throws DataError naming the path when it cannot be opened or is a FIFO,
// device, directory or larger than kMaxInputFileBytes.
std::string read_file(const std::filesystem::path& path);

}  // namespace lc2wf
