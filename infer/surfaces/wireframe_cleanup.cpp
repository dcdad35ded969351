#include "infer/surfaces/wireframe_cleanup.h"

#include <algorithm>
#include <numeric>
#include <set>
#include <utility>

namespace lc2wf {
namespace {

int find_root(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

Wireframe clean_wireframe(const Wireframe& in, double merge_distance) {
  const int n = static_cast<int>(in.junctions.size());
  // Only junctions some edge uses take part: isolated junctions are no evidence of a face.
  std::vector<bool> used(n, false);
  for (const auto& e : in.edges) used[e[0]] = used[e[1]] = true;
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      if (used[i] && used[j] && (in.junctions[i] - in.junctions[j]).norm() < merge_distance)
        parent[find_root(parent, j)] = find_root(parent, i);
  std::vector<int> id(n, -1);
  std::vector<Vec3> sum;
  std::vector<int> members;
  Wireframe out;
  for (int i = 0; i < n; ++i) {
    if (!used[i]) continue;
    const int r = find_root(parent, i);
    if (id[r] < 0) {
      id[r] = static_cast<int>(sum.size());
      sum.push_back(Vec3::Zero());
      members.push_back(0);
    }
    id[i] = id[r];
    sum[id[i]] += in.junctions[i];
    ++members[id[i]];
  }
  for (size_t k = 0; k < sum.size(); ++k) out.junctions.push_back(sum[k] / members[k]);

  std::set<std::pair<int, int>> edges;
  for (const auto& e : in.edges) {
    const int a = id[e[0]], b = id[e[1]];
    if (a != b) edges.insert({std::min(a, b), std::max(a, b)});
  }
  // Split every edge at the junctions lying on it (a corner of one face in the middle of another's side).
  std::set<std::pair<int, int>> split;
  const int m = static_cast<int>(out.junctions.size());
  for (const auto& [a, b] : edges) {
    const Vec3 pa = out.junctions[a], d = out.junctions[b] - pa;
    const double len = d.norm();
    std::vector<std::pair<double, int>> on;
    for (int j = 0; j < m; ++j) {
      if (j == a || j == b) continue;
      const double t = (out.junctions[j] - pa).dot(d) / (len * len);
      if (t * len <= merge_distance || (1 - t) * len <= merge_distance) continue;
      if ((pa + t * d - out.junctions[j]).norm() < merge_distance) on.push_back({t, j});
    }
    std::sort(on.begin(), on.end());
    int prev = a;
    for (const auto& [t, j] : on) {
      split.insert({std::min(prev, j), std::max(prev, j)});
      prev = j;
    }
    split.insert({std::min(prev, b), std::max(prev, b)});
  }
  for (const auto& [a, b] : split) out.edges.push_back({a, b});
  return out;
}

}  // namespace lc2wf
