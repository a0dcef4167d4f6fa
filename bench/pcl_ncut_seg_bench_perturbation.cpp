/*
 * pcl_ncut_seg_bench_perturbation: how far noise and small displacements of the points move the
 * segmentation, for two known limitations (docs/limitations.md; docs/cad.md, "Known
 * limitations") whose goals are not reached yet. The tests assert what holds on these cases;
 * this program prints the figures that are still short of their goal. It is not a test.
 *
 *  - CAD mode on the generated parts of test/test_cad.cpp (cube, triangular and hexagonal
 *    prisms, L-shaped block, cylinder), clean and with Gaussian noise of 0.005 and 0.01 per
 *    coordinate: segments against faces, the Rand index against the faces and the smallest share
 *    of a face's points in its main segment. Goal: Rand index 0.95 and 90% of every face in a
 *    segment of its own (test_cad's CadShapesAtTheBar asserts it for the cases that reach it).
 *  - The generated hand of test/test_robustness.cpp (3,000 points, seed 9) moved away from the
 *    origin, where float rounding displaces its points: the Rand index against the unmoved
 *    hand's segmentation, with 6 segments asked for and with the threshold. Goal: 0.99 at an
 *    offset of 1e4. Beside it, the unmoved hand with a random jitter of up to 5e-4 per
 *    coordinate, the size of that rounding.
 *
 *   pcl_ncut_seg_bench_perturbation [--seeds N]
 *
 * --seeds N repeats both with the sampling seeds 1 to N (the hand: seed 9, then 1 to N-1).
 */
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include <shapes/cad_shapes.h>
#include <shapes/metrics.h>
#include <shapes/shapes.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <set>
#include <string>
#include <vector>

namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;
using pcl_ncut_seg::test::LabeledShape;
using pcl_ncut_seg::test::randIndex;

constexpr double kCadRandGoal = 0.95, kCadShareGoal = 0.90, kFarGoal = 0.99;

/** \brief Labels of a segmentation with the defaults: CAD mode, or the given number of segments
 * (0: the threshold). */
std::vector<int> segment(const Cloud::Ptr& cloud, bool cad, int num_segments,
                         std::size_t* count = nullptr) {
  pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
  seg.setInputCloud(cloud);
  seg.setCadMode(cad);
  if (num_segments > 0)
    seg.setNumberOfSegments(num_segments);
  std::vector<pcl::PointIndices> segments;
  seg.extract(segments);
  if (count)
    *count = segments.size();
  return pcl_ncut_seg::test::segmentsToLabels(segments, cloud->size());
}

/** \brief CAD mode on the cases of test_cad.cpp; returns how many miss the goal. */
int cadParts(int seeds) {
  std::printf("CAD mode, generated parts (goal: Rand index >= %.2f, every face >= %.0f%% in a "
              "segment of its own)\n",
              kCadRandGoal, 100 * kCadShareGoal);
  std::printf("%-17s %6s %6s %4s %5s %4s %10s %10s  %s\n", "part", "n", "noise", "seed", "faces",
              "t", "Rand index", "min share", "");
  int below = 0;
  const auto& cases = pcl_ncut_seg::test::cadCases();
  for (const auto& c : cases)
    for (int seed = 1; seed <= seeds; ++seed) {
      const LabeledShape shape = pcl_ncut_seg::test::makeCadShape(c.shape, c.n, seed, c.noise);
      std::size_t t = 0;
      const std::vector<int> labels = segment(shape.cloud, true, 0, &t);
      const double ri = randIndex(labels, shape.labels);
      const auto main = pcl_ncut_seg::test::mainSegments(labels, shape.labels, shape.num_parts);
      double min_share = 1.0;
      std::set<int> own;
      for (const auto& m : main) {
        min_share = std::min(min_share, m.share);
        own.insert(m.segment);
      }
      const bool shared = own.size() < main.size();
      const bool short_of_goal = ri < kCadRandGoal || min_share < kCadShareGoal || shared;
      below += short_of_goal;
      std::printf("%-17s %6zu %6.3f %4d %5d %4zu %10.4f %10.3f  %s%s\n", c.shape.c_str(), c.n,
                  c.noise, seed, shape.num_parts, t, ri, min_share,
                  shared ? "faces share a segment " : "", short_of_goal ? "below the goal" : "");
    }
  std::printf("%d of %d runs below the goal\n\n", below, static_cast<int>(cases.size()) * seeds);
  return below;
}

