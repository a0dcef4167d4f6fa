#include "tool_common.h"

#include "mesh_sampling.h"

#include <pcl/PolygonMesh.h>
#include <pcl/console/print.h>
#include <pcl/conversions.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <limits>
#include <set>
#include <sstream>

#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

namespace pcl_ncut_seg {
namespace tool {

using pcl::console::print_error;
using pcl::console::print_warn;

void fail(const std::string& message) {
  print_error("Error: %s\n", message.c_str());
}

void warn(const std::string& message) {
  print_warn("Warning: %s\n", message.c_str());
}

SilencePcl::SilencePcl() : level_(pcl::console::getVerbosityLevel()) {
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
}
SilencePcl::~SilencePcl() {
  pcl::console::setVerbosityLevel(static_cast<pcl::console::VERBOSITY_LEVEL>(level_));
}

// ---------------------------------------------------------------------------------- paths

namespace {
std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string baseName(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

bool isReadableFile(const std::string& path) {
  struct stat st;
  return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(path.c_str(), R_OK) == 0;
}

std::string formatNumber(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}
} // namespace

std::string extension(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  const std::size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
    return "";
  return lower(path.substr(dot));
}

std::string stem(const std::string& path) {
  const std::string base = baseName(path);
  const std::size_t dot = base.find_last_of('.');
  return dot == std::string::npos || dot == 0 ? base : base.substr(0, dot);
}

std::string directoryOf(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  if (slash == std::string::npos)
    return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

// ---------------------------------------------------------------------------------- flags

Flag switchFlag(const std::string& name, const std::string& help, const std::string& def) {
  Flag f{name, FlagKind::Switch, "", help, def, 0, 0, false, ""};
  return f;
}

Flag intFlag(const std::string& name, const std::string& value, const std::string& help,
             const std::string& def, double lo, double hi) {
  Flag f{name, FlagKind::Integer, value, help, def, lo, hi, false, ""};
  f.range = hi >= 1e300 ? "an integer >= " + formatNumber(lo)
                        : "an integer in [" + formatNumber(lo) + ", " + formatNumber(hi) + "]";
  return f;
}

Flag realFlag(const std::string& name, const std::string& value, const std::string& help,
              const std::string& def, double lo, double hi, bool open_lo) {
  Flag f{name, FlagKind::Real, value, help, def, lo, hi, open_lo, ""};
  f.range = hi >= 1e300 ? std::string("a number ") + (open_lo ? "> " : ">= ") + formatNumber(lo)
                        : "a number in [" + formatNumber(lo) + ", " + formatNumber(hi) + "]";
  return f;
}

Flag textFlag(const std::string& name, const std::string& value, const std::string& help,
              const std::string& def) {
  Flag f{name, FlagKind::Text, value, help, def, 0, 0, false, ""};
  return f;
}

namespace {
// Strict conversions: the whole string must be a finite number.
bool toDouble(const std::string& s, double& value) {
  if (s.empty() || std::isspace(static_cast<unsigned char>(s[0])))
    return false;
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(s.c_str(), &end);
  if (errno != 0 || end == s.c_str() || *end != '\0' || !std::isfinite(v))
    return false;
  value = v;
  return true;
}

bool toInt(const std::string& s, long& value) {
  if (s.empty() || std::isspace(static_cast<unsigned char>(s[0])))
    return false;
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(s.c_str(), &end, 10);
  if (errno != 0 || end == s.c_str() || *end != '\0' || v < std::numeric_limits<int>::min() ||
      v > std::numeric_limits<int>::max())
    return false;
  value = v;
  return true;
}
} // namespace

long Flags::integer(const std::string& name) const {
  long v = 0;
  toInt(given.at(name), v);
  return v;
}

double Flags::real(const std::string& name) const {
  double v = 0;
  toDouble(given.at(name), v);
  return v;
}

bool parseFlags(int argc, char** argv, const std::vector<Flag>& table, Flags& flags) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto flag =
        std::find_if(table.begin(), table.end(), [&arg](const Flag& f) { return f.name == arg; });
    if (flag == table.end()) {
      if (arg.size() > 1 && arg[0] == '-') {
        fail("unknown option " + arg + " (see -h)");
        return false;
      }
      flags.files.push_back(arg);
      continue;
    }
    if (flags.has(arg)) {
      fail("option " + arg + " given more than once");
      return false;
    }
    if (flag->kind == FlagKind::Switch) {
      flags.given[arg] = "";
      continue;
    }
    if (i + 1 >= argc) {
      fail("option " + arg + " needs a value (see -h)");
      return false;
    }
    const std::string text = argv[++i]; // a value may look like a flag ("-1")
    if (flag->kind != FlagKind::Text) {
      double value = 0;
      long integer = 0;
      const bool ok = flag->kind == FlagKind::Integer
                          ? (toInt(text, integer) && (value = static_cast<double>(integer), true))
                          : toDouble(text, value);
      if (!ok || value < flag->lo || value > flag->hi || (flag->open_lo && value == flag->lo)) {
        fail("bad value '" + text + "' for " + arg + ": expected " + flag->range);
        return false;
      }
    } else if (text.empty()) {
      fail("option " + arg + " needs a non-empty value");
      return false;
    }
    flags.given[arg] = text;
  }
  return true;
}

void printFlags(const std::vector<Flag>& table) {
  for (const Flag& f : table) {
    std::string head = "    " + f.name + (f.value.empty() ? "" : " " + f.value);
    if (head.size() < 22)
      head.resize(22, ' ');
    std::string line = head + " = " + f.help;
    if (!f.def.empty())
      line += " (default: " + f.def + ")";
    pcl::console::print_info("%s\n", line.c_str());
  }
}

std::vector<Flag> algorithmFlags() {
  const Segmenter d; // the library's defaults, so that the help cannot drift from them
  const auto num = [](double v) { return formatNumber(v); };
  return {
      intFlag("-k", "K", "nearest neighbours per point in the kNN graph, >= 2",
              num(d.getNumberOfNeighbours()), 2),
      intFlag("-cen_samples", "S",
              "centrality samples per connected component, >= 0; 0 = ceil(sqrt(n)) as in the "
              "paper",
              num(d.getNumberOfSamples()), 0),
      realFlag("-crossing", "F", "feature-crossing fraction of |N(p)| (Sec. 4.2), in [0, 1]",
               num(d.getCrossingFraction()), 0, 1),
      realFlag("-area", "F",
               "small supernodes: feature area below this fraction of the total, in [0, 1]",
               num(d.getAreaFraction()), 0, 1),
      realFlag("-height", "F",
               "skinny supernodes: feature height below this fraction of the largest, in [0, 1]",
               num(d.getHeightFraction()), 0, 1),
      realFlag("-beta", "B", "beta of eq. (7), > 0", num(d.getBeta()), 0, 1e300, true),
      realFlag("-alpha1", "A", "alpha1 of eq. (9), > 0", num(d.getAlpha1()), 0, 1e300, true),
      realFlag("-alpha2", "A", "alpha2 of eq. (9), > 0", num(d.getAlpha2()), 0, 1e300, true),
      realFlag("-threshold", "T",
               "normalized-cut threshold, >= 0: no part is split at a higher NCut; the "
               "largest-gap rule then keeps the splits up to the largest jump in NCut (with "
               "-paper: a part is bisected while its best NCut <= T)",
               num(d.getThreshold()), 0),
      intFlag("-segments", "K", "ask for K segments instead of using the threshold, >= 1", "off",
              1),
      intFlag("-splits", "N", "split values tried on each eigenvector, >= 1",
              num(d.getNumberOfSplitValues()), 1),
      intFlag("-threads", "N",
              "threads for the centrality phase, >= 0; 0 = all cores; the result does not "
              "depend on it",
              num(d.getNumberOfThreads()), 0),
      realFlag("-gap_floor", "F",
               "largest-gap stopping rule: NCut values below F count as F, > 0",
               num(d.getGapFloor()), 0, 1e308, true),
      intFlag("-max_segments", "K", "largest-gap stopping rule: at most K segments, >= 1",
              num(d.getMaxSegments()), 1),
      realFlag("-adjacent_share", "S",
               "join touching supernodes that meet at no saddle when their contact is at least "
               "this share of the smaller total contact, in [0, 1]",
               num(d.getAdjacentShare()), 0, 1),
      realFlag("-bridge_gap", "G",
               "join kNN-graph components whose shortest link is at most G kNN radii long "
               "(sampling gaps), >= 0; 0 = never",
               num(d.getBridgeGap()), 0),
      realFlag("-concavity", "W",
               "concave creases: the weight between touching supernodes is multiplied by "
               "exp(-W c), c how concave their contact is, >= 0; 0 = off",
               num(d.getConcavityWeight()), 0),
      realFlag("-flat", "E",
               "flat patches: between two supernodes with feature height < E sqrt(feature "
               "area), eq. (9) leaves out the width ratio, >= 0; 0 = off",
               num(d.getFlatElongation()), 0),
      realFlag("-neck_exponent", "W",
               "short-cut stopping rule: a split's NCut is weighted by neck^W (boundary length "
               "over sqrt of the smaller side's area), >= 0; 0 = the largest jump in NCut",
               num(d.getNeckExponent()), 0),
      realFlag("-neck_bound", "K",
               "short-cut stopping rule: weighted NCut below which a split is worth making, > 0",
               num(d.getNeckBound()), 0, 1e308, true),
      realFlag("-boundary_band", "F",
               "boundary refinement: recut each pair of touching segments by a minimum cut "
               "within a band holding at most this fraction of either segment, in [0, 0.5]; "
               "0 = off",
               num(d.getBoundaryBand()), 0, 0.5),
      realFlag("-boundary_crease", "W",
               "boundary refinement: a kNN edge's cut cost is its length times exp(-W c), c "
               "its concave bend, >= 0",
               num(d.getBoundaryCreaseWeight()), 0),
      realFlag("-crease", "C",
               "crease splits: split a supernode along its most concave level cut of the "
               "centrality when that cut's mean concave bend is >= C, >= 0; 0 = off",
               num(d.getCreaseSplit()), 0),
      realFlag("-crease_cut", "S",
               "crease cuts: split a supernode no level cut splits along its minimum cut "
               "weighted by concave bend when a share >= S of the edges it crosses are "
               "concave, in [0, 1]; 0 = off",
               num(d.getCreaseCut()), 0, 1),
      realFlag("-min_fraction", "F",
               "threshold cut: a part is bisected only if each side keeps this fraction of the "
               "feature area, in [0, 0.5]",
               num(d.getMinSegmentFraction()), 0, 0.5),
      switchFlag("-exact", "exact centrality: sqrt(n) searches on the full kNN graph, as in the "
                           "paper, instead of the Fast coarse graph for large clouds"),
      intFlag("-representatives", "R",
              "Fast centrality: points of the coarse graph, >= 100 (clouds up to R points are "
              "computed exactly)",
              num(d.getNumberOfRepresentatives()), 100),
      switchFlag("-paper", "the paper to the letter: no feature-width normalisation, no joining "
                           "of supernodes that meet at no saddle, no bridging of kNN-graph "
                           "components, no concavity term, no flat patches, no crease splits, "
                           "no boundary refinement, recursive bisection while NCut <= T instead "
                           "of the largest-gap rule, exact centrality"),
      switchFlag("-cad", "CAD mode (Sec. 7): the faces of a mechanical part, separated at its "
                         "ridges"),
      realFlag("-face_angle", "DEG",
               "CAD mode: angle scale of the face-orientation similarity, in (0, 90]",
               num(d.getFaceAngle()), 0, 90, true),
  };
}

std::vector<Flag> meshFlags() {
  return {
      intFlag("-samples", "N",
              "mesh input: N points sampled uniformly by area instead of one per face, >= 1",
              "one per face", 1),
      intFlag("-seed", "S", "mesh input: random seed of -samples, >= 0", "1", 0),
  };
}

std::vector<Flag> commonFlags() {
  return {switchFlag("-quiet", "print errors and warnings only"),
          switchFlag("-h", "this help", "")};
}

bool applyAlgorithmFlags(const Flags& flags, Segmenter& seg) {
  if (flags.has("-segments") && flags.has("-threshold")) {
    fail("give either -threshold or -segments, not both");
    return false;
  }
  if (flags.has("-k"))
    seg.setNumberOfNeighbours(static_cast<int>(flags.integer("-k")));
  if (flags.has("-cen_samples"))
    seg.setNumberOfSamples(static_cast<int>(flags.integer("-cen_samples")));
  if (flags.has("-crossing"))
    seg.setCrossingFraction(static_cast<float>(flags.real("-crossing")));
  if (flags.has("-area"))
    seg.setAreaFraction(static_cast<float>(flags.real("-area")));
  if (flags.has("-height"))
    seg.setHeightFraction(static_cast<float>(flags.real("-height")));
  if (flags.has("-beta"))
    seg.setBeta(flags.real("-beta"));
  if (flags.has("-alpha1"))
    seg.setAlpha1(flags.real("-alpha1"));
  if (flags.has("-alpha2"))
    seg.setAlpha2(flags.real("-alpha2"));
  if (flags.has("-threshold"))
    seg.setThreshold(flags.real("-threshold"));
  if (flags.has("-segments"))
    seg.setNumberOfSegments(static_cast<int>(flags.integer("-segments")));
  if (flags.has("-splits"))
    seg.setNumberOfSplitValues(static_cast<int>(flags.integer("-splits")));
  if (flags.has("-threads"))
    seg.setNumberOfThreads(static_cast<unsigned>(flags.integer("-threads")));
  if (flags.has("-cad"))
    seg.setCadMode(true);
  if (flags.has("-face_angle"))
    seg.setFaceAngle(static_cast<float>(flags.real("-face_angle")));
  if (flags.has("-gap_floor"))
    seg.setGapFloor(flags.real("-gap_floor"));
  if (flags.has("-max_segments"))
    seg.setMaxSegments(static_cast<int>(flags.integer("-max_segments")));
  if (flags.has("-adjacent_share"))
    seg.setAdjacentShare(flags.real("-adjacent_share"));
  if (flags.has("-concavity"))
    seg.setConcavityWeight(flags.real("-concavity"));
  if (flags.has("-flat"))
    seg.setFlatElongation(flags.real("-flat"));
  if (flags.has("-neck_exponent"))
    seg.setNeckExponent(flags.real("-neck_exponent"));
  if (flags.has("-neck_bound"))
    seg.setNeckBound(flags.real("-neck_bound"));
  if (flags.has("-crease"))
    seg.setCreaseSplit(flags.real("-crease"));
  if (flags.has("-crease_cut"))
    seg.setCreaseCut(flags.real("-crease_cut"));
  if (flags.has("-bridge_gap"))
    seg.setBridgeGap(flags.real("-bridge_gap"));
  if (flags.has("-boundary_band"))
    seg.setBoundaryBand(flags.real("-boundary_band"));
  if (flags.has("-boundary_crease"))
    seg.setBoundaryCreaseWeight(flags.real("-boundary_crease"));
  if (flags.has("-min_fraction"))
    seg.setMinSegmentFraction(flags.real("-min_fraction"));
  if (flags.has("-exact"))
    seg.setCentralityMode(pcl_ncut_seg::CentralityMode::Exact);
  if (flags.has("-representatives"))
    seg.setNumberOfRepresentatives(static_cast<int>(flags.integer("-representatives")));
  if (flags.has("-paper")) {
    seg.setNormalizeWidth(false);
    seg.setConnectAdjacentTrees(false);
    seg.setConnectAllAdjacent(false);
    seg.setLargestGapStopping(false);
    seg.setNeckExponent(0.0);
    seg.setBridgeGap(0.0);
    seg.setConcavityWeight(0.0);
    seg.setFlatElongation(0.0);
    seg.setBoundaryBand(0.0);
    seg.setCreaseSplit(0.0);
    seg.setCreaseCut(0.0);
    seg.setCentralityMode(pcl_ncut_seg::CentralityMode::Exact);
  }
  return true;
}

std::string findBundledModel() {
  const char* kModel = "armadillo.pcd";
  // The source tree, the configured install directory, and <prefix>/share/pcl_ncut_seg beside
  // this executable's bin/ (for an install to another prefix).
  std::vector<std::string> dirs = {PCL_NCUT_SEG_SOURCE_DATA_DIR, PCL_NCUT_SEG_INSTALL_DATA_DIR};
  std::vector<char> buffer(4096);
  const ssize_t n = ::readlink("/proc/self/exe", buffer.data(), buffer.size() - 1);
  if (n > 0) {
    const std::string exe(buffer.data(), static_cast<std::size_t>(n));
    dirs.push_back(directoryOf(directoryOf(exe)) + "/share/pcl_ncut_seg");
  }
  std::string looked;
  for (const std::string& dir : dirs) {
    if (isReadableFile(dir + "/" + kModel))
      return dir + "/" + kModel;
    looked += (looked.empty() ? "" : ", ") + dir;
  }
  fail(std::string("the bundled model ") + kModel + " is in none of " + looked +
       "; give an input file");
  return "";
}

// ---------------------------------------------------------------------------------- input

const char* const kInputFormats = ".pcd, .ply, .off or .obj";

bool isInputFile(const std::string& path) {
  const std::string ext = extension(path);
  return ext == ".pcd" || ext == ".ply" || ext == ".off" || ext == ".obj";
}

namespace {

/** True when the cloud has x, y, z fields and at least one point; else one error line. */
bool hasXyzAndPoints(const std::string& path, const pcl::PCLPointCloud2& blob) {
  for (const char* name : {"x", "y", "z"}) {
    const auto it = std::find_if(blob.fields.begin(), blob.fields.end(),
                                 [name](const pcl::PCLPointField& f) { return f.name == name; });
    if (it == blob.fields.end()) {
      fail("'" + path + "' has no " + name + " field: need points with x, y and z");
      return false;
    }
  }
  if (static_cast<std::uint64_t>(blob.width) * blob.height == 0) {
    fail("'" + path + "' contains no points");
    return false;
  }
  return true;
}

/** A PCLPointCloud2 with the fields x y z (float) from a flat array. */
pcl::PCLPointCloud2 xyzBlob(const std::vector<float>& xyz) {
  pcl::PointCloud<pcl::PointXYZ> cloud;
  cloud.resize(xyz.size() / 3);
  for (std::size_t i = 0; i < cloud.size(); ++i)
    cloud[i] = pcl::PointXYZ(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
  cloud.width = static_cast<std::uint32_t>(cloud.size());
  cloud.height = 1;
  cloud.is_dense = true;
  pcl::PCLPointCloud2 blob;
  pcl::toPCLPointCloud2(cloud, blob);
  return blob;
}

/** A PLY's vertices and faces as a TriangleMesh (polygons fan-triangulated). */
bool toTriangleMesh(const std::string& path, const pcl::PolygonMesh& polygons, TriangleMesh& mesh) {
  pcl::PointCloud<pcl::PointXYZ> vertices;
  {
    SilencePcl silence;
    pcl::fromPCLPointCloud2(polygons.cloud, vertices);
  }
  mesh = TriangleMesh();
  for (const pcl::PointXYZ& p : vertices)
    mesh.vertices.insert(mesh.vertices.end(), {p.x, p.y, p.z});
  for (std::size_t f = 0; f < polygons.polygons.size(); ++f) {
    const auto& v = polygons.polygons[f].vertices;
    for (const auto index : v)
      if (static_cast<std::size_t>(index) >= vertices.size()) {
        fail("cannot read '" + path + "': face " + std::to_string(f) +
             " refers to a vertex that does not exist");
        return false;
      }
    for (std::size_t i = 1; i + 1 < v.size(); ++i) {
      mesh.faces.insert(mesh.faces.end(),
                        {static_cast<std::uint32_t>(v[0]), static_cast<std::uint32_t>(v[i]),
                         static_cast<std::uint32_t>(v[i + 1])});
      mesh.original_face.push_back(static_cast<std::uint32_t>(f));
    }
  }
  mesh.num_original_faces = polygons.polygons.size();
  return true;
}

/** Points on a mesh: one per face, or -samples area-uniform samples. */
bool sampleMesh(const std::string& path, const TriangleMesh& mesh, const Flags& flags,
                Input& input) {
  input.mesh = true;
  input.num_faces = mesh.num_original_faces;
  if (mesh.numTriangles() == 0) {
    fail("'" + path + "' is a mesh without faces (polygons of three or more vertices)");
    return false;
  }
  std::vector<float> xyz;
  std::ostringstream what;
  what << "mesh of " << mesh.num_original_faces << " faces, ";
  if (flags.has("-samples")) {
    const std::size_t n = static_cast<std::size_t>(flags.integer("-samples"));
    const std::uint64_t seed =
        flags.has("-seed") ? static_cast<std::uint64_t>(flags.integer("-seed")) : 1;
    xyz = sampleSurface(mesh, n, seed);
    if (xyz.empty()) {
      fail("'" + path + "' is a mesh without area: cannot sample points on it");
      return false;
    }
    what << n << " points sampled uniformly by area (seed " << seed << ")";
  } else {
    xyz = faceCentroids(mesh);
    what << "one point per face centroid";
  }
  input.blob = xyzBlob(xyz);
  input.description = what.str();
  return true;
}

} // namespace

bool loadInput(const std::string& path, const Flags& flags, Input& input) {
  input = Input();
  const std::string ext = extension(path);
  if (!isInputFile(path)) {
    fail("input '" + path + "' is not a " + kInputFormats + " file");
    return false;
  }
  if (!isReadableFile(path)) {
    struct stat st;
    if (::stat(path.c_str(), &st) != 0)
      fail("cannot read '" + path + "': " + std::strerror(errno));
    else if (!S_ISREG(st.st_mode))
      fail("cannot read '" + path + "': not a regular file");
    else
      fail("cannot read '" + path + "': permission denied");
    return false;
  }

  if (ext == ".off" || ext == ".obj") {
    TriangleMesh mesh;
    std::string error;
    if (!(ext == ".off" ? readOff(path, mesh, &error) : readObj(path, mesh, &error))) {
      fail("cannot read " + error);
      return false;
    }
    if (!sampleMesh(path, mesh, flags, input))
      return false;
  } else if (ext == ".ply") {
    pcl::PolygonMesh polygons;
    int status = -1;
    {
      SilencePcl silence;
      try {
        status = pcl::PLYReader().read(path, polygons);
      } catch (const std::exception&) {
        status = -1;
      }
    }
    if (status < 0) {
      fail("cannot read '" + path + "': not a valid PLY file");
      return false;
    }
    if (!polygons.polygons.empty()) {
      if (!hasXyzAndPoints(path, polygons.cloud))
        return false;
      TriangleMesh mesh;
      if (!toTriangleMesh(path, polygons, mesh) || !sampleMesh(path, mesh, flags, input))
        return false;
    } else {
      input.blob = std::move(polygons.cloud);
    }
  } else {
    // PCL 1.13's PCDReader::read crashes on a file without a header; check the header first.
    // It also tells a cloud without x, y, z or without points before its data is read.
    const std::string invalid = "cannot read '" + path + "': not a valid PCD file";
    Eigen::Vector4f origin;
    Eigen::Quaternionf orientation;
    int version = 0, data_type = 0;
    unsigned int data_index = 0;
    int status = -1;
    {
      SilencePcl silence;
      try {
        status = pcl::PCDReader().readHeader(path, input.blob, origin, orientation, version,
                                             data_type, data_index);
      } catch (const std::exception&) {
        status = -1;
      }
    }
    if (status < 0 || input.blob.fields.empty()) {
      fail(invalid);
      return false;
    }
    if (!hasXyzAndPoints(path, input.blob))
      return false;
    {
      SilencePcl silence;
      try {
        status = pcl::io::loadPCDFile(path, input.blob);
      } catch (const std::exception&) {
        status = -1;
      }
    }
    if (status < 0) {
      fail(invalid);
      return false;
    }
  }
  if (!input.mesh && (flags.has("-samples") || flags.has("-seed"))) {
    fail(std::string(flags.has("-samples") ? "-samples" : "-seed") +
         " applies to a mesh input (.off, .obj, .ply with faces); '" + path +
         "' holds points only");
    return false;
  }
  if (!hasXyzAndPoints(path, input.blob))
    return false;
  input.cloud.reset(new pcl::PointCloud<pcl::PointXYZ>);
  {
    SilencePcl silence; // fromPCLPointCloud2 warns about fields it does not need
    pcl::fromPCLPointCloud2(input.blob, *input.cloud);
  }
  std::size_t finite = 0;
  for (const pcl::PointXYZ& p : input.cloud->points)
    finite += std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
  if (finite == 0) {
    fail("'" + path + "' contains no point with finite coordinates");
    return false;
  }
  if (!input.mesh)
    input.description = std::to_string(input.cloud->size()) + " points";
  return true;
}

// ---------------------------------------------------------------------------------- output

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

bool writePcd(AtomicFile& file, const pcl::PCLPointCloud2& blob, bool binary) {
  int status = -1;
  {
    SilencePcl silence;
    try {
      pcl::PCDWriter writer;
      if (binary) {
        status = writer.writeBinary(file.temporaryPath(), blob);
      } else {
        // 9 significant digits read every float back exactly, 17 every double.
        const bool doubles =
            std::any_of(blob.fields.begin(), blob.fields.end(), [](const pcl::PCLPointField& f) {
              return f.datatype == pcl::PCLPointField::FLOAT64;
            });
        status = writer.writeASCII(file.temporaryPath(), blob, Eigen::Vector4f::Zero(),
                                   Eigen::Quaternionf::Identity(), doubles ? 17 : 9);
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

// ---------------------------------------------------------------------------------- progress

ProgressBar::ProgressBar(bool enabled) : enabled_(enabled) {
  if (!enabled_)
    return;
  if (const char* delay = std::getenv("PCL_NCUT_SEG_PROGRESS_DELAY")) {
    double v = 0;
    if (toDouble(delay, v) && v >= 0)
      delay_ = v;
  }
  thread_ = std::thread([this] { run(); });
}

ProgressBar::~ProgressBar() {
  if (!enabled_)
    return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
  std::lock_guard<std::mutex> lock(mutex_);
  draw(true);
}

void ProgressBar::update(const char* phase, double fraction) {
  if (!enabled_)
    return;
  std::lock_guard<std::mutex> lock(mutex_);
  if (phase_ != phase) { // a new phase (the last one ended, or is left without an end)
    draw(true);
    phase_ = phase;
    start_ = std::chrono::steady_clock::now();
    known_ = false;
  }
  fraction_ = std::clamp(fraction, 0.0, 1.0);
  const bool was_known = known_;
  if (fraction > 0.0 && fraction < 1.0)
    known_ = true;
  if (fraction >= 1.0) {
    draw(true);
    phase_.clear();
    return;
  }
  // Redraw now rather than wait for the thread when the bar changes kind or is stale, so that
  // what is shown does not depend on how the phase's time falls against the thread's period.
  const auto now = std::chrono::steady_clock::now();
  if (!drawn_ || known_ != was_known || now - last_draw_ >= std::chrono::milliseconds(100))
    draw(false);
}

std::function<void(const char*, double)> ProgressBar::callback() {
  return [this](const char* phase, double fraction) { update(phase, fraction); };
}

void ProgressBar::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stop_) {
    wake_.wait_for(lock, std::chrono::milliseconds(100));
    if (!stop_)
      draw(false);
  }
}

// Called with mutex_ held.
void ProgressBar::draw(bool final_clear) {
  if (final_clear) {
    if (drawn_)
      std::fprintf(stderr, "\r\033[K");
    std::fflush(stderr);
    drawn_ = false;
    return;
  }
  if (phase_.empty())
    return;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (elapsed < delay_)
    return;
  const int width = 30;
  std::string bar(width, ' ');
  char percent[16] = "    ";
  if (known_) {
    const int filled = static_cast<int>(fraction_ * width);
    std::fill(bar.begin(), bar.begin() + filled, '#');
    std::snprintf(percent, sizeof(percent), "%3d%%", static_cast<int>(fraction_ * 100));
  } else { // no fraction known: a marker that moves, so the user sees it is alive
    const int pos = static_cast<int>(elapsed * 10) % (2 * (width - 3));
    const int at = pos < width - 3 ? pos : 2 * (width - 3) - pos;
    bar.replace(static_cast<std::size_t>(at), 3, "<=>");
  }
  std::fprintf(stderr, "\r%-5s [%s] %s %6.1f s\033[K", phase_.c_str(), bar.c_str(), percent,
               elapsed);
  std::fflush(stderr);
  drawn_ = true;
  last_draw_ = std::chrono::steady_clock::now();
}

bool progressWanted(const Flags& flags) {
  return !flags.has("-quiet") && ::isatty(STDERR_FILENO);
}

std::uint64_t peakMemoryBytes() {
  struct rusage usage;
  if (::getrusage(RUSAGE_SELF, &usage) != 0)
    return 0;
  return static_cast<std::uint64_t>(usage.ru_maxrss) * 1024u; // kilobytes on Linux
}

} // namespace tool
} // namespace pcl_ncut_seg
