// Sec. 4.1's geodesic distances: Dial's bucket queue and a cache-friendly vertex order.
#include "core/graph/shortest_paths.h"
#include "core/common/prefetch.h"

#include <algorithm>
#include <limits>

namespace pcl_ncut_seg {
namespace {
constexpr std::uint32_t kNotQueued = std::numeric_limits<std::uint32_t>::max();
constexpr float kInf = std::numeric_limits<float>::infinity();

/// Dial's bucket circle for a graph: bucket width about twice the mean edge, and a power-of-two
/// number of buckets that covers the longest edge (pending entries lie within longest / width
/// + 1 buckets of the current one).
struct BucketCircle {
  double inv_width = 1.0;
  std::size_t count = 2;
};

BucketCircle bucketCircle(const CsrGraph& graph) {
  double sum = 0.0;
  float longest = 0.0f;
  for (float w : graph.lengths) {
    sum += w;
    longest = std::max(longest, w);
  }
  const std::size_t m = graph.lengths.size();
  double width = m > 0 && sum > 0.0 ? 2.0 * sum / static_cast<double>(m) : 1.0;
  // An outlier edge must not need millions of buckets: at most 2^16 + 2 buckets of the circle.
  width = std::max(width, static_cast<double>(longest) / 65536.0);
  BucketCircle c;
  c.inv_width = 1.0 / width;
  while (c.count < static_cast<std::size_t>(longest * c.inv_width) + 2)
    c.count *= 2;
  return c;
}

/// One bit per vertex.
struct PendingBits {
  std::uint64_t* bits;
  bool has(std::uint32_t v) const { return (bits[v >> 6] >> (v & 63)) & 1u; }
  void set(std::uint32_t v) const { bits[v >> 6] |= std::uint64_t(1) << (v & 63); }
  void clear(std::uint32_t v) const { bits[v >> 6] &= ~(std::uint64_t(1) << (v & 63)); }
};

/// How far ahead in the bucket to fetch rows (and, twice as far, their offsets): about the
/// number of memory accesses in flight that hide the latency of the processor's last cache.
constexpr std::size_t kAhead = 16;

/// Fetches the row of the vertex kAhead places after i in the bucket, and the offset of the one
/// 2 kAhead after: a search waits mostly on memory. Forced inline: out of line it slows the
/// search by half.
PCL_NCUT_SEG_ALWAYS_INLINE void prefetchAhead(const std::vector<std::uint32_t>& bucket,
                                              std::size_t i, const std::uint32_t* offsets,
                                              const std::uint32_t* targets, const float* lengths,
                                              std::uint32_t last_edge) {
  if (i + 2 * kAhead < bucket.size())
    prefetch(offsets + bucket[i + 2 * kAhead]);
  if (i + kAhead < bucket.size()) {
    const std::uint32_t row = offsets[bucket[i + kAhead]]; // rows average 11 edges
    const std::uint32_t row_tail = std::min(row + 15, last_edge);
    prefetch(targets + row);
    prefetch(targets + row_tail);
    prefetch(lengths + row);
    prefetch(lengths + row_tail);
  }
}
} // namespace

BucketDijkstra::BucketDijkstra(const CsrGraph& graph)
    : graph_(graph), pending_((graph.numVertices() + 63) / 64, 0) {
  const BucketCircle circle = bucketCircle(graph);
  inv_width_ = circle.inv_width;
  buckets_.resize(circle.count);
  mask_ = circle.count - 1;
}

void BucketDijkstra::run(std::uint32_t source, float* dist, const float* bound,
                         std::vector<std::uint32_t>* touched) {
  // One loop per combination, so that the full searches of the centrality run the leanest.
  if (bound)
    touched ? runImpl<Bound::PerVertex, true>(source, dist, bound, 0.0f, touched)
            : runImpl<Bound::PerVertex, false>(source, dist, bound, 0.0f, touched);
  else
    touched ? runImpl<Bound::None, true>(source, dist, bound, 0.0f, touched)
            : runImpl<Bound::None, false>(source, dist, bound, 0.0f, touched);
}

void BucketDijkstra::runWithin(std::uint32_t source, float* dist, float bound,
                               std::vector<std::uint32_t>* touched) {
  touched ? runImpl<Bound::Uniform, true>(source, dist, nullptr, bound, touched)
          : runImpl<Bound::Uniform, false>(source, dist, nullptr, bound, touched);
}

template <BucketDijkstra::Bound kBound, bool kRecord>
void BucketDijkstra::runImpl(std::uint32_t source, float* dist, const float* bound,
                             float uniform_bound, std::vector<std::uint32_t>* touched) {
  // Absolute bucket numbers fit 32 bits for any graph whose diameter is < 2^32 widths.
  const double inv_width = inv_width_;
  const std::size_t mask = mask_;
  auto bucketOf = [inv_width](float d) {
    return static_cast<std::uint32_t>(static_cast<double>(d) * inv_width);
  };
  const std::uint32_t* offsets = graph_.offsets.data();
  const std::uint32_t* targets = graph_.targets.data();
  const float* lengths = graph_.lengths.data();
  // The second cache line of a row is fetched at most up to the last edge (no address past it).
  const std::uint32_t last_edge =
      graph_.targets.empty() ? 0u : static_cast<std::uint32_t>(graph_.targets.size() - 1);
  const PendingBits pending{pending_.data()};
  constexpr std::uint32_t kChunk = 32; // edges relaxed before their targets are queued
  dist[source] = 0.0f;
  if (kRecord)
    touched->push_back(source);
  buckets_[0].push_back(source);
  pending.set(source);
  std::size_t queued = 1; // entries in the buckets, stale ones included
  for (std::uint32_t current = 0; queued > 0; ++current) {
    std::vector<std::uint32_t>& bucket = buckets_[current & mask];
    // Vertices improved within this bucket are appended to it and scanned again.
    for (std::size_t i = 0; i < bucket.size(); ++i) {
      prefetchAhead(bucket, i, offsets, targets, lengths, last_edge);
      const std::uint32_t v = bucket[i];
      --queued;
      const float dv = dist[v];
      // Stale: v was scanned since it was queued here, or it now waits in an earlier bucket.
      if (!pending.has(v) || bucketOf(dv) != current)
        continue;
      pending.clear(v);
      if (kBound == Bound::PerVertex && dv >= bound[v])
        continue;
      if (kBound == Bound::Uniform && dv >= uniform_bound)
        continue;
      // Relax the row without a branch per edge (whether an edge improves its target is
      // unpredictable), noting the improved targets; then queue those.
      std::uint32_t e = offsets[v];
      const std::uint32_t end = offsets[v + 1];
      while (e < end) {
        std::uint32_t improved[kChunk];
        float before[kChunk];
        std::size_t count = 0;
        for (const std::uint32_t stop = std::min(end, e + kChunk); e < stop; ++e) {
          const std::uint32_t t = targets[e];
          const float nd = dv + lengths[e];
          const float dt = dist[t];
          const bool better = nd < dt;
          dist[t] = better ? nd : dt;
          improved[count] = t;
          before[count] = dt;
          count += better;
        }
        for (std::size_t j = 0; j < count; ++j) {
          const std::uint32_t t = improved[j];
          const float dt = before[j];
          if (kRecord && dt == kInf)
            touched->push_back(t);
          const std::uint32_t b = bucketOf(dist[t]);
          // A pending vertex has a finite distance; if it waits in b it is scanned from there.
          if (pending.has(t) && bucketOf(dt) == b)
            continue;
          pending.set(t);
          buckets_[b & mask].push_back(t);
          ++queued;
        }
      }
    }
    bucket.clear();
  }
}

CsrGraph permuteGraph(const CsrGraph& graph, const std::vector<std::uint32_t>& order) {
  const std::size_t n = graph.numVertices();
  std::vector<std::uint32_t> position(n);
  for (std::uint32_t i = 0; i < n; ++i)
    position[order[i]] = i;
  CsrGraph out;
  out.offsets.resize(n + 1);
  out.targets.resize(graph.targets.size());
  out.lengths.resize(graph.lengths.size());
  out.offsets[0] = 0;
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t v = order[i];
    std::uint32_t at = out.offsets[i];
    for (std::uint32_t e = graph.offsets[v]; e < graph.offsets[v + 1]; ++e) {
      out.targets[at] = position[graph.targets[e]];
      out.lengths[at++] = graph.lengths[e];
    }
    out.offsets[i + 1] = at;
  }
  return out;
}

