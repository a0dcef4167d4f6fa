/*
 * pcl_ncut_seg tools: what the command-line tool and the viewer share. A table of flags (one
 * line per flag), reading a point cloud or a mesh sampled into points, writing a file in one
 * step, a progress bar on stderr, and one-line errors.
 */
#pragma once

#include <pcl_ncut_seg/supernode_ncut_segmentation.h>

#include <pcl/PCLPointCloud2.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace pcl_ncut_seg {
namespace tool {

using Segmenter = pcl::SupernodeNCutSegmentation<pcl::PointXYZ>;

/** \brief One error line on stderr, in PCL's style ("Error: ..."). */
void fail(const std::string& message);
/** \brief One warning line on stderr ("Warning: ..."). */
void warn(const std::string& message);

/// \name Flags
/// \{
enum class FlagKind { Switch, Integer, Real, Text };

/** \brief A command-line flag: its name, what it takes, its range and its help line. */
struct Flag {
  std::string name;  ///< "-k"
  FlagKind kind;     ///< a switch, or the kind of its value
  std::string value; ///< the value's name in the help ("K"), empty for a switch
  std::string help;  ///< what it does, with its range
  std::string def;   ///< its default, for the help ("" for none)
  double lo = 0, hi = 0;
  bool open_lo = false; ///< lo itself is out of range
  std::string range;    ///< the range in words, for the error ("an integer >= 2")
};

/** \brief Switch / value flag builders, so that a table row stays one line. */
Flag switchFlag(const std::string& name, const std::string& help, const std::string& def = "off");
Flag intFlag(const std::string& name, const std::string& value, const std::string& help,
             const std::string& def, double lo, double hi = 1e300);
Flag realFlag(const std::string& name, const std::string& value, const std::string& help,
              const std::string& def, double lo, double hi = 1e300, bool open_lo = false);
Flag textFlag(const std::string& name, const std::string& value, const std::string& help,
              const std::string& def = "");

/** \brief The parsed command line: flags given (each at most once) and the file arguments. */
struct Flags {
  std::map<std::string, std::string> given; ///< flag -> its text ("" for a switch)
  std::vector<std::string> files;

  bool has(const std::string& name) const { return given.count(name) > 0; }
  long integer(const std::string& name) const;
  double real(const std::string& name) const;
  const std::string& text(const std::string& name) const { return given.at(name); }
};

/** \brief Parse argv against the table; on a bad command line (unknown flag, missing or out of
 * range value, flag given twice) print one error line and return false. */
bool parseFlags(int argc, char** argv, const std::vector<Flag>& table, Flags& flags);

/** \brief The help lines of the flags in the table. */
void printFlags(const std::vector<Flag>& table);

/** \brief The algorithm's parameters as flags, with the library's defaults. */
std::vector<Flag> algorithmFlags();
/** \brief Sampling a mesh input into points: -samples, -seed. */
std::vector<Flag> meshFlags();
/** \brief -quiet and -h. */
std::vector<Flag> commonFlags();

/** \brief Set the segmenter's parameters from the algorithm flags given; false with one error
 * line when they contradict each other. */
bool applyAlgorithmFlags(const Flags& flags, Segmenter& seg);
/// \}

/** \brief Where the bundled model armadillo.pcd is, or "" with one error line. */
std::string findBundledModel();

/// \name Input
/// \{
/** \brief What was read: every field of the file (for a mesh: x, y, z of the points sampled on
 * it), and the x, y, z as PCL points. */
struct Input {
  pcl::PCLPointCloud2 blob;
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud;
  bool mesh = false;
  std::size_t num_faces = 0; ///< of a mesh
  std::string description;   ///< "8000 points" or "mesh of 500 faces, ..."
};

/** \brief Input formats, for messages. */
extern const char* const kInputFormats;

/** \brief True for a file name the tools read (.pcd, .ply, .off, .obj). */
bool isInputFile(const std::string& path);

/** \brief Read a .pcd, a .ply (points, or a mesh when it has faces), an .off or an .obj mesh.
 * A mesh becomes one point per face centroid, or with -samples N, N area-uniform samples
 * (-seed S). On failure print one error line and return false. */
bool loadInput(const std::string& path, const Flags& flags, Input& input);
/// \}

/// \name Output
/// \{
/** \brief A temporary file beside the target, renamed over it by commit() and removed
 * otherwise, so that a failed run leaves no file behind. */
class AtomicFile {
public:
  AtomicFile() = default;
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile();

  /** \brief Create the temporary file; one error line and false if that cannot be done. */
  bool open(const std::string& path);
  const std::string& temporaryPath() const { return tmp_; }
  const std::string& path() const { return path_; }
  /** \brief Rename the temporary file over the target; one error line on failure. */
  bool commit();

private:
  std::string path_, tmp_;
};

/** \brief Write a cloud as PCD to the file's temporary path (binary, or ASCII with enough
 * digits to read back every value); one error line on failure. */
bool writePcd(AtomicFile& file, const pcl::PCLPointCloud2& blob, bool binary);
/// \}

/// \name Progress and resources
/// \{
/** \brief A progress bar on stderr for phases that take longer than a delay (1 s, or the
 * PCL_NCUT_SEG_PROGRESS_DELAY environment variable in seconds). A background thread redraws
 * it every 100 ms; a report redraws it at once when the phase's first fraction arrives or the
 * last drawing is 100 ms old. The line is cleared when the phase ends. Does nothing when disabled. */
class ProgressBar {
public:
  explicit ProgressBar(bool enabled);
  ~ProgressBar();
  /** \brief 0 starts a phase, 1 ends it; values in between say how far it is. */
  void update(const char* phase, double fraction);
  /** \brief The callback for SupernodeNCutSegmentation::setProgressCallback. */
  std::function<void(const char*, double)> callback();

private:
  void run();
  void draw(bool final_clear);

  bool enabled_;
  double delay_ = 1.0;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::thread thread_;
  bool stop_ = false;
  std::string phase_;
  double fraction_ = 0;
  bool known_ = false; ///< a fraction strictly inside (0, 1) was reported for this phase
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
};

/** \brief True when stderr is a terminal and -quiet is not given. */
bool progressWanted(const Flags& flags);

/** \brief Peak resident memory of this process so far, in bytes (getrusage). */
std::uint64_t peakMemoryBytes();
/// \}

/** \brief Silences PCL's own console messages while in scope. */
class SilencePcl {
public:
  SilencePcl();
  ~SilencePcl();

private:
  int level_;
};

/** \brief Path helpers. */
std::string extension(const std::string& path); ///< lower case, with the dot
std::string stem(const std::string& path);      ///< file name without directory and extension
std::string directoryOf(const std::string& path);

} // namespace tool
} // namespace pcl_ncut_seg
