// Sec. 4.2: supernodes from the discrete gradient flow, created anew at saddle points, with
// feature-crossing edges removed by the fraction rule (b).
#include "core/supernodes/supernodes.h"
#include "core/common/prefetch.h"
#include "core/common/radix_sort.h"

#include <algorithm>
#include <numeric>

namespace pcl_ncut_seg {
std::vector<std::uint32_t> Supernodes::localMaxima() const {
  std::vector<std::uint32_t> out;
  for (std::size_t s = 0; s < size(); ++s)
    if (!at_saddle[s])
      out.push_back(origin[s]);
  return out;
}

std::vector<std::uint32_t> Supernodes::saddles() const {
  std::vector<std::uint32_t> out;
  for (std::size_t s = 0; s < size(); ++s)
    if (at_saddle[s])
      out.push_back(origin[s]);
  return out;
}

std::vector<std::uint32_t> compactLabels(const std::vector<std::uint32_t>& label,
                                         std::size_t num_labels, std::vector<std::uint32_t>& id,
                                         std::vector<std::uint32_t>& compact) {
  const std::size_t n = label.size();
  std::vector<std::uint32_t> first;
  id.assign(num_labels, kNone);
  compact.resize(n);
  for (std::uint32_t p = 0; p < n; ++p) {
    std::uint32_t& to = id[label[p]];
    if (to == kNone) {
      to = static_cast<std::uint32_t>(first.size());
      first.push_back(p);
    }
    compact[p] = to;
  }
  return first;
}

std::vector<std::uint32_t> joinGroups(const std::vector<std::uint32_t>& group,
                                      std::vector<std::uint32_t>& segment,
                                      std::size_t& num_segments) {
  const std::size_t t = group.size();
  std::vector<std::uint32_t> id(t, kNone), map(t);
  std::uint32_t count = 0;
  for (std::size_t s = 0; s < t; ++s) {
    if (id[group[s]] == kNone)
      id[group[s]] = count++;
    map[s] = id[group[s]];
  }
  for (auto& s : segment)
    s = map[s];
  num_segments = count;
  return map;
}

Supernodes renumberSupernodes(const Supernodes& sn) {
  Supernodes out;
  std::vector<std::uint32_t> id;
  const std::size_t m = compactLabels(sn.label, sn.size(), id, out.label).size();
  out.origin.resize(m);
  out.at_saddle.resize(m);
  out.parent.assign(m, kNone);
  out.children.resize(m);
  for (std::uint32_t s = 0; s < sn.size(); ++s) {
    if (id[s] == kNone)
      continue;
    out.origin[id[s]] = sn.origin[s];
    out.at_saddle[id[s]] = sn.at_saddle[s];
    if (sn.parent[s] != kNone && id[sn.parent[s]] != kNone)
      out.parent[id[s]] = id[sn.parent[s]];
  }
  for (std::uint32_t s = 0; s < m; ++s)
    if (out.parent[s] != kNone)
      out.children[out.parent[s]].push_back(s);
  return out;
}

Supernodes extractSupernodes(const CsrGraph& graph, const std::vector<float>& f,
                             float crossing_fraction) {
  const std::size_t n = graph.numVertices();
  Supernodes sn;
  sn.label.assign(n, kNone);
  // Descending f, ties by index: a deterministic order for equal values.
  const std::vector<std::uint32_t> order = descendingOrder(f);
  // One bit per vertex: processed (before p in that order, so in M(p)). The bits stay in the
  // processor's cache, where ranks would be another array read at random.
  std::vector<std::uint64_t> processed((n + 63) / 64, 0);
  auto isProcessed = [&processed](std::uint32_t v) { return (processed[v >> 6] >> (v & 63)) & 1u; };

  // A merged supernode redirects to the one created at its saddle (step (d)).
  std::vector<std::uint32_t> redirect;
  auto find = [&](std::uint32_t s) {
    std::uint32_t r = s;
    while (redirect[r] != r)
      r = redirect[r];
    while (redirect[s] != r) {
      const std::uint32_t next = redirect[s];
      redirect[s] = r;
      s = next;
    }
    return r;
  };
  auto create = [&](std::uint32_t point, bool at_saddle) {
    const auto s = static_cast<std::uint32_t>(sn.origin.size());
    sn.origin.push_back(point);
    sn.at_saddle.push_back(at_saddle);
    sn.parent.push_back(kNone);
    sn.children.emplace_back();
    redirect.push_back(s);
    return s;
  };

  std::vector<std::pair<std::uint32_t, std::uint32_t>> counts; // (supernode, points in M(p))
  std::vector<std::uint32_t> kept;
  // The order jumps around the graph: fetch the rows (and, twice as far ahead, the offsets)
  // of the vertices a few places ahead, as the searches do (core/graph/shortest_paths.h).
  constexpr std::size_t kAhead = 8;
  const std::uint32_t last_edge =
      graph.targets.empty() ? 0u : static_cast<std::uint32_t>(graph.targets.size() - 1);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t p = order[i];
    if (i + 2 * kAhead < n)
      prefetch(&graph.offsets[order[i + 2 * kAhead]]);
    if (i + kAhead < n) {
      const std::uint32_t a = order[i + kAhead];
      const std::uint32_t row = graph.offsets[a];
      prefetch(&graph.targets[row]);
      prefetch(&graph.targets[std::min(row + 15, last_edge)]);
      prefetch(&graph.lengths[row]);
      prefetch(&sn.label[a]);
      prefetch(&f[a]);
    }
    processed[p >> 6] |= std::uint64_t(1) << (p & 63);
    counts.clear();
    const std::uint32_t begin = graph.offsets[p], end = graph.offsets[p + 1];
    std::uint32_t steepest = kNone; // the supernode of argmax_{q in M(p)} z(p, q)
    float best_z = -std::numeric_limits<float>::infinity();
    for (std::uint32_t e = begin; e < end; ++e) {
      const std::uint32_t q = graph.targets[e];
      if (q == p || !isProcessed(q))
        continue; // not processed: not in M(p)
      const std::uint32_t s = find(sn.label[q]);
      auto it =
          std::find_if(counts.begin(), counts.end(), [s](const auto& c) { return c.first == s; });
      if (it == counts.end())
        counts.emplace_back(s, 1);
      else
        ++it->second;
      // z(p, q) = (f(q) - f(p)) / d(p, q); a duplicate point (d = 0) is the steepest.
      const float d = graph.lengths[e];
      const float z = d > 0.0f ? (f[q] - f[p]) / d : std::numeric_limits<float>::infinity();
      if (z > best_z) {
        best_z = z;
        steepest = s;
      }
    }
    if (counts.empty()) { // step 1: p is a local maximum
      sn.label[p] = create(p, false);
      continue;
    }
    // Step (b): drop supernodes holding only a small fraction of N(p).
    const float min_count = crossing_fraction * static_cast<float>(end - begin);
    kept.clear();
    for (const auto& c : counts)
      if (static_cast<float>(c.second) >= min_count)
        kept.push_back(c.first);
    if (kept.empty()) {
      sn.label[p] = steepest; // no rule in the text: follow the gradient
    } else if (kept.size() == 1) {
      sn.label[p] = kept.front(); // step (c)
    } else {                      // step (d): p is a saddle
      std::sort(kept.begin(), kept.end());
      const std::uint32_t s = create(p, true);
      for (std::uint32_t t : kept) {
        sn.parent[t] = s;
        sn.children[s].push_back(t);
        redirect[t] = s;
      }
      sn.label[p] = s;
    }
  }
  return sn;
}

} // namespace pcl_ncut_seg
