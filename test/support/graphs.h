// Small graphs for the phase-by-phase tests.
#pragma once

#include "core/cut/supernode_graph.h"
#include "core/graph/csr_graph.h"
#include "core/supernodes/supernodes.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <tuple>
#include <vector>

namespace pcl_ncut_seg {
namespace test {

/// An undirected graph from (a, b, length) triples.
inline CsrGraph graphFromEdges(std::size_t n,
                               const std::vector<std::tuple<int, int, float>>& edges) {
  std::vector<std::vector<std::pair<std::uint32_t, float>>> rows(n);
  for (const auto& [a, b, w] : edges) {
    rows[a].emplace_back(b, w);
    rows[b].emplace_back(a, w);
  }
  CsrGraph g;
  g.offsets.push_back(0);
  for (auto& row : rows) {
    std::sort(row.begin(), row.end());
    for (const auto& [t, w] : row) {
      g.targets.push_back(t);
      g.lengths.push_back(w);
    }
    g.offsets.push_back(static_cast<std::uint32_t>(g.targets.size()));
  }
  return g;
}

/// A graph from each vertex's neighbours (both directions listed), each edge as long as the
/// distance between its points (xyz: 3 floats per vertex).
inline CsrGraph graphFromAdjacency(std::vector<std::vector<std::uint32_t>> adj,
                                   const std::vector<float>& xyz) {
  CsrGraph g;
  g.offsets.push_back(0);
  for (std::uint32_t v = 0; v < adj.size(); ++v) {
    std::sort(adj[v].begin(), adj[v].end());
    for (std::uint32_t w : adj[v]) {
      g.targets.push_back(w);
      float d = 0;
      for (int k = 0; k < 3; ++k)
        d += (xyz[3 * v + k] - xyz[3 * w + k]) * (xyz[3 * v + k] - xyz[3 * w + k]);
      g.lengths.push_back(std::sqrt(d));
    }
    g.offsets.push_back(static_cast<std::uint32_t>(g.targets.size()));
  }
  return g;
}

/// Every one of n points in one supernode (a local maximum at point 0).
inline Supernodes oneSupernode(std::size_t n) {
  Supernodes sn;
  sn.label.assign(n, 0);
  sn.origin = {0};
  sn.at_saddle = {false};
  sn.parent = {kNone};
  sn.children = {{}};
  return sn;
}

/// Three supernodes: s0 and s1 terminate at the saddle where s2 was created (Fig. 6).
inline Supernodes threeSupernodes() {
  Supernodes sn;
  sn.label = {0, 1, 2};
  sn.origin = {0, 1, 2};
  sn.at_saddle = {false, false, true};
  sn.parent = {2, 2, kNone};
  sn.children = {{}, {}, {0, 1}};
  return sn;
}

/// The weight of the edge a-b (either way round) of a supernode graph, or -1 if there is none.
inline double edgeWeight(const WeightedGraph& g, std::uint32_t a, std::uint32_t b) {
  for (const auto& e : g.edges)
    if ((e.a == a && e.b == b) || (e.a == b && e.b == a))
      return e.w;
  return -1;
}

/// Members m_0..m_{l-1} (vertices l..2l-1) with representative edges of weight 1 and the given
/// member-member edges (member indices 0..l-1).
inline WeightedGraph memberGraph(std::size_t l,
                                 const std::vector<WeightedGraph::Edge>& member_edges) {
  const auto member = [l](std::uint32_t s) { return static_cast<std::uint32_t>(l + s); };
  WeightedGraph g;
  g.num_vertices = 2 * l;
  for (std::uint32_t i = 0; i < l; ++i)
    g.edges.push_back({i, member(i), 1.0});
  for (const auto& e : member_edges)
    g.edges.push_back({member(e.a), member(e.b), e.w});
  return g;
}

/// n random points in the unit cube and their brute-force k nearest neighbours.
inline std::vector<float> randomPoints(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<float> xyz(3 * n);
  for (float& v : xyz)
    v = static_cast<float>(rng() % 100000) / 100000.0f;
  return xyz;
}

inline std::vector<std::uint32_t> bruteForceKnn(const std::vector<float>& xyz, std::size_t k) {
  const std::size_t n = xyz.size() / 3;
  std::vector<std::uint32_t> knn(n * k);
  for (std::size_t p = 0; p < n; ++p) {
    std::vector<std::pair<float, std::uint32_t>> d;
    for (std::size_t q = 0; q < n; ++q) {
      if (q == p)
        continue;
      float s = 0;
      for (int c = 0; c < 3; ++c)
        s += (xyz[3 * p + c] - xyz[3 * q + c]) * (xyz[3 * p + c] - xyz[3 * q + c]);
      d.emplace_back(s, static_cast<std::uint32_t>(q));
    }
    std::sort(d.begin(), d.end());
    for (std::size_t j = 0; j < k; ++j)
      knn[p * k + j] = d[j].second;
  }
  return knn;
}

/// All-pairs shortest paths (Floyd-Warshall), the brute-force reference for geodesics.
inline std::vector<double> allPairsShortestPaths(const CsrGraph& g) {
  const std::size_t n = g.numVertices();
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> d(n * n, inf);
  for (std::size_t v = 0; v < n; ++v) {
    d[v * n + v] = 0;
    for (std::uint32_t e = g.offsets[v]; e < g.offsets[v + 1]; ++e)
      d[v * n + g.targets[e]] = std::min<double>(d[v * n + g.targets[e]], g.lengths[e]);
  }
  for (std::size_t k = 0; k < n; ++k)
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j)
        d[i * n + j] = std::min(d[i * n + j], d[i * n + k] + d[k * n + j]);
  return d;
}

} // namespace test
} // namespace pcl_ncut_seg
