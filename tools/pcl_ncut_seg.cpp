/*
 * pcl_ncut_seg: segment a point-sampled surface into parts with pcl::SupernodeNCutSegmentation
 * (Yamazaki et al., "Segmenting Point-sampled Surfaces") and write the points labelled and
 * coloured by segment.
 *
 *   pcl_ncut_seg [input.pcd|.ply|.off|.obj] [output.pcd] [options]
 *
 * With no input, segments the bundled model armadillo.pcd and writes armadillo_segments.pcd.
 */
#include "cli/algorithm_flags.h"
#include "cli/console.h"
#include "cli/flags.h"
#include "cli/input.h"
#include "cli/output.h"
#include "cli/paths.h"
#include "cli/progress.h"
#include "files/values.h"

#include <pcl/PCLPointCloud2.h>
#include <pcl/console/print.h>

#include <malloc.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <exception>
#include <limits>
#include <memory>
#include <string>
#include <vector>

using namespace pcl::console;
using namespace pcl_ncut_seg::tool;

namespace {

/** Every flag of the tool: the algorithm's, the mesh sampling's, the output's. */
std::vector<Flag> toolFlags() {
  std::vector<Flag> table = algorithmFlags();
  append(table, meshFlags());
  append(table,
         {switchFlag("-add", "keep every field of the input and add label (instead of writing x "
                             "y z rgb label)"),
          switchFlag("-ascii", "write ASCII PCD files (with enough digits to read back every "
                               "value exactly) instead of binary ones"),
          switchFlag("-binary",
                     "binary PCD files, the default: changes nothing, accepted for "
                     "older scripts",
                     ""),
          textFlag("-split", "PREFIX",
                   "also write each segment to PREFIX_<label>.pcd (same fields)", "off")},
         "output");
  append(table, commonFlags());
  return table;
}

void printHelp(const char* name) {
  print_info("Syntax is: %s [input] [output.pcd] <options>\n", name);
  print_info("Segments a point-sampled surface into parts (Yamazaki et al., \"Segmenting "
             "Point-sampled Surfaces\") and\nwrites the points as a binary PCD (-ascii: text) with "
             "fields x y z rgb label (label 1..t per\nsegment, 0 for points in no segment).\n");
  print_info("The input is a point cloud (.pcd, .ply) or a mesh (.off, .obj, .ply with faces); a "
             "mesh becomes one point\nper face centroid, or -samples N points sampled uniformly "
             "by area.\n");
  print_info("With no input, segments the bundled model armadillo.pcd and writes "
             "armadillo_segments.pcd in "
             "the current directory.\nWith an input and no output, writes <input "
             "name>_segments.pcd in the current directory.\n");
  print_info("  where options are:\n");
  printFlags(toolFlags());
}

bool g_quiet = false; // -quiet: errors and warnings only

// Results on stdout, unless -quiet.
template <typename... Args> void info(const char* format, Args... args) {
  if (!g_quiet)
    print_info(format, args...);
}
template <typename... Args> void value(const char* format, Args... args) {
  if (!g_quiet)
    print_value(format, args...);
}

/** A field of a point cloud blob, 4 bytes, appended to the layout. */
void addField(pcl::PCLPointCloud2& blob, const char* name, std::uint8_t type) {
  pcl::PCLPointField field;
  field.name = name;
  field.offset = blob.point_step;
  field.datatype = type;
  field.count = 1;
  blob.fields.push_back(field);
  blob.point_step += 4;
}

std::size_t fieldSize(const pcl::PCLPointField& f) {
  return pcl_ncut_seg::files::typeSize(f.datatype) * std::max<std::uint32_t>(f.count, 1);
}

/** The output cloud. By default exactly x y z (float, the points as read) rgb label, whatever
 * the input's types and order of fields; with keep_fields, every field of the input except an
 * old label, then label. rgb is packed into a float as pcl::PointXYZRGB stores it (alpha 0),
 * so pcl_viewer colours the points by segment; label 0 is black. */
pcl::PCLPointCloud2 makeOutput(const Input& input, const std::vector<std::uint32_t>& labels,
                               bool keep_fields) {
  pcl::PCLPointCloud2 blob;
  blob.header = input.blob.header;
  blob.width = input.blob.width;
  blob.height = input.blob.height;
  blob.is_dense = input.blob.is_dense;
  blob.is_bigendian = false;
  blob.point_step = 0;
  // Fields to copy from the input's blob, or from its points: (input offset, output offset, size).
  struct Copy {
    std::size_t from, to, size;
  };
  std::vector<Copy> copies;
  // x, y, z of pcl::PointXYZ (offsets 0, 4, 8): the points as read and segmented.
  const std::vector<pcl::PCLPointField> xyz = pcl_ncut_seg::files::xyzCloud(0, 0).fields;
  for (const pcl::PCLPointField& f : keep_fields ? input.blob.fields : xyz) {
    if (f.name == "label")
      continue;
    pcl::PCLPointField out = f;
    out.offset = blob.point_step;
    blob.fields.push_back(out);
    copies.push_back({f.offset, out.offset, fieldSize(f)});
    blob.point_step += static_cast<std::uint32_t>(fieldSize(f));
  }
  if (!keep_fields)
    addField(blob, "rgb", pcl::PCLPointField::FLOAT32);
  const std::size_t rgb_offset = blob.point_step - 4;
  addField(blob, "label", pcl::PCLPointField::UINT32);
  const std::size_t label_offset = blob.point_step - 4;
  blob.row_step = blob.point_step * blob.width;

  const std::size_t n = labels.size();
  blob.data.resize(static_cast<std::size_t>(blob.point_step) * n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto* in = keep_fields ? &input.blob.data[i * input.blob.point_step]
                                 : reinterpret_cast<const std::uint8_t*>((*input.cloud)[i].data);
    std::uint8_t* out = &blob.data[i * blob.point_step];
    for (const Copy& c : copies)
      std::memcpy(out + c.to, in + c.from, c.size);
    const std::uint32_t label = labels[i];
    if (!keep_fields) {
      std::uint8_t r = 0, g = 0, b = 0; // black for points in no segment
      if (label != 0)
        Segmenter::segmentColor(label - 1, r, g, b);
      const std::uint32_t rgb = (std::uint32_t(r) << 16) | (std::uint32_t(g) << 8) | b;
      std::memcpy(out + rgb_offset, &rgb, 4);
    }
    std::memcpy(out + label_offset, &label, 4);
  }
  return blob;
}

/** The points of one segment, as an unorganised cloud with the same fields. */
pcl::PCLPointCloud2 subset(const pcl::PCLPointCloud2& blob,
                           const std::vector<std::size_t>& points) {
  pcl::PCLPointCloud2 out;
  out.header = blob.header;
  out.fields = blob.fields;
  out.point_step = blob.point_step;
  out.is_bigendian = blob.is_bigendian;
  out.width = static_cast<std::uint32_t>(points.size());
  out.height = 1;
  out.row_step = out.point_step * out.width;
  out.is_dense = true;
  out.data.resize(static_cast<std::size_t>(out.point_step) * points.size());
  for (std::size_t k = 0; k < points.size(); ++k)
    std::memcpy(&out.data[k * out.point_step], &blob.data[points[k] * blob.point_step],
                blob.point_step);
  return out;
}

std::string fieldNames(const pcl::PCLPointCloud2& blob) {
  std::string names;
  for (const auto& f : blob.fields)
    names += (names.empty() ? "" : " ") + f.name;
  return names;
}

/** What the command line asks for, besides the algorithm's parameters. */
struct Command {
  std::string input_path, output_path, split_prefix; ///< split_prefix: "" for no -split
  bool bundled = false;                              ///< the bundled model, for no input
  bool keep_fields = false;                          ///< -add
  PcdEncoding encoding = PcdEncoding::Binary;
  MeshSampling sampling;
};

/** The files and the output options of the command line; false with one error line. */
bool readCommand(const Flags& flags, Command& cmd) {
  if (flags.files.size() > 2) {
    fail("too many file arguments: expected [input] [output.pcd], got '" + flags.files[2] +
         "' as a third");
    return false;
  }
  if (flags.has("-ascii") && flags.has("-binary")) {
    fail("give either -ascii or -binary (the default), not both");
    return false;
  }
  cmd.bundled = flags.files.empty();
  cmd.input_path = cmd.bundled ? findBundledModel() : flags.files[0];
  if (cmd.input_path.empty())
    return false;
  if (!isInputFile(cmd.input_path)) {
    fail("input '" + cmd.input_path + "' is not a " + kInputFormats + " file");
    return false;
  }
  cmd.output_path =
      flags.files.size() == 2 ? flags.files[1] : stem(cmd.input_path) + "_segments.pcd";
  if (extension(cmd.output_path) != ".pcd") {
    fail("output '" + cmd.output_path + "' must be a .pcd file");
    return false;
  }
  cmd.split_prefix = flags.has("-split") ? flags.text("-split") : "";
  cmd.keep_fields = flags.has("-add");
  cmd.encoding = flags.has("-ascii") ? PcdEncoding::Ascii : PcdEncoding::Binary;
  cmd.sampling = meshSampling(flags);
  return true;
}

/** The output files, claimed before the long computation so that an unwritable destination
 * fails first. The segment files of -split are opened when their number is known. */
struct Outputs {
  AtomicFile labelled;
  std::vector<std::unique_ptr<AtomicFile>> segments;
};

bool claimOutputs(const Command& cmd, Outputs& outputs) {
  if (!outputs.labelled.open(cmd.output_path))
    return false;
  AtomicFile probe; // removed at once: -split's directory is writable
  return cmd.split_prefix.empty() || probe.open(cmd.split_prefix + "_1.pcd");
}

bool readInput(const Command& cmd, ProgressBar& progress, Input& input) {
  progress.update("Read", 0.0);
  if (!loadInput(cmd.input_path, cmd.sampling, input))
    return false;
  progress.update("Read", 1.0);
  return true;
}

/** Say what is segmented (and warn when -add replaces a label field). */
void announceInput(const Command& cmd, const Input& input) {
  if (cmd.keep_fields && std::any_of(input.blob.fields.begin(), input.blob.fields.end(),
                                     [](const pcl::PCLPointField& f) { return f.name == "label"; }))
    warn("'" + cmd.input_path + "' already has a label field; -add replaces it");
  info("Segmenting ");
  value("%s", cmd.input_path.c_str());
  info(cmd.bundled ? " (bundled model): " : ": ");
  value("%s", input.description.c_str());
  if (input.mesh) {
    info(": ");
    value("%zu", input.cloud->size());
    info(" points");
  }
  info("\n");
}

/** Segment the input; false with one error line when there is no result. */
bool segment(const Command& cmd, const Input& input, ProgressBar& progress, Segmenter& seg,
             std::vector<pcl::PointIndices>& segments, std::vector<std::uint32_t>& labels) {
  seg.setInputCloud(input.cloud);
  seg.setProgressCallback(progress.callback());
  try {
    seg.extract(segments);
  } catch (const std::exception& e) {
    fail(std::string("segmentation failed: ") + e.what());
    return false;
  }
  if (segments.empty()) {
    fail("segmentation of '" + cmd.input_path + "' produced no segments");
    return false;
  }
  // Label s + 1 for the points of segment s (getLabeledCloud()'s labels, without its copy of
  // the points), 0 for points in none.
  labels.assign(input.cloud->size(), 0);
  for (std::size_t s = 0; s < segments.size(); ++s)
    for (const auto i : segments[s].indices)
      labels[static_cast<std::size_t>(i)] = static_cast<std::uint32_t>(s + 1);
  return true;
}

/** Table 1 of the paper: the time of each phase, then n, m, l, t; and the peak memory. */
void printReport(const Segmenter& seg, std::size_t num_segments) {
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
  const struct {
    const char* name;
    std::size_t count;
    const char* what;
  } counts[] = {{"n", seg.getAnalysedIndices().size(), "points analysed"},
                {"m", seg.getNumberOfSupernodes(false), "supernodes"},
                {"l", seg.getNumberOfSupernodes(true), "supernodes after refinement"},
                {"t", num_segments, "segments"}};
  for (const auto& count : counts) {
    info("%-5s: ", count.name);
    value("%zu", count.count);
    info(" %s\n", count.what);
  }
  const pcl_ncut_seg::NoiseTest noise = seg.getNoiseTest();
  if (noise.residual_growth > 0.0) {
    info("noise: residual growth ");
    value("%.2f", noise.residual_growth);
    info(noise.projected ? " (noisy: points projected onto their local planes)\n"
                         : " (no projection)\n");
  }
  const pcl_ncut_seg::ViewTest view = seg.getViewTest();
  info("view: ");
  if (view.view) {
    info("one view from ");
    info("%s",
         view.origin_estimated ? "a sensor position read off the points" : "the sensor origin");
    info(", rim of ");
    value("%zu", view.rim_points);
    info(" points\n");
  } else {
    info("not a single view\n");
  }
  if (noise.sampling_irregularity > 0.0) {
    info("spacing: irregularity ");
    value("%.3f", noise.sampling_irregularity);
    info(noise.irregular ? " (irregular: centrality averaged once)\n" : " (even)\n");
  }
  info("mem  : ");
  value("%.1f", static_cast<double>(peakMemoryBytes()) / (1024.0 * 1024.0));
  info(" MiB peak resident memory\n");
}

/** -split: each segment to PREFIX_<label>.pcd, labels zero-padded to the same width. */
bool writeSegmentFiles(const Command& cmd, const pcl::PCLPointCloud2& blob,
                       const SensorPose& sensor, const std::vector<std::uint32_t>& labels,
                       std::size_t num_segments, Outputs& outputs) {
  std::vector<std::vector<std::size_t>> members(num_segments);
  for (std::size_t i = 0; i < labels.size(); ++i)
    if (labels[i] != 0)
      members[labels[i] - 1].push_back(i);
  const int digits = static_cast<int>(std::to_string(num_segments).size());
  for (std::size_t s = 0; s < num_segments; ++s) {
    char number[32];
    std::snprintf(number, sizeof(number), "%0*zu", digits, s + 1);
    outputs.segments.emplace_back(new AtomicFile);
    AtomicFile& file = *outputs.segments.back();
    if (!file.open(cmd.split_prefix + "_" + number + ".pcd") ||
        !writePcd(file, subset(blob, members[s]), cmd.encoding, sensor))
      return false;
  }
  return true;
}

/** Write every output, then give them their names, only once all are complete. */
bool writeOutputs(const Command& cmd, const Input& input, const std::vector<std::uint32_t>& labels,
                  std::size_t num_segments, ProgressBar& progress, Outputs& outputs) {
  progress.update("Write", 0.0);
  const pcl::PCLPointCloud2 blob = makeOutput(input, labels, cmd.keep_fields);
  if (!writePcd(outputs.labelled, blob, cmd.encoding, input.sensor) ||
      (!cmd.split_prefix.empty() &&
       !writeSegmentFiles(cmd, blob, input.sensor, labels, num_segments, outputs)))
    return false;
  if (!outputs.labelled.commit())
    return false;
  for (auto& file : outputs.segments)
    if (!file->commit())
      return false;
  progress.update("Write", 1.0);
  info("Wrote ");
  value("%s", cmd.output_path.c_str());
  info(" (%s, %s)\n", fieldNames(blob).c_str(),
       cmd.encoding == PcdEncoding::Binary ? "binary" : "ASCII");
  if (!outputs.segments.empty()) {
    info("Wrote ");
    value("%zu", outputs.segments.size());
    info(" segment files ");
    value("%s", outputs.segments.front()->path().c_str());
    info(" .. ");
    value("%s", outputs.segments.back()->path().c_str());
    info("\n");
  }
  return true;
}

} // namespace

