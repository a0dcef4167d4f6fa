#include "cli/output.h"

#include "cli/console.h"
#include "cli/paths.h"

#include <pcl/io/pcd_io.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <fstream>
#include <vector>

#include <sys/stat.h>
#include <unistd.h>

namespace pcl_ncut_seg {
namespace tool {

AtomicFile::~AtomicFile() {
  if (!tmp_.empty())
    std::remove(tmp_.c_str());
}

bool AtomicFile::open(const std::string& path) {
  path_ = path;
  const std::string dir = directoryOf(path);
  std::string tmpl = (dir == "/" ? "" : dir) + "/." + baseName(path) + ".XXXXXX";
  std::vector<char> buffer(tmpl.begin(), tmpl.end());
  buffer.push_back('\0');
  const int fd = ::mkstemp(buffer.data());
  if (fd < 0) {
    fail("cannot write '" + path + "': " + std::strerror(errno));
    return false;
  }
  // mkstemp creates the file 0600; give the result the usual permissions.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::fchmod(fd, 0666 & ~mask);
  ::close(fd);
  tmp_ = buffer.data();
  return true;
}

bool AtomicFile::commit() {
  if (std::rename(tmp_.c_str(), path_.c_str()) != 0) {
    fail("cannot write '" + path_ + "': " + std::strerror(errno));
    return false;
  }
  tmp_.clear();
  return true;
}

bool writePcd(AtomicFile& file, const pcl::PCLPointCloud2& blob, PcdEncoding encoding,
              const SensorPose& sensor) {
  int status = -1;
  {
    SilencePcl silence;
    try {
      pcl::PCDWriter writer;
      if (encoding == PcdEncoding::Binary) {
        status = writer.writeBinary(file.temporaryPath(), blob, sensor.origin, sensor.orientation);
      } else {
        // 9 significant digits read every float back exactly, 17 every double.
        const bool doubles =
            std::any_of(blob.fields.begin(), blob.fields.end(), [](const pcl::PCLPointField& f) {
              return f.datatype == pcl::PCLPointField::FLOAT64;
            });
        status = writer.writeASCII(file.temporaryPath(), blob, sensor.origin, sensor.orientation,
                                   doubles ? 17 : 9);
      }
    } catch (const std::exception&) {
      status = -1;
    }
  }
  if (status < 0) {
    fail("cannot write '" + file.path() + "'");
    return false;
  }
  return true;
}

bool writeText(AtomicFile& file, const std::string& contents) {
  std::ofstream out(file.temporaryPath(), std::ios::binary | std::ios::trunc);
  out << contents;
  if (!out.flush()) {
    fail("cannot write '" + file.path() + "'");
    return false;
  }
  return true;
}

} // namespace tool
} // namespace pcl_ncut_seg
