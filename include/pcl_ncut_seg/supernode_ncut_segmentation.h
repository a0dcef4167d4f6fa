/*
 * pcl_ncut_seg: part segmentation of point-sampled surfaces.
 *
 * Implements I. Yamazaki, V. Natarajan, Z. Bai, B. Hamann, "Segmenting Point-sampled Surfaces":
 * centrality from geodesic distances on a kNN graph (Sec. 4.1), supernodes from its gradient
 * flow with saddles (4.2), local refinement (4.3), then recursive normalized-cut bisection of a
 * graph of supernodes (5).
 */
#pragma once

#include <pcl/pcl_base.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/PointIndices.h>
#include <pcl/search/search.h>

#include <pcl_ncut_seg/core/boundary_refinement.h>
#include <pcl_ncut_seg/core/cad.h>
#include <pcl_ncut_seg/core/pipeline.h>

#include <functional>
#include <memory>
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
template <typename PointT>
class SupernodeNCutSegmentation : public pcl::PCLBase<PointT> {
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

  /** \brief Provide the input cloud; invalidates the expensive stage. */
  void setInputCloud(const PointCloudConstPtr& cloud) override;
  /** \brief Restrict the segmentation to these points; invalidates the expensive stage. */
  void setIndices(const IndicesPtr& indices) override;
  void setIndices(const IndicesConstPtr& indices) override;
  void setIndices(const PointIndicesConstPtr& indices) override;

  /** \brief Search method for the kNN graph (default: FLANN's kd-tree with the index and
   * parameters of pcl::search::KdTree, so the same neighbours, built in extract() over a compact
   * copy of the points, queried in parallel and released once the graph is built;
   * getSearchMethod() then returns null). */
  void setSearchMethod(const KdTreePtr& search);
  KdTreePtr getSearchMethod() const { return search_; }

  /** \brief k, the number of nearest neighbours of each point in the graph (default 10, >= 2).
   * The graph is symmetric: p and q are joined if either is among the other's k nearest. */
  void setNumberOfNeighbours(int k);
  int getNumberOfNeighbours() const { return k_; }

  /** \brief Centrality samples per connected component (Sec. 4.1); 0 (default) means
   * ceil(sqrt(n)) as in the paper. */
  void setNumberOfSamples(int samples);
  int getNumberOfSamples() const { return num_samples_; }

  /** \brief How the centrality (Sec. 4.1) is computed. Fast (default): eq. (1) on a coarse
   * graph of about getNumberOfRepresentatives() points, carried back to every point (f within
   * about 1-2% of Exact's). Exact: as the paper, ceil(sqrt(n)) searches over the whole graph. */
  void setCentralityMode(pcl_ncut_seg::CentralityMode mode);
  pcl_ncut_seg::CentralityMode getCentralityMode() const { return centrality_mode_; }

  /** \brief Fast mode: points of the coarse graph (default 20000, >= 100). Inputs with at most
   * this many points are computed exactly. */
  void setNumberOfRepresentatives(int representatives);
  int getNumberOfRepresentatives() const { return num_representatives_; }

  /** \brief Fraction of |N(p)| below which a supernode's neighbours of p are taken as reached
   * through feature-crossing edges (Sec. 4.2 (b)); default 0.3, in [0, 1]. */
  void setCrossingFraction(float fraction);
  float getCrossingFraction() const { return crossing_fraction_; }

  /** \brief Small supernodes: feature area below this fraction of the total (default 0.01). */
  void setAreaFraction(float fraction);
  float getAreaFraction() const { return area_fraction_; }

  /** \brief Skinny supernodes: feature height below this fraction of the largest (0.01). */
  void setHeightFraction(float fraction);
  float getHeightFraction() const { return height_fraction_; }

  /** \brief beta of eq. (7), > 0 (default 2.0). */
  void setBeta(double beta);
  double getBeta() const { return similarity_.beta; }

  /** \brief alpha1 of eq. (9), > 0 (default 2.0). */
  void setAlpha1(double alpha1);
  double getAlpha1() const { return similarity_.alpha1; }

  /** \brief alpha2 of eq. (9), > 0 (default 0.5). */
  void setAlpha2(double alpha2);
  double getAlpha2() const { return similarity_.alpha2; }

  /** \brief Normalized-cut threshold (Sec. 5.2), >= 0 (default 0.1): no part is split at a
   * higher NCut. With the largest-gap rule (the default) it bounds the splits the rule chooses
   * from; without it (the paper), a part is bisected while its best NCut is at most this value.
   * Ignored when a number of segments is set. */
  void setThreshold(double threshold);
  double getThreshold() const { return cut_.threshold; }