int main(int argc, char** argv) {
  // The stages' large arrays come and go: keep freed memory for the next one rather than
  // return it to the system and fault it in again (a tenth of the time at 1M points; the same
  // peak). Arrays above 32 MB are still mapped and unmapped whole.
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, std::numeric_limits<int>::max());
  Flags flags;
  if (!parseFlags(argc, argv, toolFlags(), flags))
    return 1;
  if (flags.has("-h")) {
    printHelp(argv[0]);
    return 0;
  }
  if (flags.has("-version")) {
    printVersion();
    return 0;
  }
  if (flags.has("-quiet")) {
    g_quiet = true;
    setVerbosityLevel(L_WARN);
  }
  Command cmd;
  Segmenter seg;
  if (!readCommand(flags, cmd) || !applyAlgorithmFlags(flags, seg))
    return 1;
  ProgressBar progress(progressWanted(flags));
  Input input;
  Outputs outputs;
  std::vector<pcl::PointIndices> segments;
  if (!readInput(cmd, progress, input) || !claimOutputs(cmd, outputs))
    return 1;
  announceInput(cmd, input);
  std::vector<std::uint32_t> labels;
  if (!segment(cmd, input, progress, seg, segments, labels))
    return 1;
  printReport(seg, segments.size());
  return writeOutputs(cmd, input, labels, segments.size(), progress, outputs) ? 0 : 1;
}