NearestSources nearestTwoSources(const CsrGraph& graph, const std::vector<std::uint32_t>& sources) {
  const std::size_t n = graph.numVertices();
  NearestSources out;
  out.at.assign(n, NearestSources::Labels{kNotQueued, kNotQueued, kInf, kInf});
  // Dial's buckets as in BucketDijkstra, label-correcting: a vertex is queued in the bucket of
  // its smallest changed label and passes both labels on when scanned.
  const BucketCircle circle = bucketCircle(graph);
  const double inv_width = circle.inv_width;
  std::vector<std::vector<std::uint32_t>> buckets(circle.count);
  const std::size_t mask = circle.count - 1;
  std::vector<std::uint32_t> queued(n, kNotQueued);
  std::size_t pending = 0;
  std::uint32_t current = 0;
  auto push = [&](std::uint32_t v, float d) {
    // A label re-sent from a vertex scanned late can fall before the current bucket; it
    // cannot improve anything there, but must not wrap around the circle.
    const std::uint32_t b =
        std::max(current, static_cast<std::uint32_t>(static_cast<double>(d) * inv_width));
    if (queued[v] != kNotQueued && queued[v] <= b)
      return; // already waiting in an earlier (or this) bucket; it will send both labels
    queued[v] = b;
    buckets[b & mask].push_back(v);
    ++pending;
  };
  // Offer the label (source s, distance d) to v; true if v's labels changed.
  auto offer = [&](std::uint32_t v, std::uint32_t s, float d) {
    if (s == out.at[v].first) {
      if (!(d < out.at[v].first_dist))
        return false;
      out.at[v].first_dist = d;
    } else if (s == out.at[v].second) {
      if (!(d < out.at[v].second_dist))
        return false;
      out.at[v].second_dist = d;
      if (out.at[v].second_dist < out.at[v].first_dist) {
        std::swap(out.at[v].first, out.at[v].second);
        std::swap(out.at[v].first_dist, out.at[v].second_dist);
      }
    } else if (d < out.at[v].first_dist) {
      out.at[v].second = out.at[v].first;
      out.at[v].second_dist = out.at[v].first_dist;
      out.at[v].first = s;
      out.at[v].first_dist = d;
    } else if (d < out.at[v].second_dist) {
      out.at[v].second = s;
      out.at[v].second_dist = d;
    } else {
      return false;
    }
    return true;
  };
  for (std::uint32_t i = 0; i < sources.size(); ++i)
    if (offer(sources[i], i, 0.0f))
      push(sources[i], 0.0f);
  for (; pending > 0; ++current) {
    std::vector<std::uint32_t>& bucket = buckets[current & mask];
    for (std::size_t i = 0; i < bucket.size(); ++i) {
      const std::uint32_t v = bucket[i];
      --pending;
      if (queued[v] != current)
        continue;
      queued[v] = kNotQueued;
      const std::uint32_t s1 = out.at[v].first, s2 = out.at[v].second;
      const float d1 = out.at[v].first_dist, d2 = out.at[v].second_dist;
      for (std::uint32_t e = graph.offsets[v]; e < graph.offsets[v + 1]; ++e) {
        const std::uint32_t t = graph.targets[e];
        const float w = graph.lengths[e];
        if (offer(t, s1, d1 + w))
          push(t, d1 + w);
        if (s2 != kNotQueued && offer(t, s2, d2 + w))
          push(t, d2 + w);
      }
    }
    bucket.clear();
  }
  return out;
}

} // namespace pcl_ncut_seg
