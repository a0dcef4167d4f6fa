/*
 * Growth check: one SupernodeNCutSegmentation object runs extract() many times on changing
 * inputs (shapes, sizes, NaN points, indices, bad input, analysis and cut parameters), as a
 * long-running robot process would. Heap in use (glibc mallinfo2) and resident memory are
 * measured right after the same reference input at the start, every 100 iterations and at the
 * end, so that the retained state is alike and a difference is growth.
 *
 *   pcl_ncut_seg_leak_check [iterations] [allowed heap growth in KiB]
 *
 * Exits 1 when the heap in use grew by more than allowed (default 128 KiB). scripts/leak_check.sh
 * builds and runs it.
 */
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>
#include <shapes/shapes.h>

#include <malloc.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

using Seg = pcl::SupernodeNCutSegmentation<pcl::PointXYZ>;
using Cloud = pcl::PointCloud<pcl::PointXYZ>;

namespace {

struct Memory {
  double heap_kib, rss_kib;
};

Memory measure() {
  const struct mallinfo2 mi = mallinfo2();
  long pages = 0, resident = 0;
  std::ifstream("/proc/self/statm") >> pages >> resident;
  return {static_cast<double>(mi.uordblks + mi.hblkhd) / 1024.0,
          static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / 1024.0};
}

/** Input number i: a different shape, size, seed and set of parameters each time. */
void prepare(Seg& seg, std::size_t i) {
  static const char* shapes[] = {"hand", "quadruped", "dumbbell", "two_objects"};
  static const std::size_t sizes[] = {600, 1500, 2500};
  const std::size_t n = sizes[i % 3];
  Cloud::Ptr cloud = pcl_ncut_seg::test::makeShape(shapes[i % 4], n, 1000 + i).cloud;
  switch (i % 7) {
  case 0: // NaN points
    for (std::size_t j = 0; j < cloud->size(); j += 17)
      (*cloud)[j].x = std::numeric_limits<float>::quiet_NaN();
    break;
  case 1: { // indices, some out of range every other time: an error
    pcl::IndicesPtr idx(new pcl::Indices);
    for (std::size_t j = 0; j < cloud->size(); j += 2)
      idx->push_back(static_cast<int>(j));
    if (i % 2)
      idx->push_back(static_cast<int>(cloud->size()));
    seg.setInputCloud(cloud);
    seg.setIndices(idx);
    return;
  }
  case 2: // an empty cloud: an error
    cloud.reset(new Cloud);
    break;
  case 3: // exact copies
    *cloud += *cloud;
    break;
  default:
    break;
  }
  seg.setInputCloud(cloud);
  seg.setIndices(pcl::IndicesPtr()); // all points
  seg.setNumberOfNeighbours(8 + static_cast<int>(i % 5));
  if (i % 9 == 0)
    seg.setStoppingRule(pcl_ncut_seg::Parameters().stopping.rule);
  else
    seg.setNumberOfSegments(static_cast<int>(i % 9));
}

void extractAndUse(Seg& seg) {
  std::vector<pcl::PointIndices> segments;
  seg.extract(segments);
  // The other outputs too, as a caller would use them.
  (void)seg.getLabeledCloud();
  (void)seg.getColoredCloud();
  (void)seg.getCentrality();
  // The cheap path: only cut parameters change.
  seg.setThreshold(seg.getThreshold() == 0.02 ? 0.05 : 0.02);
  seg.extract(segments);
}

} // namespace

int main(int argc, char** argv) {
  const std::size_t iterations = argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 500;
  const double allowed_kib = argc > 2 ? std::strtod(argv[2], nullptr) : 128.0;
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS); // bad inputs are on purpose

  const Cloud::Ptr reference = pcl_ncut_seg::test::makeHand(2000, 1).cloud;
  auto runReference = [&](Seg& seg) {
    seg.setInputCloud(reference);
    seg.setIndices(pcl::IndicesPtr());
    seg.setNumberOfNeighbours(10);
    seg.setNumberOfSegments(6);
    seg.setThreshold(0.02);
    extractAndUse(seg);
  };

  Seg seg;
  // Warm-up: every kind of input once, so that lazily allocated pools exist before measuring.
  for (std::size_t i = 0; i < 14; ++i) {
    prepare(seg, i);
    extractAndUse(seg);
  }
  runReference(seg);
  const Memory start = measure();
  std::printf("leak_check: %zu iterations; start: heap in use %.0f KiB, resident %.0f KiB\n",
              iterations, start.heap_kib, start.rss_kib);
  for (std::size_t i = 0; i < iterations; ++i) {
    prepare(seg, 14 + i);
    extractAndUse(seg);
    if ((i + 1) % 100 == 0 && i + 1 < iterations) {
      runReference(seg);
      const Memory m = measure();
      std::printf("leak_check: after %5zu: heap in use %.0f KiB, resident %.0f KiB\n", i + 1,
                  m.heap_kib, m.rss_kib);
      std::fflush(stdout);
    }
  }
  runReference(seg);
  const Memory end = measure();
  std::printf("leak_check: end:   heap in use %.0f KiB, resident %.0f KiB\n", end.heap_kib,
              end.rss_kib);
  const double growth = end.heap_kib - start.heap_kib;
  std::printf("leak_check: heap growth %.1f KiB (allowed %.0f), resident growth %.0f KiB\n", growth,
              allowed_kib, end.rss_kib - start.rss_kib);
  if (growth > allowed_kib) {
    std::printf("leak_check: FAILED: the heap grew\n");
    return 1;
  }
  std::printf("leak_check: passed\n");
  return 0;
}
