/*
 * Fuzz target for pcl::SupernodeNCutSegmentation::extract(): the input bytes become a small
 * cloud (up to 256 points, some non-finite, many coincident or coplanar by construction), the
 * parameters and optionally indices. Checks the invariants a caller relies on and aborts when
 * one fails:
 *   - an empty result exactly when the input is bad (no finite selected point, an index out
 *     of range), else every finite selected point in exactly one segment and no other point
 *     in any; indices in range, segments non-empty, sorted, ordered by their first index;
 *   - at most K segments when K are asked for;
 *   - the labelled cloud agrees with the segments;
 *   - a second extract() after changing only cut parameters (the cheap path) is a partition too;
 *   - the same labels with another number of threads.
 * The (up to two) bytes after the points choose the options beyond the paper (bridging, concave
 * creases, flat patches, the threshold rule, the segment cap, joining touching supernodes,
 * exact centrality, CAD mode), flag 0x80 the short-cut rule's, the samples byte's high bits the
 * boundary refinement's and the crease splits'; zeros, as in most of the corpus, keep the
 * defaults.
 * Built with libFuzzer by -DPCL_NCUT_SEG_BUILD_FUZZERS=ON (clang); replay_main.cpp runs a
 * corpus through it without libFuzzer (the FuzzCorpus test).
 */
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include <pcl/common/point_tests.h>
#include <pcl/console/print.h>

#include <climits>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <optional>
#include <vector>

