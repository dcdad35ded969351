// Split lists (configs/splits/*.txt, --split): one building name per line.
#include "dataset/splits/splits.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lc2wf::fuzz::expect_clean_rejection([&] { (void)lc2wf::parse_name_list(lc2wf::fuzz::bytes(data, size), "fuzz.txt"); });
  return 0;
}
