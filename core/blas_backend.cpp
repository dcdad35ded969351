#include "core/blas_backend.h"

#include <dlfcn.h>

#include <cctype>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <mutex>

namespace lc2wf {
namespace {

// The CBLAS interface, declared here because the library is opened at run time (no headers needed).
enum CblasOrder { kRowMajor = 101 };
enum CblasTranspose { kNoTrans = 111, kTrans = 112 };
using CblasSgemm = void (*)(int, int, int, int, int, int, float, const float*, int, const float*, int, float, float*, int);
using InfoString = char* (*)();
using SetThreads = void (*)(int);

// Debian's threaded build, run with one thread per call: it locks its buffer pool, so our pool's threads
// may call it at once. The SINGLE_THREADED build does not (concurrent calls then share a buffer and
// return wrong products now and then: 0.7 % of small products from two threads), so it is refused.
constexpr const char* kLibraries[] = {"/usr/lib/x86_64-linux-gnu/openblas-pthread/libopenblas.so.0", "libopenblas.so.0"};

struct Backend {
  CblasSgemm sgemm = nullptr;
  std::string name;
};

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

Backend choose() {
  const char* forced = std::getenv("LC2WF_GEMM");
  const std::string want = forced ? lower(forced) : "auto";
  if (want == "eigen") return {nullptr, "eigen (LC2WF_GEMM=eigen)"};
  if (want != "auto")
    std::fprintf(stderr, "lc2wf: LC2WF_GEMM must be \"eigen\" or \"auto\", got \"%s\"; using auto\n", forced);
  std::string core;
#if defined(__x86_64__) && defined(__GNUC__)
  core = openblas_core_for(__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
                               __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512dq"),
                           __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"));
#endif
  if (core.empty()) return {nullptr, "eigen (no AVX2/FMA: no OpenBLAS kernel worth loading)"};
  // Read by OpenBLAS when it loads; a user's own kernel class wins. One thread: our pool parallelises the
  // tiles (set before loading so no OpenBLAS worker thread is started, and again below).
  setenv("OPENBLAS_CORETYPE", core.c_str(), 0);
  setenv("OPENBLAS_NUM_THREADS", "1", 1);
  void* lib = nullptr;
  for (const char* path : kLibraries)
    if ((lib = dlopen(path, RTLD_NOW | RTLD_LOCAL))) break;
  if (!lib) return {nullptr, "eigen (no libopenblas0-pthread)"};
  auto sgemm = reinterpret_cast<CblasSgemm>(dlsym(lib, "cblas_sgemm"));
  auto core_name = reinterpret_cast<InfoString>(dlsym(lib, "openblas_get_corename"));
  auto config = reinterpret_cast<InfoString>(dlsym(lib, "openblas_get_config"));
  auto set_threads = reinterpret_cast<SetThreads>(dlsym(lib, "openblas_set_num_threads"));
  const std::string loaded = core_name ? core_name() : "", built = config ? config() : "";
  std::string refused;
  if (!sgemm || !set_threads || built.empty()) refused = "eigen (the OpenBLAS found lacks cblas_sgemm or its info calls)";
  else if (built.find("SINGLE_THREADED") != std::string::npos) refused = "eigen (only OpenBLAS's single-threaded build, unsafe for concurrent calls)";
  else if (!openblas_core_acceptable(loaded, core)) refused = "eigen (OpenBLAS runs its " + (loaded.empty() ? std::string("unknown") : loaded) + " kernel, not " + core + ")";
  if (!refused.empty()) {
    dlclose(lib);
    return {nullptr, refused};
  }
  set_threads(1);
  return {sgemm, "openblas (" + loaded + ")"};
}

const Backend& backend() {
  static std::once_flag once;
  static Backend b;
  std::call_once(once, [] { b = choose(); });
  return b;
}

}  // namespace

std::string openblas_core_for(bool avx512_skylake, bool avx2_fma) {
  if (avx512_skylake) return "SkylakeX";
  if (avx2_fma) return "Haswell";
  return "";
}

bool openblas_core_acceptable(const std::string& loaded, const std::string& wanted) {
  const std::string l = lower(loaded);
  if (l == lower(wanted)) return true;
  // Kernels of the same or a neighbouring class run near the machine's peak too (OpenBLAS may decline an
  // AVX-512 class the OS does not enable); what is refused is a fallback such as Prescott (SSE3).
  const bool avx2 = l == "haswell" || l == "zen";
  const bool avx512 = l == "skylakex" || l == "cooperlake" || l == "sapphirerapids";
  return lower(wanted) == "skylakex" ? avx2 || avx512 : avx2;
}

std::string gemm_backend_name() { return backend().name; }

bool openblas_sgemm(bool ta, bool tb, int64_t M, int64_t N, int64_t K, const float* A, int64_t lda, const float* B,
                    int64_t ldb, float* C, int64_t ldc, bool accumulate) {
  const Backend& b = backend();
  if (!b.sgemm) return false;
  for (int64_t v : {M, N, K, lda, ldb, ldc})
    if (v > INT_MAX) return false;
  b.sgemm(kRowMajor, ta ? kTrans : kNoTrans, tb ? kTrans : kNoTrans, static_cast<int>(M), static_cast<int>(N),
          static_cast<int>(K), 1.0f, A, static_cast<int>(lda), B, static_cast<int>(ldb), accumulate ? 1.0f : 0.0f, C,
          static_cast<int>(ldc));
  return true;
}

}  // namespace lc2wf
