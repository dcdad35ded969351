// A bound on the junction pairs the edge model classifies, whatever a cluttered map yields: the edge model's
// time grows with its pair count (≈ 0.4 ms per pair in fp32 on two cores: 64 line slots each), and a map full
// of clutter lines yields hundreds of junction candidates. Above the cap, pairs are ranked by evidence - the
// line support near both of their junctions - and each junction keeps at most its best few. Clouds with no
// more pairs than the cap pass unchanged, so ordinary buildings are never touched.
#pragma once

#include <cstdint>
#include <vector>

#include "dataset/geometry/geometry.h"
#include "dataset/sampling/patches.h"
#include "dataset/selection/pair_support.h"

namespace lc2wf {

struct PairCapOptions {
  // Pairs kept in total (0 = no cap): ≈ 0.5 s of edge model on two cores, whatever the clutter; more than an
  // ordinary building's selection gives (dataset/README.md, "Pair cap").
  int max_pairs = 1280;
  // Pairs kept per junction when the cap bites (0 = no per-junction limit).
  int max_pairs_per_junction = 64;
  // How far from each junction the support is measured (metres): the evidence an edge leaves near its ends.
  double end_length_m = 2.0;

  bool enabled() const { return max_pairs > 0; }
  void Check() const;  // throws std::invalid_argument naming the bad field
};

// The rank of a pair: the mean of the shares of the first min(end_length_m, half its length) from each
// junction that the cloud's segments run along (the support test of pair_support.h); pairs shorter than
// support.keep_shorter_than_m rank above every other (two detections of one junction). The same ranks on
// any number of threads.
std::vector<double> pair_end_support(const std::vector<JunctionPair>& pairs, const std::vector<Segment3>& segments,
                                     const PairSupportOptions& support, double end_length_m, int threads = 1);

// `pairs` unchanged when there are no more than max_pairs; else the best-ranked pairs, each junction in at
// most max_pairs_per_junction of them and max_pairs in all (ties: the shorter pair, then the earlier one),
// in their input order. Deterministic, on any number of threads (they rank the pairs).
std::vector<JunctionPair> capped_pairs(const std::vector<JunctionPair>& pairs, const std::vector<Segment3>& segments,
                                       const PairCapOptions& cap, const PairSupportOptions& support = {}, int threads = 1);

}  // namespace lc2wf