  /** \brief With the threshold: a part is bisected only if each side keeps at least this
   * fraction of the total feature area, in [0, 0.5] (0 follows the paper). Stops the cut from
   * chipping small pieces off shapes without elongated parts. Ignored with a number of
   * segments. */
  void setMinSegmentFraction(double fraction);
  double getMinSegmentFraction() const { return cut_.min_segment_fraction; }

  /** \brief Automatic stopping rule (with the threshold): split the part with the lowest NCut
   * first while its NCut is at most the threshold and at most getMaxSegments() parts exist,
   * then keep the splits up to the largest relative jump in NCut, or by the short-cut rule
   * (setNeckExponent(), on by default) (default true; false: the paper's recursive bisection
   * while NCut <= threshold). Ignored with a number of segments. */
  void setLargestGapStopping(bool enable);
  bool getLargestGapStopping() const { return cut_.largest_gap; }

  /** \brief Upper bound on the number of segments for the largest-gap rule, >= 1 (default
   * 20). */
  void setMaxSegments(int segments);
  int getMaxSegments() const { return cut_.max_segments; }

  /** \brief For the largest-gap rule: NCut values below this floor count as the floor, so
   * that jumps among near-zero values (e.g. 1e-9 to 1e-6) do not count; > 0 (default 0.003). */
  void setGapFloor(double floor);
  double getGapFloor() const { return cut_.gap_floor; }

  /** \brief Short-cut stopping rule (with the largest-gap rule on): people cut parts off
   * across short boundaries (a finger at its base), not around long ones (a patch of a flat
   * wall). Each best-first split's NCut is weighted by neck^exponent, neck = the boundary's
   * length over the square root of the smaller side's area (measured on the kNN graph), and
   * the splits are kept up to the highest running sum of log(bound / weighted NCut), in
   * place of the largest jump. >= 0 (default 3); 0: the largest jump. */
  void setNeckExponent(double exponent);
  double getNeckExponent() const { return cut_.neck_exponent; }

  /** \brief Short-cut stopping rule: the weighted NCut below which a split is worth making,
   * > 0 (default 0.25). Larger values make more segments. */
  void setNeckBound(double bound);
  double getNeckBound() const { return cut_.neck_bound; }

  /** \brief Ask for this many segments (> 0); 0 (default) uses the threshold instead. The
   * hierarchy is refined by splitting the part with the lowest NCut first. Fewer segments
   * come out when no more parts can be split. */
  void setNumberOfSegments(int segments);
  int getNumberOfSegments() const { return cut_.num_segments; }

  /** \brief Number of uniform split values tried on the eigenvector (Sec. 5.2), >= 1
   * (default 100). */
  void setNumberOfSplitValues(int values);
  int getNumberOfSplitValues() const { return cut_.num_splits; }

  /** \brief Scale the feature width by sqrt(total feature area) so that eq. (7) is unit-free
   * (default true; false follows the paper literally). */
  void setNormalizeWidth(bool normalize);
  bool getNormalizeWidth() const { return similarity_.normalize_width; }

  /** \brief Join supernode trees that touch in the kNN graph but meet at no saddle with the
   * weight of eq. (9) (default true; false follows the paper literally). */
  void setConnectAdjacentTrees(bool connect);
  bool getConnectAdjacentTrees() const { return similarity_.connect_adjacent_trees; }

  /** \brief CAD mode (Sec. 7): segment a mechanical part into its faces, separated at its
   * ridges, instead of into elongated parts (default false). Normals come from the input when
   * the point type has them (finite ones), else from PCL's normal estimation over the kNN
   * neighbourhoods; see docs/cad.md. Changing it invalidates the expensive stage. */
  void setCadMode(bool cad);
  bool getCadMode() const { return cad_mode_; }

  /** \brief CAD mode: angle scale in degrees, in (0, 90], of the similarity of two touching
   * supernodes by the orientation of their faces, exp(-(angle / face_angle)^2) (default 15).
   * Faces that meet at a smaller angle than about this one tend to stay together. */
  void setFaceAngle(float degrees);
  float getFaceAngle() const { return cad_.face_angle; }

  /** \brief Join every pair of supernodes that touch in the kNN graph with the weight of
   * eq. (9), not only those that meet at a saddle (false follows the paper). Holds shapes
   * without elongated parts together: a supernode is no longer cut off by one small edge.
   * Implies what setConnectAdjacentTrees(true) does. */
  void setConnectAllAdjacent(bool connect);
  bool getConnectAllAdjacent() const { return similarity_.connect_all_adjacent; }