namespace {

/** Reads the fuzzer's bytes front to back; zeros once they run out. */
class Bytes {
public:
  Bytes(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  std::uint8_t next() { return pos_ < size_ ? data_[pos_++] : 0; }
  std::size_t left() const { return size_ - pos_; }

private:
  const std::uint8_t* data_;
  std::size_t size_, pos_ = 0;
};

[[noreturn]] void fail(const char* what) {
  std::fprintf(stderr, "fuzz_extract: invariant broken: %s\n", what);
  std::abort();
}

#define FUZZ_CHECK(condition)                                                                      \
  do {                                                                                             \
    if (!(condition))                                                                              \
      fail(#condition);                                                                            \
  } while (0)

using Seg = pcl::SupernodeNCutSegmentation<pcl::PointXYZ>;

/** Checks the partition; returns each point's segment (-1 for none). */
std::vector<int> checkPartition(const std::vector<pcl::PointIndices>& segments,
                                const std::vector<char>& wanted) {
  std::vector<int> label(wanted.size(), -1);
  int previous_first = -1;
  for (std::size_t s = 0; s < segments.size(); ++s) {
    const auto& idx = segments[s].indices;
    FUZZ_CHECK(!idx.empty());
    FUZZ_CHECK(idx.front() > previous_first);
    previous_first = idx.front();
    for (std::size_t j = 0; j < idx.size(); ++j) {
      FUZZ_CHECK(idx[j] >= 0 && static_cast<std::size_t>(idx[j]) < wanted.size());
      FUZZ_CHECK(j == 0 || idx[j] > idx[j - 1]);
      FUZZ_CHECK(label[idx[j]] < 0); // in one segment only
      label[idx[j]] = static_cast<int>(s);
    }
  }
  for (std::size_t i = 0; i < wanted.size(); ++i)
    FUZZ_CHECK((label[i] >= 0) == (wanted[i] != 0));
  return label;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool quiet = [] {
    pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
    return true;
  }();
  (void)quiet;
  Bytes in(data, size);

  // Parameters: 14 bytes.
  const std::uint8_t flags = in.next();
  static const double kPositive[] = {1e-300, 1e-3, 0.1, 0.5, 1, 2, 10, 1e3, 1e300};
  static const double kThreshold[] = {0, 1e-3, 0.02, 0.1, 0.5, 1, 10, 1e300};
  const int k = 2 + in.next() % 15;
  // The samples byte's low 3 bits; its high 5 bits set the boundary refinement and the crease
  // splits (0 keeps the defaults).
  const std::uint8_t samples_byte = in.next();
  const int samples = samples_byte % 8;
  const int later_options = samples_byte >> 3;
  const float crossing = in.next() / 255.0f, area = in.next() / 255.0f, height = in.next() / 255.0f;
  const double beta = kPositive[in.next() % 9], alpha1 = kPositive[in.next() % 9],
               alpha2 = kPositive[in.next() % 9];
  const double threshold = kThreshold[in.next() % 8];
  const int segments_wanted = (flags & 1) ? 1 + in.next() % 9 : (in.next(), 0);
  // The analysis' resolution: 0 the default, 255 off, else 101-354 points (subsampling).
  const std::uint8_t max_points_byte = in.next();
  const unsigned threads = 1 + in.next() % 3;
  // Scale 1e-6 .. 1e6 and an offset of up to 1e4: coordinates stay far from overflow.
  const int scale_exp = static_cast<int>(in.next() % 13) - 6;
  const double scale = std::pow(10.0, scale_exp);
  const double offset = (flags & 0x10) ? 1e4 : 0.0;

  // Points: 3 bytes each, a small integer grid (so coincident, collinear and coplanar points
  // are common); -128 is NaN and 127 infinity.
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  while (in.left() >= 3 && cloud->size() < 256) {
    float xyz[3];
    for (float& c : xyz) {
      const auto b = static_cast<std::int8_t>(in.next());
      c = b == -128  ? std::numeric_limits<float>::quiet_NaN()
          : b == 127 ? std::numeric_limits<float>::infinity()
                     : static_cast<float>(b * scale + offset);
    }
    cloud->push_back(pcl::PointXYZ(xyz[0], xyz[1], xyz[2]));
  }
  const std::size_t n = cloud->size();
  const std::uint8_t options1 = in.next(), options2 = in.next();

  // Indices (flag 0x20): every point whose position is odd or divisible by 3, some twice,
  // and one out of range with flag 0x40.
  pcl::IndicesPtr indices;
  bool out_of_range = false;
  if (flags & 0x20) {
    indices.reset(new pcl::Indices);
    for (std::size_t i = 0; i < n; ++i)
      if (i % 2 == 1 || i % 3 == 0) {
        indices->push_back(static_cast<int>(i));
        if (i % 5 == 0)
          indices->push_back(static_cast<int>(i));
      }
    if (flags & 0x40) {
      indices->push_back(static_cast<int>(n));
      out_of_range = true;
    }
  }
  std::vector<char> wanted(n, 0);
  for (std::size_t i = 0; i < n; ++i)
    wanted[i] = !indices && pcl::isXYZFinite((*cloud)[i]);
  if (indices)
    for (int i : *indices)
      if (static_cast<std::size_t>(i) < n && pcl::isXYZFinite((*cloud)[i]))
        wanted[i] = 1;
  std::size_t num_wanted = 0;
  for (char w : wanted)
    num_wanted += w;
  const bool bad_input = out_of_range || num_wanted == 0;

  auto configure = [&](Seg& seg, unsigned num_threads) {
    seg.setInputCloud(cloud);
    if (indices)
      seg.setIndices(indices);
    seg.setNumberOfNeighbours(k);
    seg.setNumberOfSamples(samples ? std::optional<int>(samples) : std::nullopt); // 0: auto
    seg.setCrossingFraction(crossing);
    seg.setAreaFraction(area);
    seg.setHeightFraction(height);
    seg.setBeta(beta);
    seg.setAlpha1(alpha1);
    seg.setAlpha2(alpha2);
    seg.setThreshold(threshold);
    if (segments_wanted > 0)
      seg.setNumberOfSegments(segments_wanted);
    if (max_points_byte == 255)
      seg.setMaxPoints(std::nullopt);
    else if (max_points_byte > 0)
      seg.setMaxPoints(100 + max_points_byte);
    seg.setNormalizeWidth(flags & 2);
    if (!(flags & 4)) // else the default, every touching pair
      seg.setAdjacency(pcl_ncut_seg::Adjacency::Saddles);
    seg.setNumberOfThreads(num_threads);
    // Options beyond the paper: 2 bits or 1 bit each, 0 keeps the default (nullopt: off).
    using Off = std::optional<double>;
    static const Off kRadii[] = {0, Off(), 0.5, 1e3}, kWeight[] = {0, Off(), 0.01, 1e3},
                     kElongation[] = {0, Off(), 1e-3, 10};
    static const int kMaxSegments[] = {0, 1, 2, INT_MAX};
    if (options1 & 3)
      seg.setBridgeGap(kRadii[options1 & 3]);
    if ((options1 >> 2) & 3)
      seg.setConcavityWeight(kWeight[(options1 >> 2) & 3]);
    if ((options1 >> 4) & 3)
      seg.setFlatElongation(kElongation[(options1 >> 4) & 3]);
    if ((options1 & 0x40) && segments_wanted == 0) // the threshold rule, unless a count
      seg.setStoppingRule(pcl_ncut_seg::StoppingRule::Threshold);
    if (options1 & 0x80)
      seg.setCadMode(true);
    if (options2 & 3)
      seg.setMaxSegments(kMaxSegments[options2 & 3]);
    if (((options2 >> 4) & 3) == 3) {
      if (seg.getAdjacency() == pcl_ncut_seg::Adjacency::All)
        seg.setAdjacency(pcl_ncut_seg::Adjacency::Trees);
    } else if (((options2 >> 4) & 3) == 1)
      seg.setAdjacency(pcl_ncut_seg::Adjacency::Saddles);
    if (options2 & 0x80)
      seg.setCentralityMode(pcl_ncut_seg::CentralityMode::Exact);
    static const Off kBand[] = {0, Off(), 0.5, 1e-3}, kCreaseSplit[] = {0, Off(), 1e-6, 1e3};
    if (later_options & 3)
      seg.setBoundaryBand(kBand[later_options & 3]);
    if (later_options & 4)
      seg.setRimMerge(std::nullopt);
    if ((later_options >> 3) & 3)
      seg.setCreaseSplit(kCreaseSplit[(later_options >> 3) & 3]);
    // The short-cut stopping rule at its extremes.
    if (flags & 0x80) {
      seg.setNeckBound(1e300);
    }
  };

  Seg seg;
  configure(seg, threads);
  std::vector<pcl::PointIndices> segments(3);
  seg.extract(segments);
  if (bad_input) {
    FUZZ_CHECK(segments.empty());
    FUZZ_CHECK(seg.getLabeledCloud()->empty());
    return 0;
  }
  FUZZ_CHECK(!segments.empty());
  const std::vector<int> label = checkPartition(segments, wanted);
  if (segments_wanted > 0)
    FUZZ_CHECK(segments.size() <= static_cast<std::size_t>(segments_wanted));
  const auto labeled = seg.getLabeledCloud();
  FUZZ_CHECK(labeled->size() == n);
  for (std::size_t i = 0; i < n; ++i)
    FUZZ_CHECK(static_cast<int>((*labeled)[i].label) == label[i] + 1);

  // The same labels with one thread.
  if (threads != 1) {
    Seg single;
    configure(single, 1);
    std::vector<pcl::PointIndices> again;
    single.extract(again);
    FUZZ_CHECK(again.size() == segments.size());
    for (std::size_t s = 0; s < again.size(); ++s)
      FUZZ_CHECK(again[s].indices == segments[s].indices);
  }

  // The cheap path: change only cut parameters and extract again.
  if (segments_wanted > 0) // from the count to the default rule, or the other way
    seg.setStoppingRule(pcl_ncut_seg::Parameters().stopping.rule);
  else
    seg.setNumberOfSegments(3);
  seg.setThreshold(kThreshold[(flags >> 5) % 8]);
  seg.setAlpha2(kPositive[flags % 9]);
  seg.setFlatElongation(options1 & 0x20 ? std::optional<double>() : 0.2);
  seg.setNeckBound(flags & 0x08 ? 1e-3 : 0.5);
  seg.setRimMerge(later_options & 4 ? std::optional<double>(170.0) : std::nullopt);
  seg.extract(segments);
  FUZZ_CHECK(!segments.empty());
  checkPartition(segments, wanted);
  return 0;
}
