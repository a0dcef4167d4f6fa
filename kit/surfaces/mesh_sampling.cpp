#include "surfaces/mesh_sampling.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <sstream>

namespace pcl_ncut_seg {

namespace {

bool isSpace(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/** \brief Split a line into tokens, dropping a '#' comment. */
std::vector<std::string> tokenize(const std::string& line) {
  std::vector<std::string> tokens;
  std::size_t i = 0;
  const std::size_t end = std::min(line.find('#'), line.size());
  while (i < end) {
    while (i < end && isSpace(line[i]))
      ++i;
    std::size_t j = i;
    while (j < end && !isSpace(line[j]))
      ++j;
    if (j > i)
      tokens.emplace_back(line, i, j - i);
    i = j;
  }
  return tokens;
}

// std::from_chars: locale-independent, unlike strtod, and rejects trailing garbage.
template <typename T> bool parseNumber(const std::string& s, T& value) {
  const char* first = s.data();
  const char* last = s.data() + s.size();
  if (first != last && *first == '+')
    ++first; // from_chars rejects a leading '+'
  const auto [ptr, ec] = std::from_chars(first, last, value);
  return ec == std::errc() && ptr == last;
}

/** \brief Reads the next line that has tokens; false at the end of the file. */
bool nextTokens(std::istream& in, std::vector<std::string>& tokens, std::size_t& line_no) {
  std::string line;
  while (std::getline(in, line)) {
    ++line_no;
    tokens = tokenize(line);
    if (!tokens.empty())
      return true;
  }
  return false;
}

/** \brief "OFF" and its prefixed variants (COFF, NOFF, STOFF...) whose extra per-vertex
 * values follow x, y, z and are ignored. "nOFF"/"4OFF" (other dimensions) are refused. */
bool isOffKeyword(const std::string& t) {
  if (t.size() < 3 || t.compare(t.size() - 3, 3, "OFF") != 0)
    return false;
  return std::all_of(t.begin(), t.end() - 3,
                     [](char c) { return c == 'S' || c == 'T' || c == 'C' || c == 'N'; });
}

bool fail(std::string* error, const std::string& path, std::size_t line_no,
          const std::string& what) {
  if (error) {
    std::ostringstream s;
    s << path;
    if (line_no > 0)
      s << ":" << line_no;
    s << ": " << what;
    *error = s.str();
  }
  return false;
}

double triangleArea(const float* a, const float* b, const float* c) {
  const double u[3] = {double(b[0]) - a[0], double(b[1]) - a[1], double(b[2]) - a[2]};
  const double v[3] = {double(c[0]) - a[0], double(c[1]) - a[1], double(c[2]) - a[2]};
  const double x = u[1] * v[2] - u[2] * v[1];
  const double y = u[2] * v[0] - u[0] * v[2];
  const double z = u[0] * v[1] - u[1] * v[0];
  return 0.5 * std::sqrt(x * x + y * y + z * z);
}

/** \brief Uniform in [0, 1) from the top 53 bits: the same on every standard library, which
 * std::uniform_real_distribution does not promise. */
double uniform01(std::mt19937_64& rng) {
  return double(rng() >> 11) * 0x1.0p-53;
}

} // namespace

bool readOff(const std::string& path, TriangleMesh& mesh, std::string* error) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    return fail(error, path, 0, "cannot open file");
  std::size_t line_no = 0;
  std::vector<std::string> tokens;
  if (!nextTokens(in, tokens, line_no) || !isOffKeyword(tokens[0]))
    return fail(error, path, line_no, "not an OFF file (no OFF header)");
  // Counts on the header line itself ("OFF 8 6 0") or on the next line.
  std::vector<std::string> counts(tokens.begin() + 1, tokens.end());
  if (counts.empty()) {
    if (!nextTokens(in, counts, line_no))
      return fail(error, path, line_no, "missing vertex and face counts");
  }
  std::size_t num_vertices = 0, num_faces = 0;
  if (counts.size() < 2 || !parseNumber(counts[0], num_vertices) ||
      !parseNumber(counts[1], num_faces))
    return fail(error, path, line_no, "bad vertex and face counts");
  if (num_vertices > std::numeric_limits<std::uint32_t>::max() ||
      num_faces > std::numeric_limits<std::uint32_t>::max())
    return fail(error, path, line_no, "too many vertices or faces");

