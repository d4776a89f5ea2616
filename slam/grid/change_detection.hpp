// Scan-to-scan change detection, after DPG-SLAM (Walcott-Bryant, Kaess, Johannsson and
// Leonard, "Dynamic Pose Graph SLAM: Long-term Mapping in Low Dynamic Environments", IROS
// 2012): laser scans of the same place taken at different times are compared, each in the
// other's frame, beam by beam. A return of the older scan is *removed* when the newer scan's
// beams at its bearing pass beyond it (the object is gone); a free beam of the older scan is
// *contradicted* when the newer scan puts a return on it, short of the older beam's end (an
// object was added). Either way the older beam shows a state the world has left: it is
// outdated. The newer scan's beams that showed it are its news.
//
// A point seen through counts only when no return of the scan that sees through it lies
// within edge_guard_m of the point and that scan's beam meets the point's surface at
// min_incidence_rad or more. A removed return counts only when the beams on both sides agree
// too (three beams beyond the point) and the older returns form a run of min_run_beams: a
// corner, an object's edge or a grazing wall, hit by one beam and missed by its neighbour or
// moved along the beam by a small pose error, is no change. An added object counts only
// when the newer returns form that run (or, where the newer scan's own view ends at a nearer
// surface, a doorway's jamb, min_run_occluded_beams of them); then each older beam through one of
// them is outdated on its own (min_incidence_added_rad; passing the point by margin_m plus half a
// beam's bearing error; the older scan's first and last beams too), for a beam that grazes
// a doorway from afar passes many of the door's returns while its neighbours hit the wall;
// and so is each older beam that crosses the newer surface between a return of the run and
// its neighbouring return, for a door seen from afar has its returns a beam's width apart,
// while up close many older beams crossed it between them. A run that reaches the edge of
// the older scan's field of view counts the newer returns on the same surface beyond that
// edge, which the older scan could not judge: a box seen by the older scan's outermost beams
// shows few of its returns inside that view. And two scans are compared only when they
// agree where they overlap: when fewer than min_agreement of the returns they both see lie
// within `margin_m` of each other, their poses disagree (drift before a loop closure) and
// nothing is marked.
// A return hidden from the other scan, whose beam there ends more than hidden_m nearer, is
// not seen by both: the robot come into a room past a desk's new place sees little of what
// it saw from the far side, and that is no disagreement of the poses.
#pragma once

#include <cstdint>
#include <vector>

#include "sensor/laser_scan.hpp"
#include "sensor/pose2.hpp"
#include "slam/grid/grid_map.hpp"

namespace lifelong::slam {

struct ChangeDetectionConfig {
  double margin_m = 0.3;  ///< a beam must pass a point by this much to see through it
  /// A point is seen through only when no return of the other scan lies this close to it:
  /// the edge of an object, which a pose error moves off its outline, is no change.
  double edge_guard_m = 0.1;
  /// A point is seen through only by a beam that meets its surface (the line through the
  /// neighbouring returns) at this angle or more: at a grazing angle a pose error of e
  /// moves the surface by e / sin(angle) along the beam.
  double min_incidence_rad = 0.35;
  /// The same for an older free beam that passes where the newer scan has a return (an
  /// object added). A lower bound serves: cutting it takes off only what lies beyond a
  /// surface seen standing now (free space and the beam's far return), and a grazing beam
  /// through a doorway marks many of the door's cells free.
  double min_incidence_added_rad = 0.1;
  /// How far behind a surface seen standing now an older beam that passed there no longer
  /// shows free space (the object's unseen depth, beyond margin_m); past it the beam is
  /// traced again to its return. Infinity: nothing behind the surface is kept but the return.
  double added_depth_m = 1.0;
  /// Outdated beams count only in runs of at least this many (a run may skip one beam): a
  /// change covers neighbouring beams, noise and pose error single ones.
  int min_run_beams = 4;
  /// An added run that the newer scan's own view cuts short (the beam beyond one of its
  /// ends returns more than hidden_m nearer: a doorway's jamb) needs only this many returns
  /// (0: always min_run_beams): a desk glimpsed through a doorway shows two or three returns
  /// per scan. Two is the least that gives the surface's direction at a return.
  int min_run_occluded_beams = 2;
  /// The share of the returns within each other's field of view, and not hidden there behind
  /// a nearer return, that must agree (within margin_m) for the two scans to be compared at
  /// all.
  double min_agreement = 0.6;
  /// A return that lies more than this behind the other scan's return along its beam is
  /// hidden from it: something nearer stands in front, where a pose error moves a surface
  /// by less. Hidden returns do not count toward min_agreement. A value under margin_m acts
  /// as margin_m.
  double hidden_m = 1.0;
};

/// What comparing an older scan with a newer one found.
struct ScanComparison {
  int judged = 0;         ///< returns of either scan within the other's field of view
  int agree = 0;          ///< of them, those the other sees within margin_m
  int hidden = 0;         ///< of them, those the other's beam ends short of by more than hidden_m
  int disagree = 0;       ///< returns of either scan that the other sees through
  bool compared = false;  ///< the scans overlap and agree enough (min_agreement) to judge
  /// The older scan's outdated beams, ascending, each with how far it still shows free
  /// space: up to its return for a return seen through (the space was free, the object is
  /// gone), up to short of the newer surface for a beam that passed where an object stands,
  /// which is traced again past the object (resume_m: margin_m and added_depth_m behind the
  /// surface, at most margin_m short of its return, which is kept: what it hit still stands).
  std::vector<BeamCut> outdated;
  std::vector<std::uint32_t> news;  ///< the newer scan's beams that showed a change, ascending
};

/// Compares `older` (taken at robot pose T_world_older) with `newer` (at T_world_newer).
/// Beams with a range <= 0 or at range_max (no return) are no evidence either way.
ScanComparison CompareScans(const LaserScan& older, const Pose2& T_world_older,
                            const LaserScan& newer, const Pose2& T_world_newer,
                            const ChangeDetectionConfig& config);

/// Whether the returns `c` judged agree enough at `min_agreement` (the share of those in view
/// and not hidden) for the two scans to be compared: c.compared at that bar.
bool Agrees(const ScanComparison& c, double min_agreement);

}  // namespace lifelong::slam
