/*
 * pcl_ncut_seg files: the numbers of a text file (a PCD's ascii data, a PLY's ascii body,
 * their headers), parsed strictly: a token is one number of its type, whole, or an error.
 */
#pragma once

#include <pcl/PCLPointCloud2.h>
#include <pcl/PCLPointField.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pcl_ncut_seg {
namespace files {

/** \brief A cloud of width x height points of the fields x y z (FLOAT32, 12 bytes a point, as
 * pcl::PointXYZ's without its padding), its data zeros. */
pcl::PCLPointCloud2 xyzCloud(std::uint32_t width, std::uint32_t height);

/** \brief The extension of a file name, lower case with its dot (".pcd"); "" for none. */
std::string extensionOf(const std::string& path);

/** \brief The size in bytes of a PCL field type (INT8 ... FLOAT64); 0 for none. */
std::size_t typeSize(std::uint8_t datatype);

/** \brief Parse [begin, end) as one value of the PCL field type and store it at out (typeSize
 * bytes, little-endian as the machine). Floats take decimal and exponent forms, "nan" and
 * "inf"; integers must fit the type. False for anything else ("1.0f", "0x10", "", "1e400"). */
bool parseValue(const char* begin, const char* end, std::uint8_t datatype, void* out);

/** \brief A non-negative integer token that fits 64 bits. */
bool parseCount(const std::string& token, std::uint64_t& value);

/** \brief A finite or infinite float token, as parseValue takes it. */
bool parseFloat(const std::string& token, float& value);

/** \brief The whitespace-separated words of a text line [begin, end). */
std::vector<std::string> words(const char* begin, const char* end);

/** \brief Read the value at p of the PCL field type as a float (x, y, z of any type). */
float valueAsFloat(const std::uint8_t* p, std::uint8_t datatype);

/** \brief The value at p of an integer PCL field type (UINT64 above 2^63: saturated). */
std::int64_t integerValue(const std::uint8_t* p, std::uint8_t datatype);

} // namespace files
} // namespace pcl_ncut_seg
