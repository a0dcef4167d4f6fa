#include "files/values.h"

#include "files/file_bytes.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstring>
#include <limits>
#include <system_error>

namespace pcl_ncut_seg {
namespace files {

pcl::PCLPointCloud2 xyzCloud(std::uint32_t width, std::uint32_t height) {
  pcl::PCLPointCloud2 blob;
  for (const char* name : {"x", "y", "z"}) {
    pcl::PCLPointField f;
    f.name = name;
    f.offset = static_cast<std::uint32_t>(4 * blob.fields.size());
    f.datatype = pcl::PCLPointField::FLOAT32;
    f.count = 1;
    blob.fields.push_back(f);
  }
  blob.width = width;
  blob.height = height;
  blob.point_step = 12;
  blob.row_step = 12 * width;
  blob.is_dense = true;
  blob.data.resize(std::size_t(width) * height * 12);
  return blob;
}

std::string extensionOf(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  const std::size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
    return "";
  std::string ext = path.substr(dot);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

std::size_t typeSize(std::uint8_t datatype) {
  switch (datatype) {
  case pcl::PCLPointField::INT8:
  case pcl::PCLPointField::UINT8:
    return 1;
  case pcl::PCLPointField::INT16:
  case pcl::PCLPointField::UINT16:
    return 2;
  case pcl::PCLPointField::INT32:
  case pcl::PCLPointField::UINT32:
  case pcl::PCLPointField::FLOAT32:
    return 4;
  case pcl::PCLPointField::INT64:
  case pcl::PCLPointField::UINT64:
  case pcl::PCLPointField::FLOAT64:
    return 8;
  default:
    return 0;
  }
}

namespace {

/** A whole token as T; from_chars' own rules, and a leading '+' as C's strtod allows. */
template <typename T> bool parseWhole(const char* begin, const char* end, T& value) {
  if (begin != end && *begin == '+' && end - begin > 1 && begin[1] != '-')
    ++begin;
  const auto [ptr, ec] = std::from_chars(begin, end, value);
  return ec == std::errc() && ptr == end && begin != end;
}

template <typename Narrow> bool storeInteger(const char* begin, const char* end, void* out) {
  using Wide = std::conditional_t<std::is_signed_v<Narrow>, std::int64_t, std::uint64_t>;
  Wide wide = 0;
  if (!parseWhole(begin, end, wide) ||
      wide < static_cast<Wide>(std::numeric_limits<Narrow>::min()) ||
      wide > static_cast<Wide>(std::numeric_limits<Narrow>::max()))
    return false;
  const Narrow value = static_cast<Narrow>(wide);
  std::memcpy(out, &value, sizeof value);
  return true;
}

template <typename Float> bool storeFloat(const char* begin, const char* end, void* out) {
  Float value = 0;
  if (!parseWhole(begin, end, value))
    return false;
  std::memcpy(out, &value, sizeof value);
  return true;
}

template <typename T> float loaded(const std::uint8_t* p) {
  T value;
  std::memcpy(&value, p, sizeof value);
  return static_cast<float>(value);
}

} // namespace

bool parseValue(const char* begin, const char* end, std::uint8_t datatype, void* out) {
  switch (datatype) {
  case pcl::PCLPointField::INT8:
    return storeInteger<std::int8_t>(begin, end, out);
  case pcl::PCLPointField::UINT8:
    return storeInteger<std::uint8_t>(begin, end, out);
  case pcl::PCLPointField::INT16:
    return storeInteger<std::int16_t>(begin, end, out);
  case pcl::PCLPointField::UINT16:
    return storeInteger<std::uint16_t>(begin, end, out);
  case pcl::PCLPointField::INT32:
    return storeInteger<std::int32_t>(begin, end, out);
  case pcl::PCLPointField::UINT32:
    return storeInteger<std::uint32_t>(begin, end, out);
  case pcl::PCLPointField::INT64:
    return storeInteger<std::int64_t>(begin, end, out);
  case pcl::PCLPointField::UINT64:
    return storeInteger<std::uint64_t>(begin, end, out);
  case pcl::PCLPointField::FLOAT32:
    return storeFloat<float>(begin, end, out);
  case pcl::PCLPointField::FLOAT64:
    return storeFloat<double>(begin, end, out);
  default:
    return false;
  }
}

bool parseCount(const std::string& token, std::uint64_t& value) {
  return !token.empty() && token[0] != '+' &&
         parseWhole(token.data(), token.data() + token.size(), value);
}

bool parseFloat(const std::string& token, float& value) {
  return parseWhole(token.data(), token.data() + token.size(), value);
}

std::vector<std::string> words(const char* begin, const char* end) {
  std::vector<std::string> out;
  while (begin != end) {
    while (begin != end && isBlank(*begin))
      ++begin;
    const char* word = begin;
    while (begin != end && !isBlank(*begin))
      ++begin;
    if (begin != word)
      out.emplace_back(word, begin);
  }
  return out;
}

template <typename T> std::int64_t loadedInteger(const std::uint8_t* p) {
  T value;
  std::memcpy(&value, p, sizeof value);
  if constexpr (std::is_same_v<T, std::uint64_t>)
    return value > std::uint64_t(INT64_MAX) ? INT64_MAX : std::int64_t(value);
  else
    return static_cast<std::int64_t>(value);
}

std::int64_t integerValue(const std::uint8_t* p, std::uint8_t datatype) {
  switch (datatype) {
  case pcl::PCLPointField::INT8:
    return loadedInteger<std::int8_t>(p);
  case pcl::PCLPointField::UINT8:
    return loadedInteger<std::uint8_t>(p);
  case pcl::PCLPointField::INT16:
    return loadedInteger<std::int16_t>(p);
  case pcl::PCLPointField::UINT16:
    return loadedInteger<std::uint16_t>(p);
  case pcl::PCLPointField::INT32:
    return loadedInteger<std::int32_t>(p);
  case pcl::PCLPointField::UINT32:
    return loadedInteger<std::uint32_t>(p);
  case pcl::PCLPointField::INT64:
    return loadedInteger<std::int64_t>(p);
  case pcl::PCLPointField::UINT64:
    return loadedInteger<std::uint64_t>(p);
  default:
    return -1;
  }
}

float valueAsFloat(const std::uint8_t* p, std::uint8_t datatype) {
  switch (datatype) {
  case pcl::PCLPointField::INT8:
    return loaded<std::int8_t>(p);
  case pcl::PCLPointField::UINT8:
    return loaded<std::uint8_t>(p);
  case pcl::PCLPointField::INT16:
    return loaded<std::int16_t>(p);
  case pcl::PCLPointField::UINT16:
    return loaded<std::uint16_t>(p);
  case pcl::PCLPointField::INT32:
    return loaded<std::int32_t>(p);
  case pcl::PCLPointField::UINT32:
    return loaded<std::uint32_t>(p);
  case pcl::PCLPointField::INT64:
    return loaded<std::int64_t>(p);
  case pcl::PCLPointField::UINT64:
    return loaded<std::uint64_t>(p);
  case pcl::PCLPointField::FLOAT32:
    return loaded<float>(p);
  case pcl::PCLPointField::FLOAT64:
    return loaded<double>(p);
  default:
    return std::numeric_limits<float>::quiet_NaN();
  }
}

} // namespace files
} // namespace pcl_ncut_seg
