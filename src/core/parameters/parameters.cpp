#include <pcl_ncut_seg/parameter_table.h>
#include <pcl_ncut_seg/parameters.h>

namespace pcl_ncut_seg {

const char* stageName(Stage stage) {
  switch (stage) {
  case Stage::Graph:
    return "graph";
  case Stage::Centrality:
    return "centrality";
  case Stage::Supernodes:
    return "supernodes";
  case Stage::Refinement:
    return "refinement";
  case Stage::Cad:
    return "CAD";
  case Stage::Similarity:
    return "similarity";
  case Stage::Stopping:
    return "stopping";
  case Stage::Boundary:
    return "boundary";
  case Stage::Execution:
    return "execution";
  }
  return "?";
}

Parameters Parameters::paper() {
  Parameters p;
  p.graph.bridge_gap.reset();
  p.graph.denoise.reset();
  p.graph.irregular_sampling.reset();
  p.graph.max_points.reset();
  p.graph.single_view = false;
  p.centrality.mode = CentralityMode::Exact;
  p.centrality.starts = 1;
  p.refinement.crease_split.reset();
  p.similarity.normalize_width = false;
  p.similarity.thickness = false;
  p.similarity.adjacency = Adjacency::Saddles;
  p.similarity.concavity.reset();
  p.similarity.flat_elongation.reset();
  p.stopping.rule = StoppingRule::Threshold;
  p.boundary.band.reset();
  p.boundary.rim_merge.reset();
  return p;
}

bool validate(const Parameters& params, std::string* why) {
  for (const ParameterInfo& row : parameterTable())
    if (!row.check(params, why))
      return false;
  return true;
}

bool analysisDiffers(const Parameters& params, const Parameters& other) {
  for (const ParameterInfo& row : parameterTable())
    if (isAnalysisStage(row.stage) && row.get(params) != row.get(other))
      return true;
  return false;
}

} // namespace pcl_ncut_seg