  /** \brief With setConnectAllAdjacent(true): join two supernodes that meet at no saddle only
   * if their contact (eq. 8) is at least this share of the smaller of their total contacts
   * with other supernodes, in [0, 1] (default 0: every touching pair). */
  void setAdjacentShare(double share);
  double getAdjacentShare() const { return similarity_.adjacent_share; }

  /** \brief Join components of the kNN graph that only a sampling gap separates: two
   * components are linked by their shortest point pair when it is at most this many kNN radii
   * long (the larger radius of the pair's two points), so that each does not become a segment
   * of its own; >= 0, default 3, 0 = never (the paper). Objects farther apart stay separate.
   * Changing it invalidates the expensive stage. */
  void setBridgeGap(double radii);
  double getBridgeGap() const { return bridge_gap_; }

  /** \brief Concave creases: the weight of eq. (9) between two touching supernodes is
   * multiplied by exp(-w c), c the mean concave bend of the surface across their contact
   * relative to the model's mean bend per kNN edge (normals fitted to each point's kNN
   * neighbourhood and oriented consistently), so that cuts follow concave creases, where
   * people cut parts apart; >= 0, default 3, 0 = off (the paper). Switching between 0 and a positive
   * value invalidates the expensive stage. */
  void setConcavityWeight(double weight);
  double getConcavityWeight() const { return similarity_.concavity_weight; }

  /** \brief Flat patches: a supernode is flat when its feature height is below e times the
   * square root of its feature area (f_h < e sqrt(f_a)); between two flat supernodes the
   * weight of eq. (9) leaves out the ratio of their feature widths, which a near-zero height
   * makes meaningless (patches of a plate or a cup wall would otherwise be cut apart for
   * almost nothing); >= 0, default 0.1, 0 = off (the paper). */
  void setFlatElongation(double elongation);
  double getFlatElongation() const { return similarity_.flat_elongation; }

  /** \brief Boundary refinement after the hierarchy: each pair of touching segments is recut
   * along the cheapest boundary, by a minimum cut on the kNN graph, within a band (fuzzy
   * region) around their common boundary that holds at most this fraction of either segment's
   * area; kNN edges across concave creases are cheap to cut (setBoundaryCreaseWeight), so
   * boundaries move from where the supernodes meet to the crease. The number of segments does
   * not change, and no segment gets more connected components in the kNN graph (a piece a recut
   * cuts off joins the neighbouring segment it touches most). In [0, 0.5], default 0.2; 0 =
   * off (the paper: boundaries are supernode boundaries). Switching between 0 and a positive
   * value invalidates the expensive stage (it keeps one byte per kNN edge when on). */
  void setBoundaryBand(double fraction);
  double getBoundaryBand() const { return boundary_.band_fraction; }

  /** \brief Boundary refinement: a kNN edge's capacity in the minimum cut is its length times
   * exp(-w c), c its concave bend relative to the model's mean bend per edge (as in
   * setConcavityWeight); >= 0, default 3; 0 = the shortest boundary within the band. */
  void setBoundaryCreaseWeight(double weight);
  double getBoundaryCreaseWeight() const { return boundary_.crease_weight; }

  /** \brief Crease splits: a supernode is split along the level cut of the centrality through
   * it whose kNN edges are most concave on average, when that mean concave bend (relative to
   * the model's mean bend per kNN edge) is at least c and each side keeps the small-supernode
   * area fraction (a head or a tail that rises into the body without a saddle gets a
   * supernode of its own; the top of a supernode created at a saddle goes to the supernodes
   * that terminate there); >= 0, default 0.75, 0 = off (the paper). Changing it invalidates the
   * expensive stage. */
  void setCreaseSplit(double concavity);
  double getCreaseSplit() const { return crease_split_; }

  /** \brief Crease cuts: a supernode that no level cut splits (setCreaseSplit()) is also split
   * along the minimum cut between its top and its bottom fifth (by the centrality) over its kNN
   * edges, each costing its length times exp(-3 c), c its concave bend, when at least this share
   * of the kNN edges the cut crosses are concave (c >= 0.75 times the model's mean bend per
   * edge); such a cut can follow a crease that slants across the level sets (a shoulder, the
   * base of a digit); in [0, 1], default 0 = off. Changing it invalidates the expensive stage. */
  void setCreaseCut(double share);
  double getCreaseCut() const { return crease_cut_; }

  /** \brief Threads for the kNN queries and the centrality phase; 0 (default) uses all cores,
   * and more than the machine's processors are not started. Output does not depend on it. */
  void setNumberOfThreads(unsigned threads);
  unsigned getNumberOfThreads() const { return num_threads_; }

