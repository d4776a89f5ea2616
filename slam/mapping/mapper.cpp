#include "slam/mapping/mapper.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "slam/backend/optimizer.hpp"
#include "slam/grid/present_view.hpp"
#include "slam/mapping/mapper_state.hpp"
#include "slam/matching/scan_matcher.hpp"

namespace lifelong::slam {
namespace {

double MsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

}  // namespace

Mapper::State::State(const MapperConfig& c)
    : config(c),
      closer(c.loops, c.incremental),
      keeper(c.grid, c.pruning.mode.Prunes(),
             {[this] { return step ? &step->stages.gain_ms : nullptr; }, &innermost_timer}),
      sequential(c.incremental) {
  if (const std::optional<ConfigProblem> problem = Validate(c)) {
    throw std::invalid_argument("mapper config: " + problem->fields + ": " + problem->message);
  }
  if (c.pruning.mode.Prunes()) pruner.emplace(c.pruning, c.optimizer);
}

Mapper::Mapper(const MapperConfig& config) : state_(std::make_unique<State>(config)) {}
Mapper::~Mapper() = default;

StepStats Mapper::AddObservation(const Observation& obs) {
  const auto start = std::chrono::steady_clock::now();
  State& s = *state_;
  StepStats stats;
  stats.scan_index = static_cast<int>(s.scans.size());
  stats.stamp_s = obs.stamp_s;
  if (s.have_last && !obs.odometry_lost) {  // a lost step is searched for at once
    const Pose2 delta = Between(s.nodes.at(s.last_node).T_odom_robot, obs.T_odom_robot);
    if (Norm(delta) < s.config.keyframes.min_translation_m &&
        std::abs(delta.theta) < s.config.keyframes.min_rotation_rad) {
      s.AddBetweenScan(obs, delta);
      return stats;
    }
  }
  s.step = &stats;
  {
    const ScopedMs timer = s.Stage(&StageTimes::match_ms);
    s.AddSequentialNode(obs, &stats);
  }
  const NodeId current = s.last_node;
  if (s.config.loops.enabled && s.graph.NumNodes() > 1) {
    const ScopedMs timer = s.Stage(&StageTimes::loop_ms);
    s.CloseLoops(current, &stats);
  }
  if (s.config.pruning.mode.Prunes() && s.observations % s.config.pruning.round_period == 0)
    s.Prune(current);

  s.step = nullptr;
  // The mapper's own time; the statistics below are instrumentation, not mapping.
  stats.time_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  stats.observation_index = s.observations++;
  stats.nodes = s.graph.NumNodes();
  stats.edges = s.graph.NumEdgesForGamma();
  stats.gamma = s.graph.Gamma();
  stats.graph_bytes = s.graph.Bytes();
  stats.loop_closures_total = static_cast<int>(s.loops.size());
  stats.nodes_removed_total = s.pruner ? static_cast<int>(s.pruner->marginalizations().size()) : 0;
  if (on_observation) on_observation(stats);
  return stats;
}

void Mapper::State::AddBetweenScan(const Observation& obs, const Pose2& delta) {
  const IncrementalConfig& inc = config.incremental;
  std::optional<Pose2> measured;
  if (inc.between_refine_m > 0.0) {
    measured = sequential.RefineBetween(ScanToPoints(obs.scan, inc.point_spacing_m), delta);
  }
  const Pose2 T_last_scan = measured.value_or(delta);
  scans.AddPending(obs.stamp_s, last_node, T_last_scan, obs.T_odom_robot, measured.has_value());
  keeper.Glimpse(obs.scan, values.at(last_node) * T_last_scan);
}

void Mapper::State::OptimizeAndSyncMap() {
  Optimize();
  const auto start = std::chrono::steady_clock::now();
  {
    const ScopedMs timer = Stage(&StageTimes::map_update_ms);
    SyncMap();
  }
  since_sync = 0;
  if (step) {
    step->map_synced = true;
    step->optimize_ms += MsSince(start);
  }
}

void Mapper::State::Optimize() {
  const auto start = std::chrono::steady_clock::now();
  OptimizerSummary summary;
  {
    const ScopedMs timer = Stage(&StageTimes::backend_ms);
    summary = slam::Optimize(graph, &values, config.optimizer);
  }
  since_optimize = 0;
  if (step) {
    step->optimized = true;
    step->optimizer_iterations += summary.iterations;
    step->optimize_ms += MsSince(start);
  }
}

void Mapper::State::SyncMap() {
  keeper.Follow(values, config.map_move_epsilon_m, config.map_move_epsilon_rad, &nodes);
}

void Mapper::Finish() {
  if (state_->graph.NumNodes() > 1) state_->OptimizeAndSyncMap();
}

const PoseGraph& Mapper::graph() const { return state_->graph; }
const Values& Mapper::values() const { return state_->values; }
const GridMap& Mapper::map() const { return state_->keeper.grid(); }

void Mapper::ForEachPresentCell(const std::function<void(CellIndex, double)>& f) const {
  const ScanStore& scans = state_->scans;
  const double now_s = scans.size() > 0 ? scans.stamp(scans.size() - 1) : 0.0;
  const GridMapConfig& grid = state_->config.grid;
  slam::ForEachPresentCell(map(), state_->keeper.ledger(), now_s,
                           {grid.present_timescale_s, grid.present_shape}, f);
}
void Mapper::set_hypothesis_hook(std::function<void(LoopHypothesis*, const Values&)> hook) {
  state_->closer.set_hypothesis_hook(std::move(hook));
}
const std::vector<LoopClosureRecord>& Mapper::loop_closures() const { return state_->loops; }
const LoopVerifierStats& Mapper::loop_verification() const { return state_->closer.stats(); }
const std::vector<MarginalizationRecord>& Mapper::marginalizations() const {
  static const std::vector<MarginalizationRecord> kNone;
  return state_->pruner ? state_->pruner->marginalizations() : kNone;
}
const std::vector<SparsificationRecord>& Mapper::sparsifications() const {
  static const std::vector<SparsificationRecord> kNone;
  return state_->pruner ? state_->pruner->sparsifications() : kNone;
}
int Mapper::observations() const { return state_->observations; }
std::size_t Mapper::cut_beams() const { return state_->cut_beams; }

double Mapper::MaxGainCacheError() const {
  double worst = 0.0;
  if (!state_->pruner) return worst;
  for (const auto& [id, data] : state_->nodes) {
    if (!state_->keeper.Tracks(id)) continue;
    const double fresh = state_->keeper.FreshGain(data.scan, data.T_world_map, data.cuts);
    worst = std::max(worst, std::abs(fresh - state_->keeper.Gain(id)));
  }
  return worst;
}

StampedPose Mapper::LastScanPose() const { return state_->scans.Last(state_->values); }

std::vector<StampedPose> Mapper::Trajectory() const {
  return state_->scans.Trajectory(state_->values);
}

}  // namespace lifelong::slam
