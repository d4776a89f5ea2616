// One mode of an experiment: its mapper, its timeline and, at the end, its outputs (the
// <mode>/ folder of the output directory) and its figures of summary.json.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "eval/experiment/experiment.hpp"
#include "eval/experiment/mode_csv.hpp"
#include "eval/metrics/metrics.hpp"
#include "eval/metrics/summary.hpp"
#include "slam/mapping/mapper.hpp"

namespace lifelong::eval {

class ModeRunner {
 public:
  ModeRunner(const slam::Mode& mode, const ExperimentConfig& config);

  const std::string& name() const { return name_; }
  const slam::Mapper& mapper() const { return *mapper_; }
  /// Frees the mapper once the mode is finished and written.
  void Release() { mapper_.reset(); }

  void Step(const Observation& obs);
  /// After Step(stream[i]): scores the map of the present (PresentAt) at each of the
  /// config's present_at_s times that stream[i] is the first scan at or after.
  void ScorePresentAt(const std::vector<Observation>& stream, std::size_t i,
                      const std::optional<GroundTruth>& truth);

  /// Counts for the progress line.
  std::string ProgressDetail() const;

  // Finishes the mapper, writes DIR/<mode>/... and returns the mode's summary.
  // `frame` is the run's scale and canvas of map figures (MakeRunMapFrame).
  ModeSummary Finish(const std::vector<Observation>& stream,
                     const std::optional<GroundTruth>& truth,
                     const std::vector<Relation>& relations, const RunMapFrame& frame,
                     std::vector<double>* kld, std::string* map_png);

 private:
  void Record(const slam::StepStats& s);

  /// Writes <mode>/loops.csv (one row per accepted closure, with its truth when known)
  /// and the precision over the last hour of runs longer than one.
  void WriteLoopsCsv(const LoopClosureResult& truth, ModeSummary* summary) const;
  /// The timeline's and the graph's figures, the peak memory, and the marginalizations' KL
  /// divergences (appended to *kld).
  ModeSummary SummarizeRun(std::vector<double>* kld) const;
  /// The loop closer's verification counts, and the accepted edges the kernel switched off.
  LoopVerificationSummary SummarizeLoops() const;
  /// ATE and RPE at 1 m against config.reference; keeps the aligned estimate for the figure.
  void ScoreAgainstReference(const std::vector<Observation>& stream,
                             const std::vector<StampedPose>& trajectory, ModeSummary* summary);
  /// scan_cells and scan_cells_reference of stream[scans[k]] at estimate[k] / reference[k].
  void CountScanCells(const std::vector<Observation>& stream, const std::vector<std::size_t>& scans,
                      const std::vector<Pose2>& estimate, const std::vector<Pose2>& reference,
                      ModeSummary* summary) const;

  /// ATE and RPE against config.reference, and, without truth, the closures against it
  /// (loops.csv, unscored when there is no reference either).
  void ScoreReference(const std::vector<Observation>& stream,
                      const std::vector<StampedPose>& trajectory, bool truth, ModeSummary* summary);
  /// Loop precision and recall, loops.csv and the loop curve, from the pose of every
  /// observation (the truth, or the log's reference).
  void ScoreLoops(const std::vector<Pose2>& true_nodes, ModeSummary* summary);
  /// The reference pose of every observation, in timeline order; nullopt when one has none.
  std::optional<std::vector<Pose2>> ReferenceAtObservations(
      const std::vector<StampedPose>& trajectory) const;

  /// Returns the ATE alignment T_truth_est (the map figures are drawn in the truth frame);
  /// also fills loop_curve().
  Pose2 TruthMetrics(const std::vector<Observation>& stream, const GroundTruth& truth,
                     const std::vector<Pose2>& estimate, const OccupancyGrid& grid,
                     ModeSummary* summary);

  slam::Mode mode_;
  std::string name_;
  const ExperimentConfig& config_;
  std::unique_ptr<slam::Mapper> mapper_;
  std::vector<TimelineRow> timeline_;
  std::vector<LoopAttemptRow> loop_attempts_;   ///< every loop search, for loop_attempts.csv
  std::vector<std::size_t> observation_scans_;  ///< per timeline row: its scan's index
  std::vector<LoopCurvePoint> loop_curve_;
  std::vector<Pose2> aligned_to_reference_;
  std::string changes_png_, changes_caption_;  ///< the changed objects' strip (change_tiles)
  std::vector<std::string> written_;
  std::vector<PresentAt> present_at_;  ///< ScorePresentAt's, in time order
  SequentialSummary sequential_;
  std::optional<int> first_pass_end_;
  double seconds_ = 0.0;

 public:
  const std::vector<TimelineRow>& timeline() const { return timeline_; }
  /// Loop precision and recall over the run (against the truth or a log's reference; empty
  /// otherwise).
  const std::vector<LoopCurvePoint>& loop_curve() const { return loop_curve_; }
  /// The estimate at the reference's poses, moved onto it by the ATE alignment (replay with
  /// a reference; empty otherwise).
  const std::vector<Pose2>& aligned_to_reference() const { return aligned_to_reference_; }
  /// The strip of changed doors and boxes (eval/figures/change_tiles.hpp), relative to the run's
  /// directory, and its caption; empty when nothing changed.
  const std::string& changes_png() const { return changes_png_; }
  /// The files Finish wrote, relative to the output directory.
  const std::vector<std::string>& written() const { return written_; }
  const std::string& changes_caption() const { return changes_caption_; }
};

}  // namespace lifelong::eval