  /** \brief Called during extract() with a phase of Table 1 ("kNN", "Cen", "Snod", "LRef",
   * "HSeg") and 0 at its start, 1 at its end, and the fraction done in between where known
   * (the centrality). Always from the thread that called extract(); it must not throw.
   * An empty function (default) turns reports off. */
  void setProgressCallback(std::function<void(const char* phase, double fraction)> progress) {
    progress_ = std::move(progress);
  }

  /** \brief Segment the input. Segments are ordered by their smallest point index; every
   * finite input point (within the indices) is in exactly one. On bad input, prints a
   * PCL_ERROR and returns no segments. */
  void extract(std::vector<pcl::PointIndices>& segments);

  /** \brief The input cloud coloured by segment (distinct colours, the same on every run);
   * points in no segment are black. Empty before a successful extract(). */
  pcl::PointCloud<pcl::PointXYZRGB>::Ptr getColoredCloud() const;

  /** \brief The input cloud labelled by segment, 1-based; 0 for points in no segment. */
  pcl::PointCloud<pcl::PointXYZL>::Ptr getLabeledCloud() const;

  /** \brief The colour of segment i (0-based) used by getColoredCloud(). */
  static void segmentColor(std::size_t i, std::uint8_t& r, std::uint8_t& g, std::uint8_t& b);

  /// \name Intermediate results (valid after a successful extract())
  /// Per-point arrays have one entry per input cloud point; NaN or kNone where not used.
  /// \{
  /** \brief Centrality f(p) of eq. (1) per input point (NaN for points not segmented). */
  std::vector<float> getCentrality() const;
  /** \brief Input indices of the points where supernodes were born (local maxima of f). */
  std::vector<int> getLocalMaxima() const;
  /** \brief Input indices of the saddle points (Sec. 4.2 (d)). */
  std::vector<int> getSaddles() const;
  /** \brief Supernode per input point before (refined = false) or after local refinement;
   * -1 for points not segmented. */
  std::vector<int> getSupernodeLabels(bool refined) const;
  /** \brief Number of supernodes before (m) or after (l) refinement. */
  std::size_t getNumberOfSupernodes(bool refined) const;
  /** \brief The hierarchy of bisections over the supernode graph (Sec. 5.2). */
  const pcl_ncut_seg::Hierarchy& getHierarchy() const { return result_.hierarchy; }
  /** \brief The supernode graph G_s (Sec. 5.1). */
  const pcl_ncut_seg::WeightedGraph& getSupernodeGraph() const { return result_.graph; }
  /** \brief Wall time of each phase of the last extract() (Table 1's columns). */
  const pcl_ncut_seg::PhaseTimes& getPhaseTimes() const { return times_; }
  /** \brief The whole expensive stage, or nullptr. */
  const pcl_ncut_seg::Analysis* getAnalysis() const { return analysis_.get(); }
  /** \brief Input index of each analysed point (the graph's vertex order). A point at exactly
   * the position of an earlier one is not analysed; it shares that point's results. */
  const std::vector<int>& getAnalysedIndices() const { return point_index_; }
  /// \}

protected:
  /** \brief Build the kNN graph and run the expensive stage; false on bad input. */
  bool analyze();
  void invalidate();

  KdTreePtr search_;
  int k_ = 10;
  int num_samples_ = 0;
  pcl_ncut_seg::CentralityMode centrality_mode_ = pcl_ncut_seg::CentralityMode::Fast;
  int num_representatives_ = 20000;
  float crossing_fraction_ = 0.3f;
  float area_fraction_ = 0.01f;
  float height_fraction_ = 0.01f;
  unsigned num_threads_ = 0;
  bool cad_mode_ = false;
  double bridge_gap_ = 3.0;
  double crease_split_ = 0.75; ///< setCreaseSplit
  double crease_cut_ = 0.0;    ///< setCreaseCut
  pcl_ncut_seg::CadParams cad_;
  pcl_ncut_seg::SimilarityParams similarity_;
  pcl_ncut_seg::CutParams cut_;
  pcl_ncut_seg::BoundaryParams boundary_;
  std::function<void(const char*, double)> progress_;

  std::shared_ptr<pcl_ncut_seg::Analysis> analysis_; ///< expensive stage, or null
  std::vector<int> point_index_;      ///< graph vertex -> input index
  std::vector<std::pair<int, std::uint32_t>> duplicates_; ///< (input index, graph vertex) of
                                                          ///< points at a vertex's position
  pcl_ncut_seg::CutResult result_;
  pcl_ncut_seg::PhaseTimes times_;
  bool have_result_ = false;

public:
  PCL_MAKE_ALIGNED_OPERATOR_NEW
};

} // namespace pcl

#ifdef PCL_NO_PRECOMPILE
#include <pcl_ncut_seg/impl/supernode_ncut_segmentation.hpp>
#endif
