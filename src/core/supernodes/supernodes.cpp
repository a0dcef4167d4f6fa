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

namespace {
/// extractSupernodes() over its state: the supernodes so far, the points processed (those
/// before p in descending f, so in M(p)), and where each merged supernode redirects (to the
/// one created at its saddle, step (d)).
class SupernodeExtractor {
public:
  SupernodeExtractor(const CsrGraph& graph, const std::vector<float>& f, float crossing_fraction)
      : graph_(graph), f_(f), crossing_fraction_(crossing_fraction),
        processed_((graph.numVertices() + 63) / 64, 0) {
    sn_.label.assign(graph.numVertices(), kNone);
  }

  /// Point p, next in descending f: steps 1 and (b)-(d) of Sec. 4.2.
  void process(std::uint32_t p) {
    processed_[p >> 6] |= std::uint64_t(1) << (p & 63);
    const std::uint32_t steepest = countProcessedNeighbours(p);
    if (counts_.empty()) { // step 1: p is a local maximum
      sn_.label[p] = create(p, false);
      return;
    }
    // Step (b): drop supernodes holding only a small fraction of N(p).
    const float min_count = crossing_fraction_ * static_cast<float>(graph_.degree(p));
    kept_.clear();
    for (const auto& c : counts_)
      if (static_cast<float>(c.second) >= min_count)
        kept_.push_back(c.first);
    if (kept_.empty()) {
      sn_.label[p] = steepest; // no rule in the text: follow the gradient
    } else if (kept_.size() == 1) {
      sn_.label[p] = kept_.front(); // step (c)
    } else {
      sn_.label[p] = createAtSaddle(p); // step (d)
    }
  }

  Supernodes& supernodes() { return sn_; }

private:
  /// One bit per vertex: processed. The bits stay in the processor's cache, where ranks would
  /// be another array read at random.
  bool isProcessed(std::uint32_t v) const { return (processed_[v >> 6] >> (v & 63)) & 1u; }

  /// counts_: per supernode, how many points of M(p) it holds. Returns the supernode of
  /// argmax_{q in M(p)} z(p, q), the steepest ascent (kNone when M(p) is empty).
  std::uint32_t countProcessedNeighbours(std::uint32_t p) {
    counts_.clear();
    std::uint32_t steepest = kNone;
    float best_z = -std::numeric_limits<float>::infinity();
    for (std::uint32_t e = graph_.offsets[p]; e < graph_.offsets[p + 1]; ++e) {
      const std::uint32_t q = graph_.targets[e];
      if (q == p || !isProcessed(q))
        continue; // not processed: not in M(p)
      const std::uint32_t s = find(sn_.label[q]);
      auto it =
          std::find_if(counts_.begin(), counts_.end(), [s](const auto& c) { return c.first == s; });
      if (it == counts_.end())
        counts_.emplace_back(s, 1);
      else
        ++it->second;
      // z(p, q) = (f(q) - f(p)) / d(p, q); a duplicate point (d = 0) is the steepest.
      const float d = graph_.lengths[e];
      const float z = d > 0.0f ? (f_[q] - f_[p]) / d : std::numeric_limits<float>::infinity();
      if (z > best_z) {
        best_z = z;
        steepest = s;
      }
    }
    return steepest;
  }

  /// Step (d): p is a saddle; a new supernode takes it, and the kept ones terminate there.
  std::uint32_t createAtSaddle(std::uint32_t p) {
    std::sort(kept_.begin(), kept_.end());
    const std::uint32_t s = create(p, true);
    for (std::uint32_t t : kept_) {
      sn_.parent[t] = s;
      sn_.children[s].push_back(t);
      redirect_[t] = s;
    }
    return s;
  }

  std::uint32_t create(std::uint32_t point, bool at_saddle) {
    const auto s = static_cast<std::uint32_t>(sn_.origin.size());
    sn_.origin.push_back(point);
    sn_.at_saddle.push_back(at_saddle);
    sn_.parent.push_back(kNone);
    sn_.children.emplace_back();
    redirect_.push_back(s);
    return s;
  }

  /// The supernode s now belongs to, with the path compressed.
  std::uint32_t find(std::uint32_t s) {
    std::uint32_t r = s;
    while (redirect_[r] != r)
      r = redirect_[r];
    while (redirect_[s] != r) {
      const std::uint32_t next = redirect_[s];
      redirect_[s] = r;
      s = next;
    }
    return r;
  }

  const CsrGraph& graph_;
  const std::vector<float>& f_;
  const float crossing_fraction_;
  Supernodes sn_;
  std::vector<std::uint64_t> processed_;
  std::vector<std::uint32_t> redirect_;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> counts_; // (supernode, points in M(p))
  std::vector<std::uint32_t> kept_;
};
} // namespace

Supernodes extractSupernodes(const CsrGraph& graph, const std::vector<float>& f,
                             float crossing_fraction) {
  const std::size_t n = graph.numVertices();
  SupernodeExtractor extractor(graph, f, crossing_fraction);
  const Supernodes& sn = extractor.supernodes();
  // Descending f, ties by index: a deterministic order for equal values.
  const std::vector<std::uint32_t> order = descendingOrder(f);
  // The order jumps around the graph: fetch the rows (and, twice as far ahead, the offsets)
  // of the vertices a few places ahead, as the searches do (core/graph/shortest_paths.h).
  constexpr std::size_t kAhead = 8;
  const std::uint32_t last_edge =
      graph.targets.empty() ? 0u : static_cast<std::uint32_t>(graph.targets.size() - 1);
  for (std::size_t i = 0; i < n; ++i) {
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
    extractor.process(order[i]);
  }
  return std::move(extractor.supernodes());
}

} // namespace pcl_ncut_seg
