#include "files/npy_reader.h"

#include "files/values.h"

#include <algorithm>
#include <cstring>
#include <vector>

namespace pcl_ncut_seg {
namespace files {

namespace {

constexpr std::size_t kMaxHeaderBytes = 1 << 16;

/** The text after 'key': in the header's dict, or npos. */
std::size_t valueOf(const std::string& dict, const char* key) {
  const std::string quoted_key = std::string("'") + key + "'";
  std::size_t at = dict.find(quoted_key);
  if (at == std::string::npos)
    return at;
  at = dict.find_first_not_of(" ", at + quoted_key.size());
  if (at == std::string::npos || dict[at] != ':')
    return std::string::npos;
  return dict.find_first_not_of(" ", at + 1);
}

struct ArrayHeader {
  std::uint8_t type = 0; ///< PCL's field type of the elements
  bool swap = false;     ///< big-endian data
  bool fortran = false;
  std::vector<std::uint64_t> shape;
  std::uint64_t data_offset = 0;
};

bool parseDescr(const std::string& dict, ArrayHeader& a, std::string& error) {
  const std::size_t at = valueOf(dict, "descr");
  const std::size_t end = at == std::string::npos ? at : dict.find('\'', at + 1);
  const std::string d = end == std::string::npos ? "" : dict.substr(at + 1, end - at - 1);
  using F = pcl::PCLPointField;
  if (d.size() == 3 && (d[0] == '<' || d[0] == '>' || d[0] == '|' || d[0] == '=')) {
    a.swap = d[0] == '>';
    const char kind = d[1], size = d[2];
    if (kind == 'f')
      a.type = size == '4' ? F::FLOAT32 : size == '8' ? F::FLOAT64 : 0;
    else if (kind == 'i' || kind == 'u') {
      const bool s = kind == 'i';
      a.type = size == '1'   ? (s ? F::INT8 : F::UINT8)
               : size == '2' ? (s ? F::INT16 : F::UINT16)
               : size == '4' ? (s ? F::INT32 : F::UINT32)
               : size == '8' ? (s ? F::INT64 : F::UINT64)
                             : 0;
    }
  }
  if (a.type == 0)
    error = "an .npy of points holds numbers (float32, float64 or integers), not " +
            quoted(d.data(), d.data() + d.size());
  return a.type != 0;
}

bool parseShape(const std::string& dict, ArrayHeader& a, std::string& error) {
  const std::size_t at = valueOf(dict, "shape");
  const std::size_t end = at == std::string::npos ? at : dict.find(')', at);
  bool ok = end != std::string::npos && dict[at] == '(';
  if (ok)
    for (std::string n : words(dict.data() + at + 1, dict.data() + end)) {
      n.erase(std::remove(n.begin(), n.end(), ','), n.end());
      std::uint64_t v = 0;
      ok = ok && parseCount(n, v);
      a.shape.push_back(v);
    }
  const std::size_t fortran = valueOf(dict, "fortran_order");
  ok = ok && fortran != std::string::npos;
  a.fortran = ok && dict.compare(fortran, 4, "True") == 0;
  ok = ok && (a.fortran || dict.compare(fortran, 5, "False") == 0);
  if (!ok)
    error = "its header has no shape or fortran_order";
  else if ((a.shape.size() != 2 && a.shape.size() != 3) || a.shape.back() != 3) {
    std::string shape;
    for (std::uint64_t v : a.shape)
      shape += (shape.empty() ? "" : ", ") + std::to_string(v);
    error = "an .npy of points must be (N, 3) or (H, W, 3), not (" + shape + ")";
    ok = false;
  }
  return ok;
}

bool readHeader(const FileBytes& file, ArrayHeader& a, std::string& error) {
  unsigned char start[12];
  if (file.size() < 10 || !file.read(0, 10, start, error) ||
      std::memcmp(start, "\x93NUMPY", 6) != 0 || start[6] < 1 || start[6] > 3) {
    error = "no \\x93NUMPY header of version 1, 2 or 3";
    return false;
  }
  std::uint64_t length = start[8] | (start[9] << 8), offset = 10;
  if (start[6] > 1) {
    if (!file.read(0, 12, start, error))
      return false;
    length = start[8] | (start[9] << 8) | (std::uint64_t(start[10]) << 16) |
             (std::uint64_t(start[11]) << 24);
    offset = 12;
  }
  std::string dict(static_cast<std::size_t>(std::min<std::uint64_t>(length, kMaxHeaderBytes)),
                   '\0');
  if (length > kMaxHeaderBytes || !file.read(offset, dict.size(), dict.data(), error)) {
    error = "its header of " + std::to_string(length) + " bytes is cut short";
    return false;
  }
  a.data_offset = offset + length;
  return parseDescr(dict, a, error) && parseShape(dict, a, error);
}

} // namespace

bool readNpy(const FileBytes& file, pcl::PCLPointCloud2& blob, std::string& error) {
  blob = pcl::PCLPointCloud2();
  ArrayHeader a;
  if (!readHeader(file, a, error))
    return false;
  const std::uint64_t height = a.shape.size() == 3 ? a.shape[0] : 1;
  const std::uint64_t width = a.shape.size() == 3 ? a.shape[1] : a.shape[0];
  const std::size_t size = typeSize(a.type);
  const std::uint64_t available = file.size() - std::min(file.size(), a.data_offset);
  if (width > UINT32_MAX || height > UINT32_MAX ||
      (width > 0 && height > available / size / 3 / width)) {
    error =
        "the .npy's data holds fewer than its " + std::to_string(width * height) + " x 3 values";
    return false;
  }
  const std::size_t n = static_cast<std::size_t>(width * height);
  std::vector<std::uint8_t> raw(n * 3 * size);
  if (!file.read(a.data_offset, raw.size(), raw.data(), error))
    return false;
  blob = xyzCloud(static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t c = 0; c < 3; ++c) {
      // Fortran order: (h, w, c) at h + H (w + W c); C order: at 3 (h W + w) + c.
      const std::size_t h = i / width, w = i % width;
      std::uint8_t* v = raw.data() + (a.fortran ? c * n + h + height * w : 3 * i + c) * size;
      if (a.swap)
        std::reverse(v, v + size);
      const float value = valueAsFloat(v, a.type);
      std::memcpy(blob.data.data() + 12 * i + 4 * c, &value, 4);
    }
  return true;
}

} // namespace files
} // namespace pcl_ncut_seg