  TriangleMesh result;
  // Reserve only modestly: a corrupt header must not allocate gigabytes up front.
  result.vertices.reserve(3 * std::min<std::size_t>(num_vertices, 1u << 22));
  for (std::size_t v = 0; v < num_vertices; ++v) {
    if (!nextTokens(in, tokens, line_no))
      return fail(error, path, line_no, "file ends before vertex " + std::to_string(v));
    float xyz[3];
    if (tokens.size() < 3 || !parseNumber(tokens[0], xyz[0]) || !parseNumber(tokens[1], xyz[1]) ||
        !parseNumber(tokens[2], xyz[2]))
      return fail(error, path, line_no, "bad vertex " + std::to_string(v));
    result.vertices.insert(result.vertices.end(), xyz, xyz + 3);
  }
  result.faces.reserve(3 * std::min<std::size_t>(num_faces, 1u << 22));
  std::vector<std::uint32_t> polygon;
  for (std::size_t f = 0; f < num_faces; ++f) {
    if (!nextTokens(in, tokens, line_no))
      return fail(error, path, line_no, "file ends before face " + std::to_string(f));
    std::size_t k = 0;
    if (!parseNumber(tokens[0], k) || k < 3 || tokens.size() < k + 1)
      return fail(error, path, line_no, "bad face " + std::to_string(f));
    polygon.resize(k);
    for (std::size_t i = 0; i < k; ++i) {
      if (!parseNumber(tokens[i + 1], polygon[i]) || polygon[i] >= num_vertices)
        return fail(error, path, line_no, "bad vertex index in face " + std::to_string(f));
    }
    // Tokens after the k indices are a colour: ignored. Fan-triangulate the polygon.
    for (std::size_t i = 1; i + 1 < k; ++i) {
      result.faces.insert(result.faces.end(), {polygon[0], polygon[i], polygon[i + 1]});
      result.original_face.push_back(static_cast<std::uint32_t>(f));
    }
  }
  result.num_original_faces = num_faces;
  mesh = std::move(result);
  return true;
}

bool readObj(const std::string& path, TriangleMesh& mesh, std::string* error) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    return fail(error, path, 0, "cannot open file");
  TriangleMesh result;
  std::size_t line_no = 0;
  std::vector<std::string> tokens;
  std::vector<std::uint32_t> polygon;
  std::size_t num_faces = 0;
  while (nextTokens(in, tokens, line_no)) {
    if (tokens[0] == "v") {
      float xyz[3];
      if (tokens.size() < 4 || !parseNumber(tokens[1], xyz[0]) || !parseNumber(tokens[2], xyz[1]) ||
          !parseNumber(tokens[3], xyz[2]))
        return fail(error, path, line_no, "bad vertex");
      result.vertices.insert(result.vertices.end(), xyz, xyz + 3);
    } else if (tokens[0] == "f") {
      if (tokens.size() < 4)
        return fail(error, path, line_no, "a face needs at least three vertices");
      const long long count = static_cast<long long>(result.numVertices());
      polygon.clear();
      for (std::size_t i = 1; i < tokens.size(); ++i) {
        long long index = 0; // the vertex before any '/'
        if (!parseNumber(tokens[i].substr(0, tokens[i].find('/')), index) || index == 0)
          return fail(error, path, line_no, "bad vertex index in face");
        index = index > 0 ? index - 1 : count + index; // negative: relative to the end
        if (index < 0 || index >= count)
          return fail(error, path, line_no, "vertex index out of range in face");
        polygon.push_back(static_cast<std::uint32_t>(index));
      }
      for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
        result.faces.insert(result.faces.end(), {polygon[0], polygon[i], polygon[i + 1]});
        result.original_face.push_back(static_cast<std::uint32_t>(num_faces));
      }
      ++num_faces;
    }
  }
  if (result.vertices.empty() && num_faces == 0)
    return fail(error, path, 0, "not an OBJ file (no vertices)");
  result.num_original_faces = num_faces;
  mesh = std::move(result);
  return true;
}

