/*
 * pcl_ncut_seg: part segmentation of point-sampled surfaces.
 *
 * Implements I. Yamazaki, V. Natarajan, Z. Bai, B. Hamann, "Segmenting Point-sampled Surfaces":
 * centrality from geodesic distances on a kNN graph (Sec. 4.1), supernodes from its gradient
 * flow with saddles (4.2), local refinement (4.3), then recursive normalized-cut bisection of a
 * graph of supernodes (5).
 */
#pragma once

#include <pcl/PointIndices.h>
#include <pcl/pcl_base.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/search/search.h>

#include <pcl_ncut_seg/analysis_report.h>
#include <pcl_ncut_seg/parameters.h>
#include <pcl_ncut_seg/segment_points.h>
#include <pcl_ncut_seg/segment_tree.h>
#include <pcl_ncut_seg/status.h>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace pcl {

/** \brief Segments a point-sampled surface into parts (the fingers of a hand, the legs of a
 * horse) with the method of Yamazaki et al., "Segmenting Point-sampled Surfaces".
 *
 * Usage:
 * \code
 * pcl::SupernodeNCutSegmentation<pcl::PointXYZ> seg;
 * seg.setInputCloud(cloud);
 * seg.setNumberOfNeighbours(10);
 * std::vector<pcl::PointIndices> segments;
 * seg.extract(segments);
 * \endcode
 *
 * The work runs in two stages. The expensive one (kNN graph, centrality, supernodes and their
 * refinement) is computed once per input; changing only the cut parameters (threshold, number
 * of segments, alpha1, alpha2, beta, split values) and calling extract() again reuses it.
 * A new input cloud, new indices, a new search method or a change of any analysis parameter
 * invalidates it.
 *
 * Points with a non-finite coordinate are in no segment. Output indices refer to the input
 * cloud, also when indices are set.
 */