Cloud::Ptr shifted(const Cloud& in, double offset) {
  Cloud::Ptr out(new Cloud);
  for (const auto& p : in)
    out->push_back(pcl::PointXYZ(static_cast<float>(p.x + offset), static_cast<float>(p.y + offset),
                                 static_cast<float>(p.z + offset)));
  return out;
}

Cloud::Ptr jittered(const Cloud& in, double amplitude, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  Cloud::Ptr out(new Cloud);
  for (const auto& p : in)
    out->push_back(pcl::PointXYZ(static_cast<float>(p.x + u(rng)), static_cast<float>(p.y + u(rng)),
                                 static_cast<float>(p.z + u(rng))));
  return out;
}

/** \brief The hand far from the origin; returns whether seed 9 misses the goal at 1e4. */
bool farFromTheOrigin(int seeds) {
  std::printf("The hand (3,000 points) moved by an offset on every coordinate, and jittered at "
              "the origin: Rand index against the unmoved hand's segmentation (goal at 1e4, "
              "seed 9: >= %.2f)\n",
              kFarGoal);
  std::printf("%4s %-22s %13s %13s\n", "seed", "change", "6 segments", "threshold");
  std::vector<int> hand_seeds = {9};
  for (int s = 1; s < seeds; ++s)
    hand_seeds.push_back(s);
  bool short_of_goal = false;
  for (const int seed : hand_seeds) {
    const LabeledShape hand = pcl_ncut_seg::test::makeHand(3000, seed);
    const std::vector<int> six = segment(hand.cloud, false, 6);
    const std::vector<int> threshold = segment(hand.cloud, false, 0);
    auto row = [&](const std::string& what, const Cloud::Ptr& cloud) {
      const double a = randIndex(segment(cloud, false, 6), six);
      const double b = randIndex(segment(cloud, false, 0), threshold);
      std::printf("%4d %-22s %13.4f %13.4f\n", seed, what.c_str(), a, b);
      return a;
    };
    for (const double offset : {10.0, 100.0, 300.0, 1e3, 1e4, 1e5}) {
      char what[64];
      std::snprintf(what, sizeof what, "offset %g", offset);
      const double ri = row(what, shifted(*hand.cloud, offset));
      if (seed == 9 && offset == 1e4)
        short_of_goal = ri < kFarGoal;
    }
    for (std::uint64_t j = 1; j <= 5; ++j)
      row("jitter 5e-4, seed " + std::to_string(j), jittered(*hand.cloud, 5e-4, j));
  }
  std::printf("\n");
  return short_of_goal;
}

} // namespace

int main(int argc, char** argv) {
  int seeds = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--seeds" && i + 1 < argc && std::atoi(argv[i + 1]) >= 1) {
      seeds = std::atoi(argv[++i]);
    } else {
      std::printf("Usage: %s [--seeds N]\n"
                  "The segmentation under noise (CAD mode on generated parts) and under small\n"
                  "displacements (a generated hand far from the origin, or jittered), against\n"
                  "the goals the tests do not assert yet.\n"
                  "  --seeds N  the sampling seeds 1 to N (default 1, the tests' cases)\n",
                  argv[0]);
      return a == "-h" || a == "--help" ? 0 : 1;
    }
  }
  const int cad_below = cadParts(seeds);
  const bool far_below = farFromTheOrigin(seeds);
  std::printf("Below the goal: %d CAD runs; the hand at 1e4 %s\n", cad_below,
              far_below ? "yes" : "no");
  return 0;
}
