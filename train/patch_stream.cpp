#include "train/patch_stream.h"

#include <algorithm>
#include <stdexcept>

#include "dataset/batch_loader.h"
#include "dataset/rng.h"

namespace lc2wf {

template <class Patches>
struct PatchStream<Patches>::Impl {
  size_t num_buildings;
  BuildFn build;
  PatchStreamOptions options;
  std::vector<size_t> order;
  int64_t epoch = 0, first = 0;
  std::unique_ptr<BatchLoader<StreamBatch<Patches>>> loader;
};

template <class Patches>
PatchStream<Patches>::PatchStream(size_t num_buildings, BuildFn build, PatchStreamOptions options)
    : impl_(std::make_unique<Impl>()) {
  if (options.batch_size < 1) throw std::invalid_argument("PatchStreamOptions.batch_size must be >= 1");
  if (options.workers < 1) throw std::invalid_argument("PatchStreamOptions.workers must be >= 1");
  if (options.max_batches < 0) throw std::invalid_argument("PatchStreamOptions.max_batches must be >= 0");
  if (options.ranks < 1 || options.rank < 0 || options.rank >= options.ranks)
    throw std::invalid_argument("PatchStreamOptions.rank must be in [0, ranks)");
  impl_->num_buildings = num_buildings;
  impl_->build = std::move(build);
  impl_->options = options;
}

template <class Patches>
PatchStream<Patches>::~PatchStream() = default;

template <class Patches>
int64_t PatchStream<Patches>::batches_per_epoch() const {
  const int64_t n = static_cast<int64_t>(impl_->num_buildings), b = impl_->options.batch_size;
  int64_t count = impl_->options.drop_last ? n / b : (n + b - 1) / b;
  if (impl_->options.max_batches > 0) count = std::min(count, impl_->options.max_batches);
  return count;
}

template <class Patches>
void PatchStream<Patches>::start(int64_t epoch, int64_t first_batch) {
  Impl& s = *impl_;
  s.loader.reset();
  s.epoch = epoch;
  s.first = first_batch;
  s.order.resize(s.num_buildings);
  for (size_t i = 0; i < s.num_buildings; ++i) s.order[i] = i;
  if (s.options.shuffle) {
    DataRng rng(mix_seed(s.options.seed, static_cast<uint64_t>(epoch)));
    rng.shuffle(s.order);
  }
  const int64_t remaining = std::max<int64_t>(0, batches_per_epoch() - first_batch);
  // The loader walks batch indices (one "item" per batch) so skipped batches cost nothing.
  LoaderOptions lo;
  lo.batch_size = 1;
  lo.workers = static_cast<int>(s.options.workers);
  lo.prefetch_batches = 2;
  lo.shuffle = false;
  lo.drop_last = false;
  auto build_batch = [this](const std::vector<size_t>& items, uint64_t) {
    const Impl& st = *impl_;
    const int64_t b = st.first + static_cast<int64_t>(items.at(0));
    const uint64_t batch_seed = mix_seed(mix_seed(st.options.seed, static_cast<uint64_t>(st.epoch)), static_cast<uint64_t>(b));
    const size_t begin = static_cast<size_t>(b * st.options.batch_size);
    const size_t end = std::min(begin + static_cast<size_t>(st.options.batch_size), st.num_buildings);
    StreamBatch<Patches> out;
    out.batch = static_cast<int64_t>(end - begin);
    out.share = batch_share(out.batch, st.options.rank, st.options.ranks);
    std::vector<Patches> parts;
    const size_t first = begin + static_cast<size_t>(out.share.first);
    for (size_t k = first; k < first + static_cast<size_t>(out.share.count); ++k)
      parts.push_back(st.build(st.order[k], mix_seed(batch_seed, k - begin)));
    if (!parts.empty()) out.patches = stack(parts);
    return out;
  };
  s.loader = std::make_unique<BatchLoader<StreamBatch<Patches>>>(static_cast<size_t>(remaining), build_batch, lo);
  s.loader->start_epoch(static_cast<int>(epoch));
}

template <class Patches>
std::optional<StreamBatch<Patches>> PatchStream<Patches>::next() {
  if (!impl_->loader) throw std::logic_error("PatchStream::next called before start");
  return impl_->loader->next();
}

template class PatchStream<JunctionPatches>;
template class PatchStream<PairPatches>;

}  // namespace lc2wf
