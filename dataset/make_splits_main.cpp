// lc2wf-make-splits: writes train.txt / val.txt / test.txt from the Roof-Image building names.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "dataset/building.h"
#include "dataset/splits.h"

namespace {

void usage(std::FILE* out) {
  std::fprintf(out,
               "Usage: lc2wf-make-splits --data DIR --out DIR [--seed N] [--test N] [--val N]\n"
               "Writes DIR/train.txt, val.txt, test.txt (one building name per line) from the .polyshape\n"
               "files in --data (e.g. ../shared/data/roof-image/res_building).\n"
               "Rule: sort names by mix(FNV-1a-64(name), seed); first --test are test (default 757), next --val\n"
               "validation (default 200), the rest train. Default seed 1555.\n");
}

}  // namespace

int main(int argc, char** argv) {
  std::string data, out;
  lc2wf::SplitRule rule;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      usage(stdout);
      return 0;
    }
    if (i + 1 >= argc) {
      std::fprintf(stderr, "error: %s needs a value\n", a.c_str());
      usage(stderr);
      return 2;
    }
    const std::string v = argv[++i];
    try {
      if (a == "--data") data = v;
      else if (a == "--out") out = v;
      else if (a == "--seed") rule.seed = std::stoull(v);
      else if (a == "--test") rule.test_count = std::stoi(v);
      else if (a == "--val") rule.val_count = std::stoi(v);
      else {
        std::fprintf(stderr, "error: unknown option %s\n", a.c_str());
        usage(stderr);
        return 2;
      }
    } catch (const std::exception&) {
      std::fprintf(stderr, "error: bad number for %s: %s\n", a.c_str(), v.c_str());
      return 2;
    }
  }
  if (data.empty() || out.empty()) {
    std::fprintf(stderr, "error: --data and --out are required\n");
    usage(stderr);
    return 2;
  }
  try {
    const auto names = lc2wf::list_polyshape_names(data);
    const auto s = lc2wf::make_splits(names, rule);
    std::filesystem::create_directories(out);
    lc2wf::write_name_list(std::filesystem::path(out) / "train.txt", s.train);
    lc2wf::write_name_list(std::filesystem::path(out) / "val.txt", s.val);
    lc2wf::write_name_list(std::filesystem::path(out) / "test.txt", s.test);
    std::printf("%zu buildings: %zu train, %zu val, %zu test -> %s\n", names.size(), s.train.size(), s.val.size(),
                s.test.size(), out.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
