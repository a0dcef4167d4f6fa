/*
 * pcl_ncut_seg: the segmentation of a plain array of points, without PCL's types:
 * segmentPoints() in one call, or PointSegmenter, which keeps the expensive analysis for
 * repeated cuts and takes the caller's neighbour search and CAD normals (the PCL front end,
 * supernode_ncut_segmentation.h, is built on it). The analysis itself is the core's and stays
 * behind a pointer to a type declared here only.
 */
#pragma once

#include <pcl_ncut_seg/analysis_report.h>
#include <pcl_ncut_seg/parameters.h>
#include <pcl_ncut_seg/segment_tree.h>
#include <pcl_ncut_seg/status.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

namespace pcl_ncut_seg {

struct Analysis;  // one start's analysis (the core's model)
struct Analyses;  // the analyses of every start
struct CutResult; // the cut's result

/** \brief The whole pipeline on n finite points (3 floats each) with FLANN's kd-tree for the
 * kNN graph: per point its segment in [0, t), the segments numbered by their first point.
 * The labels extract() of the PCL class gives for the same points and parameters (and no
 * sensor origin). Invalid parameters or no points: empty.
 * \param[in] xyz     3 floats per point, finite
 * \param[in] n       the points
 * \param[in] params  the parameters
 * \param[out] status if not null: why the result is empty (StatusCode::BadParameter with the
 *                    first bad parameter, StatusCode::NoFinitePoint for no points), and the
 *                    warnings (WarningCode::FewPoints) */
std::vector<std::uint32_t> segmentPoints(const float* xyz, std::size_t n, const Parameters& params,
                                         Status* status = nullptr);

/** \brief The segmentation of an array of points in its two stages: prepare() and analyze()
 * once per input (the expensive stage), then cut() for each set of cut parameters.
 * Copies share the analysis. */
class PointSegmenter {
public:
  /** \brief Where each prepared vertex came from. */
  struct VertexMap {
    std::vector<std::uint32_t> point; ///< per vertex, the index of its (first) input point
    /// (index of a point at an earlier point's position, its vertex)
    std::vector<std::pair<std::uint32_t, std::uint32_t>> copies;
  };
  /** \brief The caller's neighbour search: per vertex v (in the order of VertexMap::point), its
   * k nearest other vertices, nearest first, into knn[v * k, (v + 1) * k); a row it leaves
   * short keeps 0xffffffff. Called from the calling thread; it may use num_threads. */
  using NeighbourSearch = std::function<void(std::size_t k, int num_threads, std::uint32_t* knn)>;
  /** \brief CAD mode's approximate normals (Sec. 7) given the symmetric kNN graph, vertex v's
   * neighbours targets[offsets[v] .. offsets[v + 1]): 3 floats per vertex, any orientation,
   * NaN where unknown. */
  using CadNormals = std::function<std::vector<float>(const std::vector<std::uint32_t>& offsets,
                                                      const std::vector<std::uint32_t>& targets)>;

  PointSegmenter();
  ~PointSegmenter();
  PointSegmenter(const PointSegmenter& other);
  PointSegmenter(PointSegmenter&& other) noexcept;
  PointSegmenter& operator=(const PointSegmenter& other);
  PointSegmenter& operator=(PointSegmenter&& other) noexcept;

  /** \brief Forget the points, the analysis and the cut. */
  void reset();

  /** \brief Order, deduplicate and centre the points, on an even subset of at most
   * graph.max_points of them (a dense cloud; core's graph/subsample.h). Forgets the analysis.
   * \param[in] xyz            3 floats per point, finite; consumed
   * \param[in] params         valid (validate())
   * \param[in] sensor_origin  where the sensor stood (3 floats, the points' coordinates), or
   *                           null; not read in CAD mode
   * \return per vertex its input point; the vertices number numVertices() */
  VertexMap prepare(std::vector<float> xyz, const Parameters& params,
                    const float* sensor_origin = nullptr);
  /** \brief Prepared vertices (0 before prepare() and after analyze()). */
  std::size_t numVertices() const;

  /** \brief The expensive stage on the prepared points: the k nearest neighbours (FLANN's
   * kd-tree as pcl::search::KdTree builds it, or search), CAD mode's normals (NaN without
   * normals), then the analysis (Secs. 4, 7). Reports the phases "kNN", "Cen", "Snod", "LRef".
   * Adds the phases' times to times. Without prepared points: no analysis (analysed() false).
   * \return StatusCode::NoInput without prepared points; WarningCode::FewPoints when fewer
   * than graph.k + 1 vertices were prepared (each then has fewer neighbours) */
  Status analyze(const Parameters& params, PhaseTimes& times, const PhaseProgressFn& progress = {},
                 const NeighbourSearch& search = {}, const CadNormals& normals = {});
  /** \brief Whether there is an analysis. */
  bool analysed() const { return static_cast<bool>(analyses_); }
  /** \brief Whether the analysis holds what a cut with these parameters needs. */
  bool serves(const Parameters& params) const;

  /** \brief The cheap stage (Sec. 5) on the analysis; replaces the result (an empty one, no
   * segments, when there is no analysis). */
  void cut(const Parameters& params, PhaseTimes& times);
  /** \brief Per vertex its segment, by the last cut(). */
  const std::vector<std::uint32_t>& pointSegments() const;
  /** \brief Segments of the last cut(). */
  std::size_t numSegments() const;
  /** \brief The start whose segments the last cut() chose (0 with one start). */
  std::size_t start() const;
  /** \brief Renumber the last cut's segments: segment s becomes rank[s]. */
  void renumberSegments(const std::vector<std::uint32_t>& rank);
  /** \brief The hierarchy of bisections of the last cut() (Sec. 5.2), a copy; empty without
   * one. Its supernode_segment follows renumberSegments(). */
  SegmentTree hierarchy() const;
  /** \brief The supernode graph G_s of the last cut() (Sec. 5.1), a copy; empty without one. */
  SupernodeGraph supernodeGraph() const;
  const CutResult& result() const; ///< the last cut() (the core's type)

  /// \name The analysis of a start (0: the first; start() after a cut), analysed()
  /// \{
  const std::vector<float>& centrality(std::size_t start) const; ///< f per vertex (eq. (1))
  /** \brief Per vertex its supernode, after (refined) or before Sec. 4.3's refinement. */
  const std::vector<std::uint32_t>& supernodeLabels(std::size_t start, bool refined) const;
  std::size_t numSupernodes(std::size_t start, bool refined) const;
  std::vector<std::uint32_t> localMaxima(std::size_t start) const; ///< vertices (Sec. 4.2)
  std::vector<std::uint32_t> saddles(std::size_t start) const;     ///< vertices (Sec. 4.2 (d))
  /// \}
  /** \brief The noise test and view test of the analysis (empty ones without). */
  NoiseTest noiseTest() const;
  ViewTest viewTest() const;
  /** \brief The first start's analysis, or null. */
  const Analysis* analysis() const;
  /** \brief Every start's analysis, or null. */
  const Analyses* analyses() const { return analyses_.get(); }

private:
  struct Prepared;
  std::unique_ptr<Prepared> prepared_;       ///< until analyze()
  std::shared_ptr<const Analyses> analyses_; ///< the expensive stage, or null
  std::unique_ptr<CutResult> result_;        ///< the last cut (never null)
};

} // namespace pcl_ncut_seg
