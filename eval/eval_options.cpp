#include "eval_options.h"

#include <cli/algorithm_flags.h>

#include <pcl/console/print.h>

#include <sstream>
#include <utility>

namespace pcl_ncut_seg {
namespace eval {

using namespace pcl_ncut_seg::tool;

const std::vector<std::string> kAllMethods = {"ours", "whole",   "lccp", "cpc",
                                              "one",  "octants", "human"};
const std::vector<std::string> kFinestMethods = {"finest", "oracle", "kmeans_oracle"};
const std::vector<std::string> kAllModes = {"auto", "given"};
const std::vector<std::string> kViewForms = {"view", "crop", "voxel", "laser"};

namespace {

/** Every word -methods takes: the default methods and those of the finest level. */
std::vector<std::string> methodWords() {
  std::vector<std::string> words = kAllMethods;
  words.insert(words.end(), kFinestMethods.begin(), kFinestMethods.end());
  return words;
}

std::string numberText(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// ------------------------------------------------------------------------------ command line

/** "1-3,181" as the ids 1, 2, 3, 181; false with the reason. */
bool parseIds(const std::string& text, std::vector<int>& ids, std::string* why) {
  for (const std::string& item : splitList(text)) {
    const std::size_t dash = item.find('-', 1);
    long lo = 0, hi = 0;
    if (!toInt(item.substr(0, dash), lo) ||
        !toInt(dash == std::string::npos ? item : item.substr(dash + 1), hi)) {
      *why = "expected ids and ranges such as 1-3,181";
      return false;
    }
    if (lo < 1 || hi < lo) {
      *why = "bad id range '" + item + "': expected ids >= 1, low-high";
      return false;
    }
    for (long id = lo; id <= hi; ++id)
      ids.push_back(static_cast<int>(id));
  }
  if (ids.empty())
    *why = "no ids";
  return !ids.empty();
}

/** Every item of a list is one of the words; false with the reason. */
bool parseWords(const std::string& text, const std::vector<std::string>& words,
                std::vector<std::string>& items, std::string* why) {
  items = splitList(text);
  for (const std::string& item : items)
    if (std::find(words.begin(), words.end(), item) == words.end()) {
      *why = "unknown '" + item + "'";
      break;
    }
  if (items.empty())
    *why = "an empty list";
  return why->empty();
}

/** A list of numbers in [lo, hi]; false with the reason. */
bool parseNumbers(const std::string& text, double lo, double hi, std::vector<double>& values,
                  std::string* why) {
  for (const std::string& item : splitList(text)) {
    double v = 0;
    if (!toDouble(item, v) || v < lo || v > hi) {
      *why = "'" + item + "' is not a number " +
             (hi > 1e300 ? ">= " + numberText(lo)
                         : "in [" + numberText(lo) + ", " + numberText(hi) + "]");
      return false;
    }
    values.push_back(v);
  }
  if (values.empty())
    *why = "an empty list";
  return !values.empty();
}

/** The evaluator's own flags: what to run, on which models, and the sweeps of 'ours'. */
std::vector<Flag> runFlags() {
  std::vector<Flag> rows = {
      textFlag("-methods", "LIST",
               "of ours,whole,lccp,cpc,one,octants,human (whole: with -views, 'ours whole', ours "
               "on the whole object scored on the faces each view sees), and, only when named, "
               "the finest level's diagnostic: finest (ours asked for -oracle_segments parts), "
               "oracle (finest's segments each merged into the person's segment it overlaps "
               "most, per person: it READS THE PEOPLE'S ANSWERS, a bound, not a method) and "
               "kmeans_oracle (the same merge of k-means of the points with finest's count)",
               "all but finest,oracle,kmeans_oracle"),
      textFlag("-modes", "LIST",
               "of auto,given: the segmenter chooses the number of segments, or gets "
               "nSeg-ByModel.txt's",
               "auto,given"),
      textFlag("-ids", "LIST", "model ids and ranges, e.g. 1-3,181", "every off/<id>.off"),
      textFlag("-thresholds", "LIST",
               "NCut thresholds for 'ours' in auto mode, each its own row (a sweep of "
               "-threshold that reuses each model's expensive stage)",
               "-threshold"),
      intFlag("-oracle_segments", "N",
              "the finest level of finest, oracle and kmeans_oracle: ours asked for N parts "
              "(the hierarchy stops sooner where it has nothing left to split)",
              "30", 1, 10000),
  };
  rows[0].check = [](const std::string& t, std::string* why) {
    std::vector<std::string> items;
    return parseWords(t, methodWords(), items, why);
  };
  rows[1].check = [](const std::string& t, std::string* why) {
    std::vector<std::string> items;
    return parseWords(t, kAllModes, items, why);
  };
  rows[2].check = [](const std::string& t, std::string* why) {
    std::vector<int> ids;
    return parseIds(t, ids, why);
  };
  rows[3].check = [](const std::string& t, std::string* why) {
    std::vector<double> v;
    return parseNumbers(t, 0, 1e308, v, why);
  };
  return rows;
}

/** The view mode: how many views of each model, and the camera. */
std::vector<Flag> viewFlags() {
  const pcl_ncut_seg::CameraSettings cam;
  std::vector<Flag> rows = {
      intFlag("-views", "V",
              "score V seeded depth-camera views of each model instead of the whole object, each "
              "on the faces it sees (ours also on the whole object, on the same faces)",
              "off", 1, 1000),
      textFlag("-resolution", "WxH", "the views' image size in pixels, each side in [8, 4096]",
               std::to_string(cam.width) + "x" + std::to_string(cam.height)),
      realFlag("-view_distance", "D",
               "the camera's distance from the object's centre, in bounding-box diagonals (2: "
               "close, 15-30k points on the object; the default: 1 m from a 0.3 m object)",
               numberText(cam.distance / cam.object_diagonal), 1, 100),
      realFlag("-range_noise", "SIGMA",
               "the views' range noise in metres at 1 m; it grows with the depth squared (0: none)",
               numberText(cam.noise_at_1m), 0, 0.1),
      textFlag("-view_forms", "LIST",
               "of view,crop,voxel,laser: how a view reaches the segmenters, each its own mode: "
               "the organized frame; its valid points (unorganized, NaN-free, as a tabletop "
               "pipeline hands an object over); that crop on a voxel grid of 1% of its "
               "bounding-box diagonal (pcl::VoxelGrid); or as many points as the crop, drawn "
               "uniformly by area on the faces the camera sees, with isotropic noise of 0.002 "
               "diagonals (a laser scanner)",
               "view"),
      textFlag("-view_origin", "known|unknown",
               "the sensor's pose in the clouds (unknown: sensor_origin_ left at 0, the object's "
               "centre, and LCCP's and CPC's normals oriented away from the points' centroid)",
               "known"),
  };
  rows[4].check = [](const std::string& t, std::string* why) {
    std::vector<std::string> items;
    return parseWords(t, kViewForms, items, why);
  };
  rows[5].check = [](const std::string& t, std::string* why) {
    if (t != "known" && t != "unknown")
      *why = "expected known or unknown";
    return why->empty();
  };
  rows[1].check = [](const std::string& t, std::string* why) {
    int w = 0, h = 0;
    if (!pcl_ncut_seg::parseResolution(t, w, h))
      *why = "expected WxH such as 640x480, each side in [8, 4096]";
    return why->empty();
  };
  return rows;
}

/** The view settings; a failure for the flags that the view mode does not take. */
void readViewOptions(const Flags& flags, Options& o) {
  const bool views = flags.has("-views");
  for (const char* name :
       {"-resolution", "-view_distance", "-range_noise", "-view_forms", "-view_origin"})
    if (flags.has(name) && !views)
      throw Failure(std::string(name) + " needs -views");
  if (!views)
    return;
  for (const char* name : {"-modes", "-thresholds"})
    if (flags.has(name))
      throw Failure(std::string("-views scores the automatic mode with the parameters given; "
                                "it takes no ") +
                    name);
  if (o.sampling.active())
    throw Failure("-views renders its own points; it takes no -samples");
  o.views = static_cast<int>(flags.integer("-views"));
  if (flags.has("-resolution"))
    pcl_ncut_seg::parseResolution(flags.text("-resolution"), o.camera.width, o.camera.height);
  if (flags.has("-view_distance"))
    o.camera.distance = flags.real("-view_distance") * o.camera.object_diagonal;
  if (flags.has("-range_noise"))
    o.camera.noise_at_1m = flags.real("-range_noise");
  std::string why;
  if (flags.has("-view_forms"))
    parseWords(flags.text("-view_forms"), kViewForms, o.view_forms, &why);
  o.view_origin_known = !flags.has("-view_origin") || flags.text("-view_origin") == "known";
  o.modes = o.view_forms;
}

/** A text flag that takes one of the words of `choices` ("a|b"). */
Flag choiceFlag(const std::string& name, const std::string& choices, const std::string& help,
                const std::string& def) {
  Flag f = textFlag(name, choices, help, def);
  f.check = [choices](const std::string& text, std::string* why) {
    if (("|" + choices + "|").find("|" + text + "|") != std::string::npos && !text.empty())
      return true;
    *why = "one of " + choices;
    return false;
  };
  return f;
}

/** LCCP's and CPC's settings (psb_peers.h), scaled to the points' bounding-box diagonal. */
std::vector<Flag> peerFlags() {
  const std::string tuned = "-peer_settings' row, else psb_peers.h's PeerParams";
  return {
      textFlag("-peer_settings", "FILE",
               "LCCP's and CPC's settings per peer and input, as scripts/tune_peers.py writes "
               "them (results/peer_settings.csv); the other -peer_* flags apply over them"),
      intFlag("-peer_min_segment", "N",
              "LCCP's and CPC's smallest segment, in supervoxels (smaller ones merge into a "
              "neighbour; 0: none)",
              tuned, 0, 1000),
      realFlag("-peer_seed", "F", "LCCP's and CPC's supervoxel seed resolution, F diagonals", tuned,
               1e-4, 1),
      realFlag("-peer_voxel", "F", "LCCP's and CPC's voxel resolution, F diagonals", tuned, 1e-4,
               1),
      realFlag("-peer_concavity", "DEG", "LCCP's and CPC's concavity tolerance in degrees", tuned,
               0, 90),
      choiceFlag("-peer_normals", "estimated|mesh",
                 "LCCP's and CPC's normals on whole objects: PCL's estimate from the points "
                 "oriented outward by the mesh, or the mesh's face normals (views: always "
                 "estimated, towards the sensor)",
                 tuned),
      choiceFlag("-peer_sanity", "on|off", "LCCP's and CPC's sanity criterion", tuned),
      realFlag("-peer_cut_score", "F", "CPC's smallest score of a cut", tuned, 0, 1),
      intFlag("-peer_max_cuts", "N", "CPC's most cuts per segment", tuned, 0, 1000),
  };
}

/** The -peer_* flags given, over p. */
void applyPeerFlags(const Flags& flags, PeerParams& p) {
  if (flags.has("-peer_min_segment"))
    p.min_segment_size = static_cast<unsigned>(flags.integer("-peer_min_segment"));
  if (flags.has("-peer_seed"))
    p.seed_fraction = flags.real("-peer_seed");
  if (flags.has("-peer_voxel"))
    p.voxel_fraction = flags.real("-peer_voxel");
  if (flags.has("-peer_concavity"))
    p.concavity_tolerance = static_cast<float>(flags.real("-peer_concavity"));
  if (flags.has("-peer_normals"))
    p.normals = flags.text("-peer_normals") == "mesh" ? PeerNormals::Mesh : PeerNormals::Estimated;
  if (flags.has("-peer_sanity"))
    p.sanity_check = flags.text("-peer_sanity") == "on";
  if (flags.has("-peer_cut_score"))
    p.cpc_min_cut_score = static_cast<float>(flags.real("-peer_cut_score"));
  if (flags.has("-peer_max_cuts"))
    p.cpc_max_cuts = static_cast<unsigned>(flags.integer("-peer_max_cuts"));
}

void readPeerOptions(const Flags& flags, Options& o) {
  std::string error;
  if (flags.has("-peer_settings") &&
      !readPeerSettings(flags.text("-peer_settings"), o.peer_settings, &error))
    throw Failure(flags.text("-peer_settings") + ": " + error);
  for (const Flag& f : peerFlags())
    if (flags.has(f.name) && f.name != "-peer_settings")
      o.peer_flags.given[f.name] = flags.text(f.name);
  for (const bool cpc : {false, true})
    for (const bool view : {false, true})
      if (o.peerParams(cpc, view).voxel_fraction >= o.peerParams(cpc, view).seed_fraction)
        throw Failure("-peer_voxel must be smaller than -peer_seed");
}

} // namespace

PeerParams Options::peerParams(bool cpc, bool view) const {
  PeerParams p = peer_settings.of(cpc, view);
  applyPeerFlags(peer_flags, p);
  return p;
}

namespace {

/** The sampling conditions: the points each model is segmented as, instead of its centroids. */
std::vector<Flag> samplingFlags() {
  return {
      intFlag("-samples", "N",
              "segment N points drawn on each mesh, uniformly by area (seeded by model and "
              "draw), instead of one point per face centroid; each face takes the label of its "
              "nearest sample (before noise). 0: the face centroids",
              "0", 0, 1e9),
      intFlag("-draws", "D",
              "independent draws of the samples per model (with -samples); the reports add "
              "spread.csv and the spread of every metric over the draws",
              "1", 1, 1000),
      realFlag("-density_ratio", "R",
               "sample with a density gradient: R times denser at the low end of the mesh's "
               "longest bounding-box axis than at its high end, linear in between (with "
               "-samples)",
               "1", 1, 1e6),
      realFlag("-noise", "S",
               "Gaussian noise, sigma S mean point spacings per coordinate, the spacing being "
               "sqrt(surface area / N) (with -samples)",
               "0", 0, 1e6),
      switchFlag("-permute",
                 "the draws are one sample set in different orders: draw 1 as sampled, the "
                 "others in seeded random orders, labels mapped back (with -samples and -draws "
                 ">= 2)"),
      realFlag("-jitter", "S",
               "the draws are one sample set, draw 1 as sampled, each other moved by Gaussian "
               "noise of sigma S mean spacings per coordinate: how much a change far below any "
               "sensor's noise (1e-4: about a millionth of the model) changes the segments "
               "(with -samples and -draws >= 2)",
               "0", 0, 1e6),
  };
}

/** The sampling options, checked against each other. */
SamplingOptions readSampling(const Flags& flags) {
  SamplingOptions s;
  if (flags.has("-samples"))
    s.samples = static_cast<std::size_t>(flags.integer("-samples"));
  if (flags.has("-draws"))
    s.draws = static_cast<int>(flags.integer("-draws"));
  if (flags.has("-density_ratio"))
    s.density_ratio = flags.real("-density_ratio");
  if (flags.has("-noise"))
    s.noise = flags.real("-noise");
  s.permute = flags.has("-permute");
  if (flags.has("-jitter"))
    s.jitter = flags.real("-jitter");
  if (!s.active())
    for (const char* name : {"-draws", "-density_ratio", "-noise", "-permute", "-jitter"})
      if (flags.has(name))
        throw Failure(std::string(name) + " needs -samples N (N > 0)");
  if (s.permute && s.draws < 2)
    throw Failure("-permute needs -draws 2 or more (draw 1 is the drawn order)");
  if (s.jitter > 0 && s.draws < 2)
    throw Failure("-jitter needs -draws 2 or more (draw 1 is the sample set as drawn)");
  if (s.jitter > 0 && s.permute)
    throw Failure("-jitter and -permute are separate conditions: give one");
  return s;
}

/** The algorithm's defaults in the evaluator: those of the library, on one thread. */
pcl_ncut_seg::Parameters evalDefaults() {
  pcl_ncut_seg::Parameters p;
  p.execution.num_threads = 1;
  return p;
}

} // namespace

std::vector<Flag> evalFlags() {
  std::vector<Flag> table;
  append(table, runFlags(), "evaluation");
  append(table, viewFlags(), "views (57 degrees across, the model scaled to 0.3 m, 1 m away)");
  append(table, samplingFlags(), "sampling conditions");
  append(table, peerFlags(), "LCCP and CPC (every input)");
  append(table, algorithmFlags(evalDefaults()));
  append(table, commonFlags());
  return table;
}

void printHelp() {
  pcl::console::print_info(
      "Syntax: pcl_ncut_seg_eval <psb_dir> <out_dir> [options]\n"
      "Scores segmenters on the Princeton Segmentation Benchmark (points at face centroids,\n"
      "or sampled with -samples) and writes out_dir/models.csv, categories.csv, tables.md\n"
      "(and spread.csv with -draws). The algorithm's options are pcl_ncut_seg's, for 'ours'.\n"
      "With -views V it renders V seeded depth-camera views of each model instead (organized,\n"
      "noisy, NaN where nothing was hit), segments each and scores it on the faces it sees\n"
      "(mode 'view'; 'ours whole': ours on the whole object, scored on the same faces).\n"
      "  where options are:\n");
  printFlags(evalFlags());
}

Options readOptions(const Flags& flags) {
  if (flags.files.size() != 2)
    throw Failure("expected <psb_dir> <out_dir> (see -h)");
  if (flags.has("-thresholds") && flags.has("-threshold"))
    throw Failure("give either -threshold or -thresholds, not both");
  Options o;
  if (!parametersFromFlags(flags, evalDefaults(), o.params))
    throw Failure(""); // said why
  if (o.params.stopping.rule == pcl_ncut_seg::StoppingRule::Count && flags.has("-thresholds"))
    throw Failure("the count rule (-segments) takes no -thresholds");
  o.psb_dir = flags.files[0];
  o.out_dir = flags.files[1];
  std::string why;
  if (flags.has("-methods"))
    parseWords(flags.text("-methods"), methodWords(), o.methods, &why);
  if (flags.has("-modes"))
    parseWords(flags.text("-modes"), kAllModes, o.modes, &why);
  if (flags.has("-ids"))
    parseIds(flags.text("-ids"), o.ids, &why);
  if (flags.has("-thresholds"))
    parseNumbers(flags.text("-thresholds"), 0, 1e308, o.thresholds, &why);
  o.sampling = readSampling(flags);
  o.quiet = flags.has("-quiet");
  if (flags.has("-oracle_segments"))
    o.oracle_segments = static_cast<int>(flags.integer("-oracle_segments"));
  if (flags.has("-oracle_segments") && !o.hasFinest())
    throw Failure("-oracle_segments needs -methods with finest, oracle or kmeans_oracle");
  if (flags.has("-views") && o.hasFinest())
    throw Failure("finest, oracle and kmeans_oracle score whole objects; they take no -views");
  readViewOptions(flags, o);
  readPeerOptions(flags, o);
  return o;
}

} // namespace eval
} // namespace pcl_ncut_seg
