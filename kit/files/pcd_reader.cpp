#include "files/pcd_reader.h"

#include "files/values.h"

#include <pcl/io/lzf.h>

#include <cstring>
#include <map>
#include <vector>

namespace pcl_ncut_seg {
namespace files {

namespace {

constexpr std::size_t kMaxHeaderBytes = 1 << 20;  // a header is a few hundred bytes
constexpr std::uint64_t kMaxPointBytes = 1 << 20; // per point, every field's values
constexpr std::uint64_t kLzfMaxExpansion = 88;    // 3 bytes of LZF hold at most 264

enum class Encoding { Ascii, Binary, Compressed };

/** The header's lines by key, and where the data starts. */
struct Header {
  std::map<std::string, std::vector<std::string>> entries;
  std::uint64_t data_offset = 0;
  std::size_t data_line = 0; ///< 1-based line number of the first data line
};

const char* const kKeys[] = {"VERSION", "FIELDS", "COLUMNS", "SIZE",      "TYPE",
                             "COUNT",   "WIDTH",  "HEIGHT",  "VIEWPOINT", "POINTS"};

bool readHeader(const FileBytes& file, Header& header, std::string& error) {
  std::string text;
  if (!file.readRest(0, text, error, kMaxHeaderBytes))
    return false;
  TextLine line;
  std::size_t number = 0;
  for (std::size_t pos = 0; nextLine(text, pos, line); pos = line.next) {
    ++number;
    std::vector<std::string> w = words(text.data() + line.begin, text.data() + line.end);
    if (w.empty() || w[0][0] == '#')
      continue;
    std::string key = w[0];
    if (key == "DATA") {
      if (w.size() != 2) {
        error = "line " + std::to_string(number) +
                ": DATA needs one of ascii, binary, "
                "binary_compressed";
        return false;
      }
      header.entries["DATA"] = {w[1]};
      header.data_offset = line.next;
      header.data_line = number + 1;
      return true;
    }
    if (std::find(std::begin(kKeys), std::end(kKeys), key) == std::end(kKeys)) {
      error = "line " + std::to_string(number) + ": " +
              quoted(text.data() + line.begin, text.data() + line.end) +
              " is not a header line (FIELDS, SIZE, TYPE, COUNT, WIDTH, HEIGHT, VIEWPOINT, "
              "POINTS, DATA)";
      return false;
    }
    if (key == "COLUMNS")
      key = "FIELDS";
    if (!header.entries.emplace(key, std::vector<std::string>(w.begin() + 1, w.end())).second) {
      error = "line " + std::to_string(number) + ": a second " + key + " line";
      return false;
    }
  }
  error = text.size() == kMaxHeaderBytes ? "no DATA line in the first 1 MiB"
                                         : "the header ends without a DATA line";
  return false;
}

/** The PCL type of a PCD TYPE and SIZE, 0 for none the format allows. */
std::uint8_t fieldType(const std::string& type, std::uint64_t size) {
  if (type == "F")
    return size == 4 ? pcl::PCLPointField::FLOAT32 : size == 8 ? pcl::PCLPointField::FLOAT64 : 0;
  const bool i = type == "I";
  if (!i && type != "U")
    return 0;
  switch (size) {
  case 1:
    return i ? pcl::PCLPointField::INT8 : pcl::PCLPointField::UINT8;
  case 2:
    return i ? pcl::PCLPointField::INT16 : pcl::PCLPointField::UINT16;
  case 4:
    return i ? pcl::PCLPointField::INT32 : pcl::PCLPointField::UINT32;
  case 8:
    return i ? pcl::PCLPointField::INT64 : pcl::PCLPointField::UINT64;
  default:
    return 0;
  }
}

/** One header value as a count; false with the reason. */
bool headerCount(const Header& h, const char* key, std::uint64_t fallback, std::uint64_t max,
                 std::uint64_t& value, std::string& error) {
  const auto it = h.entries.find(key);
  if (it == h.entries.end()) {
    value = fallback;
    if (fallback == UINT64_MAX)
      error = std::string("no ") + key + " line";
    return fallback != UINT64_MAX;
  }
  if (it->second.size() != 1 || !parseCount(it->second[0], value) || value > max) {
    error = std::string(key) + " must be one whole number from 0 to " + std::to_string(max);
    return false;
  }
  return true;
}

/** FIELDS, SIZE, TYPE and COUNT as PCL's fields, with offsets and the point's size. */
bool headerFields(const Header& h, pcl::PCLPointCloud2& blob, std::string& error) {
  const auto get = [&](const char* key) {
    const auto it = h.entries.find(key);
    return it == h.entries.end() ? std::vector<std::string>() : it->second;
  };
  const std::vector<std::string> names = get("FIELDS"), sizes = get("SIZE"), types = get("TYPE");
  std::vector<std::string> counts = get("COUNT");
  if (h.entries.count("COUNT") == 0)
    counts.assign(names.size(), "1");
  if (names.empty() || sizes.size() != names.size() || types.size() != names.size() ||
      counts.size() != names.size()) {
    error = "FIELDS has " + std::to_string(names.size()) + " names, SIZE " +
            std::to_string(sizes.size()) + " values, TYPE " + std::to_string(types.size()) +
            ", COUNT " + std::to_string(counts.size()) + ": they must match";
    return false;
  }
  std::uint64_t offset = 0;
  for (std::size_t i = 0; i < names.size(); ++i) {
    std::uint64_t size = 0, count = 0;
    const bool size_ok = parseCount(sizes[i], size);
    const std::uint8_t type = size_ok ? fieldType(types[i], size) : 0;
    if (type == 0) {
      error = "field '" + names[i] + "' has TYPE " + types[i] + " SIZE " + sizes[i] +
              ": a field is F of SIZE 4 or 8, or I or U of SIZE 1, 2, 4 or 8";
      return false;
    }
    if (!parseCount(counts[i], count) || count == 0 || count > kMaxPointBytes) {
      error = "field '" + names[i] + "' has COUNT " + counts[i] + ": from 1 to " +
              std::to_string(kMaxPointBytes);
      return false;
    }
    pcl::PCLPointField f;
    f.name = names[i];
    f.offset = static_cast<std::uint32_t>(offset);
    f.datatype = type;
    f.count = static_cast<std::uint32_t>(count);
    blob.fields.push_back(f);
    offset += size * count;
    if (offset > kMaxPointBytes) {
      error =
          "a point of these fields takes more than " + std::to_string(kMaxPointBytes) + " bytes";
      return false;
    }
  }
  blob.point_step = static_cast<std::uint32_t>(offset);
  return true;
}

bool headerViewpoint(const Header& h, Viewpoint& viewpoint, std::string& error) {
  const auto it = h.entries.find("VIEWPOINT");
  if (it == h.entries.end())
    return true;
  float v[7];
  bool ok = it->second.size() == 7;
  for (std::size_t i = 0; ok && i < 7; ++i)
    ok = parseFloat(it->second[i], v[i]);
  if (!ok) {
    error = "VIEWPOINT must be 7 numbers (tx ty tz qw qx qy qz)";
    return false;
  }
  viewpoint.origin = Eigen::Vector4f(v[0], v[1], v[2], 0.0f);
  viewpoint.orientation = Eigen::Quaternionf(v[3], v[4], v[5], v[6]);
  return true;
}

/** The ascii data: one line per point, exactly the fields' values, nothing after. */
bool readAscii(const FileBytes& file, const Header& h, pcl::PCLPointCloud2& blob,
               std::uint64_t points, std::string& error) {
  std::string text;
  if (!file.readRest(h.data_offset, text, error))
    return false;
  std::uint64_t values = 0;
  for (const pcl::PCLPointField& f : blob.fields)
    values += f.count;
  if (points > text.size() / (2 * values) + 1) { // a value takes a digit and a separator
    error = "POINTS " + std::to_string(points) + " of " + std::to_string(values) +
            " values each cannot fit in the " + std::to_string(text.size()) + " bytes of data";
    return false;
  }
  blob.data.assign(static_cast<std::size_t>(points) * blob.point_step, 0);
  TextLine line;
  std::size_t pos = 0, number = h.data_line;
  for (std::uint64_t i = 0; i < points; ++i, ++number, pos = line.next) {
    if (!nextLine(text, pos, line)) {
      error =
          "the data ends after " + std::to_string(i) + " of " + std::to_string(points) + " points";
      return false;
    }
    const char* p = text.data() + line.begin;
    const char* end = text.data() + line.end;
    std::uint8_t* point = blob.data.data() + i * blob.point_step;
    std::uint64_t taken = 0;
    for (const pcl::PCLPointField& f : blob.fields) {
      const std::size_t size = typeSize(f.datatype);
      for (std::uint32_t k = 0; k < f.count; ++k, ++taken) {
        while (p != end && isBlank(*p))
          ++p;
        const char* token = p;
        while (p != end && !isBlank(*p))
          ++p;
        if (token == p) {
          error = "line " + std::to_string(number) + " has " + std::to_string(taken) +
                  " values, the fields need " + std::to_string(values);
          return false;
        }
        if (f.name != "_" && !parseValue(token, p, f.datatype, point + f.offset + k * size)) {
          error = "line " + std::to_string(number) + ": " + quoted(token, p) +
                  " is not a value of field '" + f.name + "'";
          return false;
        }
      }
    }
    while (p != end && isBlank(*p))
      ++p;
    if (p != end) {
      error = "line " + std::to_string(number) + " has more than the " + std::to_string(values) +
              " values of the fields";
      return false;
    }
  }
  for (; pos < text.size(); ++pos)
    if (!isBlank(text[pos]) && text[pos] != '\n') {
      error = "line " + std::to_string(number) + ": data after the " + std::to_string(points) +
              " points";
      return false;
    }
  return true;
}

bool readBinary(const FileBytes& file, const Header& h, pcl::PCLPointCloud2& blob,
                std::uint64_t points, std::string& error) {
  const std::uint64_t available = file.size() - std::min(file.size(), h.data_offset);
  if (points > available / blob.point_step) {
    error = "the data holds " + std::to_string(available / blob.point_step) + " of the " +
            std::to_string(points) + " points of " + std::to_string(blob.point_step) +
            " bytes the header gives";
    return false;
  }
  blob.data.resize(static_cast<std::size_t>(points) * blob.point_step);
  return file.read(h.data_offset, blob.data.size(), blob.data.data(), error);
}

/** binary_compressed: two sizes, then LZF of each field's values for all points in turn. */
bool readCompressed(const FileBytes& file, const Header& h, pcl::PCLPointCloud2& blob,
                    std::uint64_t points, std::string& error) {
  std::uint32_t sizes[2]; // compressed, uncompressed (little-endian, as PCL writes them)
  if (!file.read(h.data_offset, sizeof sizes, sizes, error)) {
    error = "no compressed block after DATA";
    return false;
  }
  const std::uint64_t compressed = sizes[0], size = sizes[1];
  const std::uint64_t expected = points * blob.point_step; // both < 2^52: no overflow
  if (points > (std::uint64_t(1) << 32) || size != expected) {
    error = "the compressed block holds " + std::to_string(size) + " bytes, the " +
            std::to_string(points) + " points of " + std::to_string(blob.point_step) +
            " bytes need " + std::to_string(expected);
    return false;
  }
  if (size > compressed * kLzfMaxExpansion) {
    error = "a compressed block of " + std::to_string(compressed) + " bytes cannot hold " +
            std::to_string(size);
    return false;
  }
  const std::uint64_t start = h.data_offset + sizeof sizes;
  if (compressed > file.size() - std::min(file.size(), start)) { // before it is allocated
    error = "the compressed block of " + std::to_string(compressed) + " bytes is cut short";
    return false;
  }
  std::vector<char> in(static_cast<std::size_t>(compressed));
  if (!file.read(start, in.size(), in.data(), error))
    return false;
  std::vector<std::uint8_t> raw(static_cast<std::size_t>(size));
  if (size > 0 && pcl::lzfDecompress(in.data(), static_cast<unsigned>(compressed), raw.data(),
                                     static_cast<unsigned>(size)) != size) {
    error = "the compressed block is corrupt";
    return false;
  }
  blob.data.resize(raw.size());
  const std::uint8_t* column = raw.data();
  for (const pcl::PCLPointField& f : blob.fields) {
    const std::size_t bytes = typeSize(f.datatype) * f.count;
    for (std::uint64_t i = 0; i < points; ++i, column += bytes)
      std::memcpy(blob.data.data() + i * blob.point_step + f.offset, column, bytes);
  }
  return true;
}

} // namespace

bool readPcd(const FileBytes& file, pcl::PCLPointCloud2& blob, Viewpoint& viewpoint,
             std::string& error) {
  blob = pcl::PCLPointCloud2();
  viewpoint = Viewpoint();
  Header h;
  std::uint64_t width = 0, height = 0, points = 0;
  if (!readHeader(file, h, error) || !headerFields(h, blob, error) ||
      !headerCount(h, "WIDTH", UINT64_MAX, UINT32_MAX, width, error) ||
      !headerCount(h, "HEIGHT", 1, UINT32_MAX, height, error) ||
      !headerCount(h, "POINTS", width * height, UINT64_MAX - 1, points, error) ||
      !headerViewpoint(h, viewpoint, error))
    return false;
  if (points != width * height) {
    error = "POINTS " + std::to_string(points) + " is not WIDTH x HEIGHT (" +
            std::to_string(width) + " x " + std::to_string(height) + ")";
    return false;
  }
  blob.width = static_cast<std::uint32_t>(width);
  blob.height = static_cast<std::uint32_t>(height);
  blob.row_step = blob.point_step * blob.width;
  blob.is_dense = true;
  const std::string& data = h.entries["DATA"][0];
  if (data == "ascii")
    return readAscii(file, h, blob, points, error);
  if (data == "binary")
    return readBinary(file, h, blob, points, error);
  if (data == "binary_compressed")
    return readCompressed(file, h, blob, points, error);
  error = "DATA " + data + ": one of ascii, binary, binary_compressed";
  return false;
}

} // namespace files
} // namespace pcl_ncut_seg
