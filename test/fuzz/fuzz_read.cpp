/*
 * Fuzz target for the tools' one reader, files::readPointFile() (kit/files/point_file.h): the
 * first byte chooses the format (.pcd, .ply, .npy, .off, .obj, by its value modulo 5), the rest
 * is the file. Checks what every front end relies on and aborts when it fails:
 *   - a refusal is one line that names the file, and leaves nothing read;
 *   - a cloud read has WIDTH x HEIGHT points, data of point_step bytes each, fields inside the
 *     point, x, y and z among them, at least one point with finite x, y and z;
 *   - a mesh read has faces, and one point per face centroid;
 *   - reading the same file twice gives the same points.
 * libFuzzer's -rss_limit_mb and -timeout catch unbounded allocation and endless loops.
 * Built with libFuzzer by -DPCL_NCUT_SEG_BUILD_FUZZERS=ON (clang); replay_main.cpp runs a corpus
 * through it without libFuzzer (the FuzzReadCorpus test).
 */
#include "files/point_file.h"
#include "files/values.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include <unistd.h>

namespace {

[[noreturn]] void fail(const char* what) {
  std::fprintf(stderr, "fuzz_read: %s\n", what);
  std::abort();
}

/** A file of this process with the format's extension, rewritten for each input. */
std::string writeInput(const std::uint8_t* data, std::size_t size, const char* ext) {
  const std::string path = "/tmp/pcl_ncut_seg_fuzz_read_" + std::to_string(::getpid()) + ext;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f || (size > 0 && std::fwrite(data, 1, size, f) != size) || std::fclose(f) != 0)
    fail("cannot write the input file");
  return path;
}

void checkCloud(const pcl_ncut_seg::files::PointFile& file) {
  const pcl::PCLPointCloud2& blob = file.blob;
  const std::size_t n = std::size_t(blob.width) * blob.height;
  if (n == 0 || !file.cloud || file.cloud->size() != n || blob.data.size() != n * blob.point_step)
    fail("a cloud read whose sizes disagree");
  for (const pcl::PCLPointField& f : blob.fields)
    if (f.offset + pcl_ncut_seg::files::typeSize(f.datatype) * f.count > blob.point_step)
      fail("a field outside its point");
  std::size_t finite = 0;
  for (const pcl::PointXYZ& p : *file.cloud)
    finite += std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
  if (finite == 0)
    fail("a cloud read without a finite point");
  if (file.mesh && (file.num_faces == 0 || n > file.num_faces))
    fail("a mesh read without faces, or with more centroids than faces");
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const char* const kExtensions[] = {".pcd", ".ply", ".npy", ".off", ".obj"};
  if (size == 0)
    return 0;
  const std::string path = writeInput(data + 1, size - 1, kExtensions[data[0] % 5]);
  pcl_ncut_seg::files::PointFile file, again;
  std::string error, error_again;
  const bool read = pcl_ncut_seg::files::readPointFile(path, {}, file, error);
  if (read != pcl_ncut_seg::files::readPointFile(path, {}, again, error_again) ||
      error != error_again)
    fail("the same file read twice, two outcomes");
  if (!read) {
    if (error.empty() || error.find('\n') != std::string::npos ||
        error.find(path) == std::string::npos)
      fail("a refusal that is not one line naming the file");
    if (file.cloud || !file.blob.data.empty())
      fail("a refusal that leaves points");
    return 0;
  }
  checkCloud(file);
  if (file.blob.data != again.blob.data)
    fail("the same file read twice, two clouds");
  return 0;
}
