/*
 * pcl_ncut_seg: segment a point-sampled surface into parts with pcl::SupernodeNCutSegmentation
 * (Yamazaki et al., "Segmenting Point-sampled Surfaces") and write the points labelled and
 * coloured by segment.
 *
 *   pcl_ncut_seg [input.pcd|input.ply] [output.pcd] [options]
 *
 * With no input, segments the bundled model hand.pcd and writes hand_segments.pcd.
 */
#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include <pcl/PCLPointCloud2.h>
#include <pcl/console/parse.h>
#include <pcl/console/print.h>
#include <pcl/conversions.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <sys/stat.h>
#include <unistd.h>

using namespace pcl::console;

namespace {

using Segmenter = pcl::SupernodeNCutSegmentation<pcl::PointXYZ>;

// Options that take a value, and switches. Anything else starting with '-' is an error.
const std::vector<std::string> kValueOptions = {"-k",         "-samples",  "-crossing", "-area",
                                                "-height",    "-beta",     "-alpha1",   "-alpha2",
                                                "-threshold", "-segments", "-splits",   "-threads"};
const std::vector<std::string> kSwitches = {"-paper", "-quiet", "-h", "--help"};

const char* kBundledModel = "hand.pcd";

void printHelp(const char* name) {
  const Segmenter d; // the library's defaults, so the help cannot drift from them
  print_info("Syntax is: %s [input.pcd|input.ply] [output.pcd] <options>\n", name);
  print_info("Segments a point-sampled surface into parts (Yamazaki et al., \"Segmenting "
             "Point-sampled Surfaces\") and\nwrites the points as a binary PCD with fields "
             "x y z rgb label (label 1..t per segment, 0 for points in no segment).\n");
  print_info("With no input, segments the bundled model %s and writes hand_segments.pcd in the "
             "current directory.\nWith an input and no output, writes <input name>_segments.pcd "
             "in the current directory.\n",
             kBundledModel);
  print_info("  where options are:\n");
  print_info("    -k K          = nearest neighbours per point in the kNN graph, >= 2 "
             "(default: %d)\n",
             d.getNumberOfNeighbours());
  print_info("    -samples S    = centrality samples per connected component, >= 0; 0 = "
             "ceil(sqrt(n)) as in the paper (default: %d)\n",
             d.getNumberOfSamples());
  print_info("    -crossing F   = feature-crossing fraction of |N(p)| (Sec. 4.2), in [0, 1] "
             "(default: %g)\n",
             d.getCrossingFraction());
  print_info("    -area F       = small supernodes: feature area below this fraction of the "
             "total, in [0, 1] (default: %g)\n",
             d.getAreaFraction());
  print_info("    -height F     = skinny supernodes: feature height below this fraction of the "
             "largest, in [0, 1] (default: %g)\n",
             d.getHeightFraction());
  print_info("    -beta B       = beta of eq. (7), > 0 (default: %g)\n", d.getBeta());
  print_info("    -alpha1 A     = alpha1 of eq. (9), > 0 (default: %g)\n", d.getAlpha1());
  print_info("    -alpha2 A     = alpha2 of eq. (9), > 0 (default: %g)\n", d.getAlpha2());
  print_info("    -threshold T  = normalized-cut threshold, >= 0: no split above it; the largest-gap "
             "rule then keeps the splits up to the largest jump in NCut (with -paper: a part is "
             "bisected while its best NCut <= T) (default: %g)\n",
             d.getThreshold());
  print_info("    -segments K   = ask for K segments instead of using the threshold, > 0 "
             "(default: off)\n");
  print_info("    -splits N     = split values tried on each eigenvector, >= 1 (default: %d)\n",
             d.getNumberOfSplitValues());
  print_info("    -threads N    = threads for the centrality phase, >= 0; 0 = all cores; the "
             "result does not depend on it (default: %u)\n",
             d.getNumberOfThreads());
  print_info("    -paper        = the paper to the letter: no feature-width normalisation, no "
             "joining of supernodes that meet at no saddle, recursive bisection while NCut "
             "<= T instead of the largest-gap rule (default: off)\n");
  print_info("    -quiet        = print errors only (default: off)\n");
  print_info("    -h            = this help\n");
}

bool g_quiet = false; // -quiet: errors only

// Progress and results on stdout, unless -quiet.
template <typename... Args> void info(const char* format, Args... args) {
  if (!g_quiet)
    print_info(format, args...);
}
template <typename... Args> void value(const char* format, Args... args) {
  if (!g_quiet)
    print_value(format, args...);
}

// One line on stderr, in PCL's style.
void fail(const std::string& message) {
  print_error("Error: %s\n", message.c_str());
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string extension(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  const std::size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
    return "";
  return lower(path.substr(dot));
}

std::string baseName(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
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

bool isReadableFile(const std::string& path) {
  struct stat st;
  return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(path.c_str(), R_OK) == 0;
}

// Strict conversions: the whole string must be a finite number in range.
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

/** Where the bundled model may be: the source tree, the configured install directory, and
 * <prefix>/share/pcl_ncut_seg beside this executable's bin/ (for an install to another prefix). */
std::vector<std::string> bundledDataDirs() {
  std::vector<std::string> dirs = {PCL_NCUT_SEG_SOURCE_DATA_DIR, PCL_NCUT_SEG_INSTALL_DATA_DIR};
  std::vector<char> buffer(4096);
  const ssize_t n = ::readlink("/proc/self/exe", buffer.data(), buffer.size() - 1);
  if (n > 0) {
    const std::string exe(buffer.data(), static_cast<std::size_t>(n));
    dirs.push_back(directoryOf(directoryOf(exe)) + "/share/pcl_ncut_seg");
  }
  return dirs;
}

/** The parsed command line. */
struct Options {
  std::string input, output;
  bool bundled = false; // no input given: the shipped model
  bool quiet = false, paper = false;
  std::map<std::string, double> real;  // -crossing, -area, ...
  std::map<std::string, long> integer; // -k, -samples, ...
};

bool isIntegerOption(const std::string& name) {
  return name == "-k" || name == "-samples" || name == "-segments" || name == "-splits" ||
         name == "-threads";
}

// Range of each option: [lo, hi], lo exclusive when open_lo.
struct Range {
  double lo, hi;
  bool open_lo;
  const char* text;
};

Range rangeOf(const std::string& name) {
  const double inf = std::numeric_limits<double>::infinity();
  if (name == "-k")
    return {2, inf, false, "an integer >= 2"};
  if (name == "-samples" || name == "-threads")
    return {0, inf, false, "an integer >= 0"};
  if (name == "-segments" || name == "-splits")
    return {1, inf, false, "an integer >= 1"};
  if (name == "-crossing" || name == "-area" || name == "-height")
    return {0, 1, false, "a number in [0, 1]"};
  if (name == "-threshold")
    return {0, inf, false, "a number >= 0"};
  return {0, inf, true, "a number > 0"}; // -beta, -alpha1, -alpha2
}

/** Parse argv; on error print one line and return false. */
bool parseCommandLine(int argc, char** argv, Options& opt) {
  std::vector<std::string> positional;
  std::set<std::string> seen;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool takes_value =
        std::find(kValueOptions.begin(), kValueOptions.end(), arg) != kValueOptions.end();
    const bool is_switch = std::find(kSwitches.begin(), kSwitches.end(), arg) != kSwitches.end();
    if (takes_value || is_switch) {
      if (!seen.insert(arg).second) {
        fail("option " + arg + " given more than once");
        return false;
      }
      if (takes_value) {
        if (i + 1 >= argc) {
          fail("option " + arg + " needs a value (see -h)");
          return false;
        }
        ++i; // its value may look like a flag ("-1"); range checks reject it below
      }
      continue;
    }
    if (arg.size() > 1 && arg[0] == '-') {
      fail("unknown option " + arg + " (see -h)");
      return false;
    }
    positional.push_back(arg);
  }
  if (positional.size() > 2) {
    fail("too many file arguments: expected [input.pcd|input.ply] [output.pcd], got '" +
         positional[2] + "' as a third");
    return false;
  }

  for (const std::string& name : kValueOptions) {
    std::string text;
    if (parse_argument(argc, argv, name.c_str(), text) < 0)
      continue;
    const Range range = rangeOf(name);
    double value = 0;
    bool ok;
    if (isIntegerOption(name)) {
      long v = 0;
      ok = toInt(text, v);
      value = static_cast<double>(v);
      if (ok)
        opt.integer[name] = v;
    } else {
      ok = toDouble(text, value);
      if (ok)
        opt.real[name] = value;
    }
    if (!ok || value < range.lo || value > range.hi || (range.open_lo && value == range.lo)) {
      fail("bad value '" + text + "' for " + name + ": expected " + range.text);
      return false;
    }
  }
  if (opt.integer.count("-segments") && opt.real.count("-threshold")) {
    fail("give either -threshold or -segments, not both");
    return false;
  }
  opt.paper = find_switch(argc, argv, "-paper");
  opt.quiet = find_switch(argc, argv, "-quiet");

  if (positional.empty()) {
    opt.bundled = true;
    const std::vector<std::string> dirs = bundledDataDirs();
    std::string looked;
    for (const std::string& dir : dirs) {
      const std::string candidate = dir + "/" + kBundledModel;
      if (isReadableFile(candidate)) {
        opt.input = candidate;
        break;
      }
      looked += (looked.empty() ? "" : ", ") + dir;
    }
    if (opt.input.empty()) {
      fail(std::string("the bundled model ") + kBundledModel + " is in none of " + looked +
           "; give an input file");
      return false;
    }
  } else {
    opt.input = positional[0];
  }
  opt.output = positional.size() == 2 ? positional[1] : stem(opt.input) + "_segments.pcd";

  const std::string in_ext = extension(opt.input);
  if (in_ext != ".pcd" && in_ext != ".ply") {
    fail("input '" + opt.input + "' is neither a .pcd nor a .ply file");
    return false;
  }
  if (extension(opt.output) != ".pcd") {
    fail("output '" + opt.output + "' must be a .pcd file");
    return false;
  }
  return true;
}

/** Silences PCL's own console messages while in scope (they would add lines to ours). */
class SilencePcl {
public:
  SilencePcl() : level_(getVerbosityLevel()) { setVerbosityLevel(L_ALWAYS); }
  ~SilencePcl() { setVerbosityLevel(level_); }

private:
  VERBOSITY_LEVEL level_;
};

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

/** Load a .pcd or .ply into XYZ points; on error print one line and return false. */
bool loadCloud(const std::string& path, pcl::PointCloud<pcl::PointXYZ>& cloud) {
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
  const bool ply = extension(path) == ".ply";
  const std::string invalid =
      "cannot read '" + path + "': not a valid " + (ply ? "PLY" : "PCD") + " file";
  pcl::PCLPointCloud2 blob;
  if (!ply) {
    // PCL 1.13's PCDReader::read crashes on a file without a header; check the header first.
    // It also tells a cloud without x, y, z or without points before its data is read.
    Eigen::Vector4f origin;
    Eigen::Quaternionf orientation;
    int version = 0, data_type = 0;
    unsigned int data_index = 0;
    int status = -1;
    {
      SilencePcl silence;
      try {
        status = pcl::PCDReader().readHeader(path, blob, origin, orientation, version, data_type,
                                             data_index);
      } catch (const std::exception&) {
        status = -1;
      }
    }
    if (status < 0 || blob.fields.empty()) {
      fail(invalid);
      return false;
    }
    if (!hasXyzAndPoints(path, blob))
      return false;
  }
  int status = -1;
  {
    SilencePcl silence;
    try {
      status = ply ? pcl::io::loadPLYFile(path, blob) : pcl::io::loadPCDFile(path, blob);
    } catch (const std::exception&) {
      status = -1;
    }
  }
  if (status < 0) {
    fail(invalid);
    return false;
  }
  if (!hasXyzAndPoints(path, blob))
    return false;
  {
    SilencePcl silence; // fromPCLPointCloud2 warns about fields it does not need
    pcl::fromPCLPointCloud2(blob, cloud);
  }
  std::size_t finite = 0;
  for (const pcl::PointXYZ& p : cloud.points)
    finite += std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
  if (finite == 0) {
    fail("'" + path + "' contains no point with finite coordinates");
    return false;
  }
  return true;
}

/** A temporary file in the output's directory, renamed over the output on commit() and
 * removed otherwise, so that a failed run leaves no file behind. */
class AtomicOutput {
public:
  bool open(const std::string& path) {
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

  /** Write the cloud to the temporary file, then rename it; one error line on failure. */
  bool commit(const pcl::PCLPointCloud2& blob) {
    int status = -1;
    {
      SilencePcl silence;
      try {
        pcl::PCDWriter writer;
        status = writer.writeBinary(tmp_, blob);
      } catch (const std::exception&) {
        status = -1;
      }
    }
    if (status < 0) {
      fail("cannot write '" + path_ + "'");
      return false;
    }
    if (std::rename(tmp_.c_str(), path_.c_str()) != 0) {
      fail("cannot write '" + path_ + "': " + std::strerror(errno));
      return false;
    }
    tmp_.clear();
    return true;
  }

  ~AtomicOutput() {
    if (!tmp_.empty())
      std::remove(tmp_.c_str());
  }

private:
  std::string path_, tmp_;
};

/** The output cloud: exactly the fields x y z rgb label (no padding). rgb is packed into a float
 * as pcl::PointXYZRGB stores it (alpha 0, so the float is finite), so pcl_viewer colours the
 * points by segment; points in no segment (label 0) are black. */
pcl::PCLPointCloud2 makeOutput(const pcl::PointCloud<pcl::PointXYZL>& labeled,
                               const pcl::PointCloud<pcl::PointXYZRGB>& colored) {
  pcl::PCLPointCloud2 blob;
  blob.header = labeled.header;
  blob.width = labeled.width;
  blob.height = labeled.height;
  blob.is_dense = labeled.is_dense;
  blob.is_bigendian = false;
  const struct {
    const char* name;
    std::uint8_t type;
  } fields[] = {{"x", pcl::PCLPointField::FLOAT32},
                {"y", pcl::PCLPointField::FLOAT32},
                {"z", pcl::PCLPointField::FLOAT32},
                {"rgb", pcl::PCLPointField::FLOAT32},
                {"label", pcl::PCLPointField::UINT32}};
  std::uint32_t offset = 0;
  for (const auto& f : fields) {
    pcl::PCLPointField field;
    field.name = f.name;
    field.offset = offset;
    field.datatype = f.type;
    field.count = 1;
    blob.fields.push_back(field);
    offset += 4;
  }
  blob.point_step = offset;
  blob.row_step = blob.point_step * blob.width;
  blob.data.resize(static_cast<std::size_t>(blob.point_step) * labeled.size());
  for (std::size_t i = 0; i < labeled.size(); ++i) {
    std::uint8_t* out = &blob.data[i * blob.point_step];
    const pcl::PointXYZL& p = labeled[i];
    std::uint32_t rgb = 0; // black for points in no segment
    if (i < colored.size() && p.label != 0)
      rgb = (std::uint32_t(colored[i].r) << 16) | (std::uint32_t(colored[i].g) << 8) |
            std::uint32_t(colored[i].b);
    std::memcpy(out + 0, &p.x, 4);
    std::memcpy(out + 4, &p.y, 4);
    std::memcpy(out + 8, &p.z, 4);
    std::memcpy(out + 12, &rgb, 4);
    std::memcpy(out + 16, &p.label, 4);
  }
  return blob;
}

} // namespace

int main(int argc, char** argv) {
  if (find_switch(argc, argv, "-h") || find_switch(argc, argv, "--help")) {
    printHelp(argv[0]);
    return 0;
  }
  Options opt;
  if (!parseCommandLine(argc, argv, opt))
    return 1;
  if (opt.quiet) {
    g_quiet = true;
    setVerbosityLevel(L_ERROR);
  }

  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  if (!loadCloud(opt.input, *cloud))
    return 1;
  // Claim the output now, so that an unwritable destination fails before the long computation.
  AtomicOutput output;
  if (!output.open(opt.output))
    return 1;
  info("Segmenting ");
  value("%s", opt.input.c_str());
  info(opt.bundled ? " (bundled model): " : ": ");
  value("%zu", cloud->size());
  info(" points\n");

  Segmenter seg;
  seg.setInputCloud(cloud);
  if (opt.integer.count("-k"))
    seg.setNumberOfNeighbours(static_cast<int>(opt.integer["-k"]));
  if (opt.integer.count("-samples"))
    seg.setNumberOfSamples(static_cast<int>(opt.integer["-samples"]));
  if (opt.real.count("-crossing"))
    seg.setCrossingFraction(static_cast<float>(opt.real["-crossing"]));
  if (opt.real.count("-area"))
    seg.setAreaFraction(static_cast<float>(opt.real["-area"]));
  if (opt.real.count("-height"))
    seg.setHeightFraction(static_cast<float>(opt.real["-height"]));
  if (opt.real.count("-beta"))
    seg.setBeta(opt.real["-beta"]);
  if (opt.real.count("-alpha1"))
    seg.setAlpha1(opt.real["-alpha1"]);
  if (opt.real.count("-alpha2"))
    seg.setAlpha2(opt.real["-alpha2"]);
  if (opt.real.count("-threshold"))
    seg.setThreshold(opt.real["-threshold"]);
  if (opt.integer.count("-segments"))
    seg.setNumberOfSegments(static_cast<int>(opt.integer["-segments"]));
  if (opt.integer.count("-splits"))
    seg.setNumberOfSplitValues(static_cast<int>(opt.integer["-splits"]));
  if (opt.integer.count("-threads"))
    seg.setNumberOfThreads(static_cast<unsigned>(opt.integer["-threads"]));
  if (opt.paper) {
    seg.setNormalizeWidth(false);
    seg.setConnectAdjacentTrees(false);
    seg.setConnectAllAdjacent(false);
    seg.setLargestGapStopping(false);
  }

  std::vector<pcl::PointIndices> segments;
  try {
    seg.extract(segments);
  } catch (const std::exception& e) {
    fail(std::string("segmentation failed: ") + e.what());
    return 1;
  }
  if (segments.empty()) {
    fail("segmentation of '" + opt.input + "' produced no segments");
    return 1;
  }

  const pcl_ncut_seg::PhaseTimes& times = seg.getPhaseTimes();
  const struct {
    const char* name;
    double seconds;
  } phases[] = {{"kNN", times.knn},         {"Cen", times.centrality}, {"Snod", times.supernodes},
                {"LRef", times.refinement}, {"HSeg", times.hierarchy}, {"PSeg", times.points},
                {"total", times.total()}};
  for (const auto& phase : phases) {
    info("%-5s: ", phase.name);
    value("%.3f", phase.seconds);
    info(" s\n");
  }
  const std::size_t n = seg.getAnalysedIndices().size();
  info("n    : ");
  value("%zu", n);
  info(" points segmented\n");
  info("m    : ");
  value("%zu", seg.getNumberOfSupernodes(false));
  info(" supernodes\n");
  info("l    : ");
  value("%zu", seg.getNumberOfSupernodes(true));
  info(" supernodes after refinement\n");
  info("t    : ");
  value("%zu", segments.size());
  info(" segments\n");

  const pcl::PointCloud<pcl::PointXYZL>::Ptr labeled = seg.getLabeledCloud();
  const pcl::PointCloud<pcl::PointXYZRGB>::Ptr colored = seg.getColoredCloud();
  if (!labeled || labeled->size() != cloud->size()) {
    fail("segmentation of '" + opt.input + "' returned no labelled cloud");
    return 1;
  }
  if (!output.commit(makeOutput(*labeled, *colored)))
    return 1;
  info("Wrote ");
  value("%s", opt.output.c_str());
  info(" (x y z rgb label)\n");
  return 0;
}