std::vector<double> faceAreas(const TriangleMesh& mesh) {
  std::vector<double> areas(mesh.num_original_faces, 0.0);
  const float* v = mesh.vertices.data();
  for (std::size_t t = 0; t < mesh.numTriangles(); ++t) {
    const std::uint32_t* f = &mesh.faces[3 * t];
    areas[mesh.original_face[t]] += triangleArea(v + 3 * f[0], v + 3 * f[1], v + 3 * f[2]);
  }
  return areas;
}

std::vector<float> faceCentroids(const TriangleMesh& mesh) {
  const std::size_t n = mesh.num_original_faces;
  // Area-weighted sums, and plain sums of triangle centroids for faces with no area.
  std::vector<std::array<double, 3>> weighted(n, {0, 0, 0}), plain(n, {0, 0, 0});
  std::vector<double> area(n, 0.0);
  std::vector<std::uint32_t> count(n, 0);
  const float* v = mesh.vertices.data();
  for (std::size_t t = 0; t < mesh.numTriangles(); ++t) {
    const std::uint32_t* f = &mesh.faces[3 * t];
    const float *a = v + 3 * f[0], *b = v + 3 * f[1], *c = v + 3 * f[2];
    const double w = triangleArea(a, b, c);
    const std::uint32_t face = mesh.original_face[t];
    for (int d = 0; d < 3; ++d) {
      const double centroid = (double(a[d]) + b[d] + c[d]) / 3.0;
      weighted[face][d] += w * centroid;
      plain[face][d] += centroid;
    }
    area[face] += w;
    ++count[face];
  }
  std::vector<float> xyz(3 * n);
  for (std::size_t face = 0; face < n; ++face) {
    for (int d = 0; d < 3; ++d) {
      if (area[face] > 0)
        xyz[3 * face + d] = static_cast<float>(weighted[face][d] / area[face]);
      else
        xyz[3 * face + d] = static_cast<float>(plain[face][d] / std::max(count[face], 1u));
    }
  }
  return xyz;
}

std::vector<float> sampleSurface(const TriangleMesh& mesh, std::size_t n, std::uint64_t seed,
                                 std::vector<std::uint32_t>* face_of_sample) {
  if (face_of_sample)
    face_of_sample->clear();
  const std::size_t num_triangles = mesh.numTriangles();
  std::vector<double> cumulative(num_triangles);
  const float* v = mesh.vertices.data();
  double total = 0;
  for (std::size_t t = 0; t < num_triangles; ++t) {
    const std::uint32_t* f = &mesh.faces[3 * t];
    total += triangleArea(v + 3 * f[0], v + 3 * f[1], v + 3 * f[2]);
    cumulative[t] = total;
  }
  if (!(total > 0) || !std::isfinite(total))
    return {};

  std::mt19937_64 rng(seed);
  std::vector<float> xyz;
  xyz.reserve(3 * n);
  if (face_of_sample)
    face_of_sample->reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    // The first triangle whose cumulative area exceeds u: never one with zero area.
    const double u = uniform01(rng) * total;
    const std::size_t t = std::min<std::size_t>(
        std::upper_bound(cumulative.begin(), cumulative.end(), u) - cumulative.begin(),
        num_triangles - 1);
    // sqrt(r1) makes the barycentric point uniform over the triangle's area.
    const double s = std::sqrt(uniform01(rng));
    const double r2 = uniform01(rng);
    const double wa = 1.0 - s, wb = s * (1.0 - r2), wc = s * r2;
    const std::uint32_t* f = &mesh.faces[3 * t];
    const float *a = v + 3 * f[0], *b = v + 3 * f[1], *c = v + 3 * f[2];
    for (int d = 0; d < 3; ++d)
      xyz.push_back(static_cast<float>(wa * a[d] + wb * b[d] + wc * c[d]));
    if (face_of_sample)
      face_of_sample->push_back(mesh.original_face[t]);
  }
  return xyz;
}

bool readSeg(const std::string& path, std::vector<int>& labels) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    return false;
  std::vector<int> result;
  std::string line;
  while (std::getline(in, line)) {
    const std::vector<std::string> tokens = tokenize(line);
    if (tokens.empty())
      continue; // blank lines, e.g. a trailing one
    int label = 0;
    if (tokens.size() != 1 || !parseNumber(tokens[0], label))
      return false;
    result.push_back(label);
  }
  labels = std::move(result);
  return true;
}

} // namespace pcl_ncut_seg