template <typename PointT> class SupernodeNCutSegmentation : public pcl::PCLBase<PointT> {
public:
  using PointCloud = pcl::PointCloud<PointT>;
  using PointCloudConstPtr = typename PointCloud::ConstPtr;
  using KdTree = pcl::search::Search<PointT>;
  using KdTreePtr = typename KdTree::Ptr;

  using PCLBase<PointT>::input_;
  using PCLBase<PointT>::indices_;
  using PCLBase<PointT>::fake_indices_;
  using PCLBase<PointT>::initCompute;
  using PCLBase<PointT>::deinitCompute;

  SupernodeNCutSegmentation();
  ~SupernodeNCutSegmentation() override;

  /** \brief Provide the input cloud; invalidates the expensive stage.
   * \param[in] cloud  the points (NaN points are in no segment) */
  void setInputCloud(const PointCloudConstPtr& cloud) override;
  /** \brief Restrict the segmentation to these points; invalidates the expensive stage.
   * \param[in] indices  indices into the input cloud (output indices still refer to it) */
  void setIndices(const IndicesPtr& indices) override;
  void setIndices(const IndicesConstPtr& indices) override;
  void setIndices(const PointIndicesConstPtr& indices) override;

  /** \brief Search method for the kNN graph (default: FLANN's kd-tree with the index and
   * parameters of pcl::search::KdTree, so the same neighbours, built in extract() over a compact
   * copy of the points, queried in parallel and released once the graph is built;
   * getSearchMethod() then returns null).
   * \param[in] search  any pcl::search::Search over the input's point type */
  void setSearchMethod(const KdTreePtr& search);
  KdTreePtr getSearchMethod() const { return search_; }

  /** \brief All parameters at once (pcl_ncut_seg::Parameters; see its stages and the README's
   * table). Invalid parameters print a PCL_ERROR naming the first bad one and change nothing.
   * A change in an analysis stage (graph, centrality, supernodes, refinement, CAD) invalidates
   * the expensive stage; other changes re-cut the kept one.
   * \param[in] params  e.g. pcl_ncut_seg::Parameters::paper() for the paper to the letter
   * \return whether the parameters were taken */
  bool setParameters(const pcl_ncut_seg::Parameters& params);
  /** \brief The parameters in use. */
  const pcl_ncut_seg::Parameters& getParameters() const { return params_; }

  /// \name Single parameters
  /// Thin wrappers of setParameters(): each sets one field of pcl_ncut_seg::Parameters (its
  /// meaning, default and range are documented there and in the README's table), rejects a bad
  /// value with a PCL_ERROR and keeps the old one. An extension that can be off takes and
  /// returns a std::optional: std::nullopt turns it off, and 0, where the range leaves it
  /// out, is rejected like any other bad value.
  /// \{
  /** \param[in] k  graph.k, >= 2 */
  void setNumberOfNeighbours(int k);
  int getNumberOfNeighbours() const { return params_.graph.k; }
  /** \param[in] samples  centrality.samples, >= 1; std::nullopt: ceil(sqrt(n)) as in the paper */
  void setNumberOfSamples(std::optional<int> samples);
  std::optional<int> getNumberOfSamples() const { return params_.centrality.samples; }
  /** \param[in] mode  centrality.mode */
  void setCentralityMode(pcl_ncut_seg::CentralityMode mode);
  pcl_ncut_seg::CentralityMode getCentralityMode() const { return params_.centrality.mode; }
  /** \param[in] starts  centrality.starts, in [1, 16]; 1: one start of the farthest-point
   * sampling, as the paper. CAD mode and open views (a cloud with a rim) use one. */
  void setStarts(int starts);
  int getStarts() const { return params_.centrality.starts; }
  /** \param[in] fraction  supernodes.crossing_fraction, in [0, 1] */
  void setCrossingFraction(float fraction);
  float getCrossingFraction() const { return params_.supernodes.crossing_fraction; }
  /** \param[in] fraction  refinement.area_fraction, in [0, 1] */
  void setAreaFraction(float fraction);
  float getAreaFraction() const { return params_.refinement.area_fraction; }
  /** \param[in] fraction  refinement.height_fraction, in [0, 1] */
  void setHeightFraction(float fraction);
  float getHeightFraction() const { return params_.refinement.height_fraction; }
  /** \param[in] beta  similarity.beta, > 0 */
  void setBeta(double beta);
  double getBeta() const { return params_.similarity.beta; }
  /** \param[in] alpha1  similarity.alpha1, > 0 */
  void setAlpha1(double alpha1);
  double getAlpha1() const { return params_.similarity.alpha1; }
  /** \param[in] alpha2  similarity.alpha2, > 0 */
  void setAlpha2(double alpha2);
  double getAlpha2() const { return params_.similarity.alpha2; }
  /** \param[in] threshold  stopping.threshold, >= 0 */
  void setThreshold(double threshold);
  double getThreshold() const { return params_.stopping.threshold; }
  /** \param[in] rule  stopping.rule */
  void setStoppingRule(pcl_ncut_seg::StoppingRule rule);
  pcl_ncut_seg::StoppingRule getStoppingRule() const { return params_.stopping.rule; }
  /** \param[in] segments  stopping.max_segments, >= 1 */
  void setMaxSegments(int segments);
  int getMaxSegments() const { return params_.stopping.max_segments; }
  /** \param[in] bound  stopping.neck_bound, > 0 */
  void setNeckBound(double bound);
  double getNeckBound() const { return params_.stopping.neck_bound; }
  /** \brief Ask for a number of segments: stopping.segments, and the count rule (as the tools'
   * -segments). Another rule is chosen with setStoppingRule().
   * \param[in] segments  stopping.segments, >= 1 */
  void setNumberOfSegments(int segments);
  /** \brief stopping.segments, which only the count rule reads (getStoppingRule()). */
  int getNumberOfSegments() const { return params_.stopping.segments; }
  /** \param[in] normalize  similarity.normalize_width */
  void setNormalizeWidth(bool normalize);
  bool getNormalizeWidth() const { return params_.similarity.normalize_width; }
  /** \param[in] adjacency  similarity.adjacency */
  void setAdjacency(pcl_ncut_seg::Adjacency adjacency);
  pcl_ncut_seg::Adjacency getAdjacency() const { return params_.similarity.adjacency; }
  /** \param[in] cad  cad.enabled: CAD mode (Sec. 7); normals come from the input when the
   * point type has finite ones, else from PCL's estimation over the kNN neighbourhoods */
  void setCadMode(bool cad);
  bool getCadMode() const { return params_.cad.enabled; }
  /** \param[in] radii  graph.bridge_gap, > 0; std::nullopt: off */
  void setBridgeGap(std::optional<double> radii);
  std::optional<double> getBridgeGap() const { return params_.graph.bridge_gap; }
  /** \brief Sensor noise (core/graph/denoise.h): a cloud whose local plane fits scatter less than
   * growth times more over the 2-ring than over the 1-ring counts as noisy, and its points are
   * projected onto their 2-ring's planes before anything is measured.
   * \param[in] growth  graph.denoise, > 1; std::nullopt: off */
  void setDenoise(std::optional<double> growth);
  std::optional<double> getDenoise() const { return params_.graph.denoise; }
  /** \brief Irregular sampling (core/graph/denoise.h): when the points' spacings vary at least this
   * much (samplingIrregularity(): about 0.45 for points drawn at random, 0.05-0.2 for points
   * spread evenly; 0.3 between them), the centrality of a whole surface is averaged over each
   * point's neighbourhood once, as on a noisy one. 0.3 by default (docs/sampling.md).
   * \param[in] variation  graph.irregular_sampling, > 0 (default 0.3); std::nullopt: off (the
   * paper) */
  void setIrregularSampling(std::optional<double> variation);
  std::optional<double> getIrregularSampling() const { return params_.graph.irregular_sampling; }
  /** \brief The analysis' resolution (core/graph/subsample.h): a cloud of more distinct points is
   * analysed on an even subset of at most this many (one per cube of a grid, whatever their
   * order), and every other point takes the segment of its nearest analysed point.
   * \param[in] points  graph.max_points, >= 100; std::nullopt: off (every point is analysed) */
  void setMaxPoints(std::optional<int> points);
  std::optional<int> getMaxPoints() const { return params_.graph.max_points; }
  /** \param[in] weight  similarity.concavity, > 0; std::nullopt: off */
  void setConcavityWeight(std::optional<double> weight);
  std::optional<double> getConcavityWeight() const { return params_.similarity.concavity; }
  /** \param[in] thickness  similarity.thickness: thin parts by their medial balls */
  void setThickness(bool thickness);
  bool getThickness() const { return params_.similarity.thickness; }
  /** \param[in] elongation  similarity.flat_elongation, > 0; std::nullopt: off */
  void setFlatElongation(std::optional<double> elongation);
  std::optional<double> getFlatElongation() const { return params_.similarity.flat_elongation; }
  /** \param[in] fraction  boundary.band, in (0, 0.5]; std::nullopt: off */
  void setBoundaryBand(std::optional<double> fraction);
  std::optional<double> getBoundaryBand() const { return params_.boundary.band; }
  /** \brief Open views (core/views/rim_merge.h): on one view from the sensor origin, two touching
   * segments, one of which reaches the view's rim, are merged when the planes of their boundary's
   * two sides meet at a concave angle below this and the boundary is no limb's neck; then a
   * segment smaller than 1% of the object's area (twice the view's) joins its neighbour unless
   * a limb's neck holds it. \param[in] degrees  boundary.rim_merge, in (0, 180]; std::nullopt:
   * off */
  void setRimMerge(std::optional<double> degrees);
  std::optional<double> getRimMerge() const { return params_.boundary.rim_merge; }
  /** \param[in] concavity  refinement.crease_split, > 0; std::nullopt: off */
  void setCreaseSplit(std::optional<double> concavity);
  std::optional<double> getCreaseSplit() const { return params_.refinement.crease_split; }
  /** \param[in] threads  execution.num_threads; 0: the cores that other processes leave free
   * when each phase starts (all of them on an idle machine). The output does not depend on it. */
  void setNumberOfThreads(unsigned threads);
  unsigned getNumberOfThreads() const { return params_.execution.num_threads; }
  /// \}

  /** \brief Called during extract() with a phase of Table 1 ("kNN", "Cen", "Snod", "LRef",
   * "HSeg") and 0 at its start, 1 at its end, and the fraction done in between where known
   * (the centrality). Always from the thread that called extract(); it must not throw.
   * An empty function (default) turns reports off.
   * \param[in] progress  called with (phase, fraction) */
  void setProgressCallback(std::function<void(const char* phase, double fraction)> progress) {
    progress_ = std::move(progress);
  }

  /** \brief Segment the input. Segments are ordered by their smallest point index; every
   * finite input point (within the indices) is in exactly one. On bad input, prints a
   * PCL_ERROR and returns no segments; getStatus() then says why.
   * \param[out] segments  the segments, each a list of input indices in ascending order */
  void extract(std::vector<pcl::PointIndices>& segments);

  /** \brief The outcome of the last extract(): ok, or why it gave no segments (the reason its
   * PCL_ERROR printed), and the warnings it printed with PCL_WARN (fewer points than k + 1,
   * repeated indices), each with a code. Ok with no warnings before any extract(). */
  const pcl_ncut_seg::Status& getStatus() const { return status_; }

  /** \brief Whether this object prints its errors and warnings with PCL_ERROR and PCL_WARN
   * (default: true). A front end that reports getStatus() itself (the Python module, the ROS
   * node) turns them off; other objects and PCL's own messages are not affected.
   * \param[in] print  print them (true) or only return them in getStatus() (false) */
  void setConsoleMessages(bool print) { console_messages_ = print; }
  bool getConsoleMessages() const { return console_messages_; }

  /** \brief The input cloud coloured by segment (distinct colours, the same on every run);
   * points in no segment are black. Empty before a successful extract(). */
  pcl::PointCloud<pcl::PointXYZRGB>::Ptr getColoredCloud() const;

  /** \brief The input cloud labelled by segment, 1-based; 0 for points in no segment. */
  pcl::PointCloud<pcl::PointXYZL>::Ptr getLabeledCloud() const;

  /** \brief The colour of segment i (0-based) used by getColoredCloud().
   * \param[in] i  the segment
   * \param[out] r, g, b  its colour */
  static void segmentColor(std::size_t i, std::uint8_t& r, std::uint8_t& g, std::uint8_t& b);

  /// \name Intermediate results (valid after a successful extract())
  /// Per-point arrays have one entry per input cloud point; NaN or kNone where not used. With
  /// several starts (setStarts), those of the start whose segments extract() returned.
  /// \{
  /** \brief Centrality f(p) of eq. (1) per input point, on a noisy or irregularly sampled
   * whole surface after the neighbourhood mean (setDenoise, setIrregularSampling; not on an open
   * view); NaN for points not segmented. */
  std::vector<float> getCentrality() const;
  /** \brief Input indices of the points where supernodes were born (local maxima of f). */
  std::vector<int> getLocalMaxima() const;
  /** \brief Input indices of the saddle points (Sec. 4.2 (d)). */
  std::vector<int> getSaddles() const;
  /** \brief Supernode per input point before (refined = false) or after local refinement;
   * -1 for points not segmented.
   * \param[in] refined  after (true) or before (false) the local refinement of Sec. 4.3 */
  std::vector<int> getSupernodeLabels(bool refined) const;
  /** \brief Number of supernodes before (m) or after (l) refinement.
   * \param[in] refined  after (true) or before (false) the local refinement */
  std::size_t getNumberOfSupernodes(bool refined) const;
  /** \brief The last analysis' noise test (setDenoise): the residual growth of the points'
   * local plane fits (about 1 for noise, 4 for curvature; 0 when not measured: denoise off,
   * CAD mode or no analysis yet) and whether the points were projected onto their planes; and
   * (setIrregularSampling) the sampling irregularity and whether it counted as irregular. */
  pcl_ncut_seg::NoiseTest getNoiseTest() const;
  /** \brief The last analysis' view test (graph.single_view): whether the points are one view
   * (they have a rim, and the open-view stages ran), from which sensor position (the cloud's
   * sensor_origin_ less the points' centroid, or one read off the points when the points are
   * no view from sensor_origin_), and how many points lie on the rim. */
  pcl_ncut_seg::ViewTest getViewTest() const;
  /** \brief The hierarchy of bisections over the supernode graph (Sec. 5.2): a tree whose
   * root holds every vertex of G_s, each split node with the NCut of its bisection, and each
   * supernode's segment (numbered as extract()'s). A copy; empty without a result. */
  pcl_ncut_seg::SegmentTree getHierarchy() const { return segmenter_.hierarchy(); }
  /** \brief The supernode graph G_s (Sec. 5.1): two vertices per refined supernode and the
   * weighted edges of eqs. (7) and (9). A copy; empty without a result. */
  pcl_ncut_seg::SupernodeGraph getSupernodeGraph() const { return segmenter_.supernodeGraph(); }
  /** \brief Wall time of each phase of the last extract() (Table 1's columns). */
  const pcl_ncut_seg::PhaseTimes& getPhaseTimes() const { return times_; }
  /** \brief The whole expensive stage (of the first start), or nullptr; its type is the
   * core's (core/model/model.h, in the source tree). */
  const pcl_ncut_seg::Analysis* getAnalysis() const { return segmenter_.analysis(); }
  /** \brief The analyses of every start (setStarts), or nullptr (core/model/model.h). */
  const pcl_ncut_seg::Analyses* getAnalyses() const { return segmenter_.analyses(); }
  /** \brief Input index of each analysed point (the graph's vertex order). A point at exactly
   * the position of an earlier one is not analysed; it shares that point's results. Nor is a
   * point left out by setMaxPoints(); it shares its nearest analysed point's segment. */
  const std::vector<int>& getAnalysedIndices() const { return point_index_; }
  /// \}

protected:
  /** \brief Turn the cloud into arrays, find the neighbours and run the core's analysis;
   * false on bad input. */
  bool analyze();
  /** \brief The valid points (in range, finite, each once), sorted; false on a bad index. */
  bool validIndices(std::vector<int>& valid);
  /** \brief Record why extract() fails, and print it (setConsoleMessages()). */
  void fail(pcl_ncut_seg::StatusCode code, std::string message);
  /** \brief Record a warning of extract(), and print it. */
  void warn(pcl_ncut_seg::WarningCode code, std::string message);
  /** \brief The k nearest neighbours of each vertex with the search method set. */
  void searchNeighbours(const std::vector<int>& vertex_index, std::size_t k, int threads,
                        std::uint32_t* knn);
  /** \brief CAD mode's approximate normals: the input's, or PCL's over N(p), given the kNN
   * graph (PointSegmenter::CadNormals). */
  std::vector<float> cadNormals(const std::vector<std::uint32_t>& offsets,
                                const std::vector<std::uint32_t>& targets) const;
  /** \brief Take params (valid) in place of params_, invalidating what they change. */
  bool update(const pcl_ncut_seg::Parameters& params, const char* method);
  void invalidate();
  /** \brief The start whose segments extract() returned (0 without a result). */
  std::size_t shownStart() const { return have_result_ ? segmenter_.start() : 0; }

  KdTreePtr search_;
  pcl_ncut_seg::Parameters params_;
  std::function<void(const char*, double)> progress_;

  /// The points as arrays, the expensive stage (or none) and the last cut.
  pcl_ncut_seg::PointSegmenter segmenter_;
  std::vector<int> point_index_;                          ///< graph vertex -> input index
  std::vector<std::pair<int, std::uint32_t>> duplicates_; ///< (input index, graph vertex) of
                                                          ///< points at a vertex's position
  pcl_ncut_seg::PhaseTimes times_;
  bool have_result_ = false;
  pcl_ncut_seg::Status status_; ///< of the last extract()
  bool console_messages_ = true;

public:
  PCL_MAKE_ALIGNED_OPERATOR_NEW
};

} // namespace pcl

#ifdef PCL_NO_PRECOMPILE
#include <pcl_ncut_seg/impl/supernode_ncut_segmentation.hpp>
#endif
