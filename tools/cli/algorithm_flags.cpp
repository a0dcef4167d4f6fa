#include "cli/algorithm_flags.h"

#include "cli/console.h"

#include <sstream>
#include <string>

namespace pcl_ncut_seg {
namespace tool {

namespace {
std::string formatNumber(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

/** The row with an old spelling (the evaluator's) that is read as its name. */
Flag alias(Flag flag, const std::vector<std::string>& aliases) {
  flag.aliases = aliases;
  return flag;
}
} // namespace

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
      alias(realFlag("-gap_floor", "F",
                     "largest-gap stopping rule: NCut values below F count as F, > 0",
                     num(d.getGapFloor()), 0, 1e308, true),
            {"-gapfloor"}),
      alias(intFlag("-max_segments", "K", "largest-gap stopping rule: at most K segments, >= 1",
                    num(d.getMaxSegments()), 1),
            {"-maxseg"}),
      alias(
          realFlag("-adjacent_share", "S",
                   "join touching supernodes that meet at no saddle when their contact is at least "
                   "this share of the smaller total contact, in [0, 1]",
                   num(d.getAdjacentShare()), 0, 1),
          {"-share"}),
      alias(realFlag("-bridge_gap", "G",
                     "join kNN-graph components whose shortest link is at most G kNN radii long "
                     "(sampling gaps), >= 0; 0 = never",
                     num(d.getBridgeGap()), 0),
            {"-bridge"}),
      realFlag("-concavity", "W",
               "concave creases: the weight between touching supernodes is multiplied by "
               "exp(-W c), c how concave their contact is, >= 0; 0 = off",
               num(d.getConcavityWeight()), 0),
      realFlag("-flat", "E",
               "flat patches: between two supernodes with feature height < E sqrt(feature "
               "area), eq. (9) leaves out the width ratio, >= 0; 0 = off",
               num(d.getFlatElongation()), 0),
      alias(
          realFlag("-neck_exponent", "W",
                   "short-cut stopping rule: a split's NCut is weighted by neck^W (boundary length "
                   "over sqrt of the smaller side's area), >= 0; 0 = the largest jump in NCut",
                   num(d.getNeckExponent()), 0),
          {"-neck"}),
      alias(realFlag(
                "-neck_bound", "K",
                "short-cut stopping rule: weighted NCut below which a split is worth making, > 0",
                num(d.getNeckBound()), 0, 1e308, true),
            {"-neckbound"}),
      alias(realFlag("-boundary_band", "F",
                     "boundary refinement: recut each pair of touching segments by a minimum cut "
                     "within a band holding at most this fraction of either segment, in [0, 0.5]; "
                     "0 = off",
                     num(d.getBoundaryBand()), 0, 0.5),
            {"-band"}),
      alias(realFlag("-boundary_crease", "W",
                     "boundary refinement: a kNN edge's cut cost is its length times exp(-W c), c "
                     "its concave bend, >= 0",
                     num(d.getBoundaryCreaseWeight()), 0),
            {"-bandcrease"}),
      realFlag("-crease", "C",
               "crease splits: split a supernode along its most concave level cut of the "
               "centrality when that cut's mean concave bend is >= C, >= 0; 0 = off",
               num(d.getCreaseSplit()), 0),
      alias(realFlag("-crease_cut", "S",
                     "crease cuts: split a supernode no level cut splits along its minimum cut "
                     "weighted by concave bend when a share >= S of the edges it crosses are "
                     "concave, in [0, 1]; 0 = off",
                     num(d.getCreaseCut()), 0, 1),
            {"-creasecut"}),
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

} // namespace tool
} // namespace pcl_ncut_seg
