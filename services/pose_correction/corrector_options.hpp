#pragma once
// What a PoseCorrector is configured with: the mapper's --slam-* flags and the evaluation programs'
// options set these fields; the defaults are the mapper's.
#include <cstddef>

#include "pose_correction/correction_schedule.hpp"
#include "pose_correction/keyframe_builder.hpp"
#include "pose_correction/scan_matcher.hpp"
#include "pose_correction/wall_axes.hpp"

namespace slam::correction {

struct CorrectorOptions {
  KeyframeOptions keyframe;
  MatcherOptions matcher;
  SearchWindow track_window{0.15, 0.08};  // every keyframe, around the prediction
  SearchWindow closure_window{1.0, 0.3};  // loop closure, around the prediction
  double closure_min_score = 0.6;         // mean likelihood a closure match must reach
  double old_age_s = 60.0;                // a keyframe this old (or another robot's) counts as "old map"
  double closure_radius_m = 2.0;          // old keyframes this close to the prediction are candidates
  int closure_min_keyframes = 4;          // fewer old keyframes around: no closure attempt
  // A tracking match's covariance is the search response's spread times this. The spread is
  // deliberately broad (MatcherOptions::independent_points keeps a ridge visible to the closure
  // gate), which overstates a distinct match's error: at 1 tracking followed odometry through new
  // rooms and drifted twice as far (replayed runs, docs/mapping-quality.md).
  double track_variance_scale = 0.5;
  // The same for a keyframe of laser scans (KeyframeOptions::scan_points), read with this many
  // independent points: a scan pins its pose far better than the odometry of a 10 cm step, and
  // fusing it at the sparse robots' weight left real robots' headings to drift (the benchmark logs,
  // docs/mapping-quality.md).
  double scan_track_variance_scale = 0.05;
  double scan_independent_points = 100.0;
  // A keyframe of scans spans a few degrees of turning, over which real odometry can be off by as
  // much again (Freiburg 079's by 5-10 degrees a second): its heading is searched wider.
  SearchWindow scan_track_window{0.15, 0.2};
  // A scan keyframe whose tracking match lies on its window's edge (odometry off by more than the
  // window: Freiburg 079's odometry integrates forward while the robot backs up at 0.5 m/s) is
  // searched again by branch and bound in this wider window, and the tracking window's match around
  // what it finds is taken when it is no longer on the edge and scores better.
  SearchWindow scan_recovery_window{0.6, 0.4};
  double scan_recovery_gain = 0.05;  // ...by at least this much more mean likelihood (0..1)
  // What makes a loop closure's match distinct. A scan's hundreds of points put a second peak that
  // sums nine tenths of the best far below it (its weight under the response's reading is e^-8 at
  // 700 points), where a sparse keyframe's would still be a real rival.
  DistinctMatch distinct;
  DistinctMatch scan_distinct{0.95, 0.05, 0.035};
  double odom_sigma_m_per_sqrt_m = 0.03;  // odometry edge noise (a little above the usual drift)
  double odom_sigma_rad_per_m = 0.02;     // heading noise per metre travelled (edge and chain)
  // The walls' heading (wall_axes.hpp): each keyframe's heading is pulled toward the one its
  // straight walls give against the map's axes, and held there in the graph. It acts only once the
  // map's walls agree on two perpendicular directions, so maps with walls at many angles are left
  // alone; off for a building whose walls are square to each other only in places.
  bool wall_heading = true;
  // Each robot's systematic odometry heading error (odometry_calibration.hpp) learned from its
  // matches and taken out of its odometry; off for robots whose odometry is calibrated already.
  bool odometry_calibration = true;
  // Odometry that counts backward driving as forward (odometry_direction.hpp) turned round while the
  // matches show the robot reversing.
  bool odometry_direction = true;
  WallAxisOptions wall_axis;
  double wall_heading_floor_rad = 0.005;  // added to a reading's spread: no building is exactly square
  double wall_heading_gate_rad = 0.08;    // a larger correction is not taken: a wall at another angle
  // Each match (tracking and tie) refined against the points of the keyframes around it
  // (point_refiner.hpp): the grid alone leaves walls up to half a cell off.
  bool point_refine = true;
  // The keyframes around a match: those within its farthest point, at most local_reach_m, hold the
  // points a tie's local grid and the point refinement read; at most tie_max_keyframes old ones
  // (nearest first) for a tie, refine_max_keyframes for the refinement.
  double local_reach_m = 10.0;
  size_t tie_max_keyframes = 40;
  size_t refine_max_keyframes = 60;
  double window_margin_m = 0.3;  // beyond a keyframe's farthest point: the matcher's field blur
  double tied_sigma_m = 0.05;    // chain uncertainty above which a tie searches the wide window
  // After a long loop a sparse robot can be metres off, beyond closure_window, where one keyframe's
  // few dozen points fit many places. While its pose's sigma in the map exceeds relocalise_sigma_m,
  // the points of its last placement_trail_m of keyframes are searched by branch and bound within
  // 3 sigma (at most relocalise_max_m, relocalise_max_rad) among the old keyframes there, and a match
  // as distinct as a placement's is taken as a loop closure once relocalise_confirmations keyframes
  // in a row agree on it (as global localisation confirms a placement). The pose's sigma, not the
  // chain's since its last tie: a robot just switched on at a trusted start is untied but not lost,
  // and in the simulator's two-room world a search for it took the other room.
  bool relocalise = true;
  double relocalise_sigma_m = 0.5;
  double relocalise_max_m = 8.0;
  double relocalise_max_rad = 0.6;
  int relocalise_confirmations = 3;
  // A trail whose rays run through more than this share of the old keyframes' walls is a look-alike
  // place. The trail is drawn at its drifting estimates and a 16-beam keyframe's points were seen
  // from along its half metre, so true matches on the benchmark logs cross far more than a
  // placement's; the simulator's look-alike rooms were taken at 0.7 (0.3 refused most true ones).
  double relocalise_max_crossed_walls = 0.7;
  // A keyframe whose robot moved less than this since its previous one, and within it, was taken
  // standing still: it sees what its previous keyframe saw, and matching it again adds nothing but
  // the chance to be dragged by other robots' fresh keyframes (placed by odometry instead).
  double standing_travel_m = 0.02;
  double standing_turn_rad = 0.02;
  // A robot whose odometry starts farther than this from the map's origin (a real robot's counters
  // start wherever they were last reset: the MIT CSAIL log's at x = 600 m) starts with its first pose
  // moved to the origin, heading kept, instead of beyond the map's extent.
  double far_start_m = 100.0;
  // A robot that joins a map others have built is first searched for on it (global localisation,
  // branch_and_bound_search.hpp over the whole map and every heading). Until it is placed its
  // keyframes wait, unmatched and unfinalised, so nothing of it is drawn into the shared map; it is
  // placed when placement_confirmations keyframes in a row agree on where its odometry frame lies,
  // each match distinct (runner-up at most placement_max_ambiguity of the best) and scoring at least
  // placement_min_score. It is never drawn where its odometry says instead (robots switched on
  // elsewhere would be pasted onto the first one's map): it is searched for as long as it takes, and
  // only its latest placement_max_keyframes keyframes wait (older ones are dropped with their
  // observations). Off by default (the mapper's --slam-global-localisation): until an unplaced robot
  // maps into a submap of its own, what it sees before it is found is lost to the map.
  bool global_localisation = false;
  int placement_confirmations = 3;
  double placement_min_score = 0.6;
  double placement_max_ambiguity = 0.85;
  double placement_agree_m = 0.3;  // a later keyframe's match this close to the hypothesis agrees
  double placement_agree_rad = 0.1;
  int placement_max_keyframes = 40;
  size_t placement_max_rejected = 16;  // an operator's rejected places kept per robot (the latest)
  // What is searched: the newest keyframe and the ones before it within this much travel, by
  // odometry (a sparse robot's single keyframe fits many places), evenly thinned to max_points.
  double placement_trail_m = 4.0;
  // The whole map is searched again only once the robot has moved this far since the last search
  // (doubled by each search in a row that found nothing, up to the trail): the keyframes in between
  // add little to a 4 m trail, and each whole-map search costs a tenth of a second on an office, 2 s
  // on 100 x 100 m (confirming a hypothesis searches only around it, every keyframe).
  double placement_search_travel_m = 0.5;
  size_t placement_max_points = 400;
  // A match whose rays run through more than this share of the map's walls is a look-alike place
  // (free_space_check.hpp), however well its points land. True placements of the benchmark logs'
  // robots cross 10-18 % (a few metres of real odometry smear the trail; 30 m rays pass doorways
  // and glass), look-alikes in the simulator's office about 40 %.
  double placement_max_crossed_walls = 0.3;
  // The searched maps: the grid's occupied part, coarsened (2, 4, ... cells to one) until it fits.
  // The whole map, every heading, is searched on the coarser one (a search costs about its cells
  // times its headings: 9 s over 100 x 100 m at 10 cm, 2 s at 20 cm; docs/performance.md); a
  // hypothesis is confirmed around where it puts the robot on the finer one. The benchmark logs'
  // buildings (up to about 70 m) are searched whole at 10 cm or finer: at 20 cm one piece of ACES
  // was not found.
  size_t placement_max_map_cells = 1 << 20;
  size_t placement_whole_map_cells = 1 << 19;
  // A placed robot is lost (carried, or its odometry broke) when its tracking match fails
  // lost_after_unmatched keyframes in a row (each with points enough to match), or, for a laser
  // robot, when its last lost_window scans matched at lost_mean_score or less on average: a wrong
  // place still puts many points near some wall, but fewer. Measured on the benchmark logs and the
  // simulator's runs, a tracking match fails 1-6 times in thousands of keyframes, never twice in a
  // row, and the lowest mean of 6 scan scores was 0.663 (ACES; Intel 0.677, Freiburg 079 0.710, a
  // 180-beam simulator run 0.776); carried in a small room the test's robot scored 0.60-0.65. The
  // sparse robots' scores overlap that (a 16-beam simulator robot's mean of 6 fell to 0.63 where it
  // was), so they are found lost only when their matches fail. Its chain ends there, and it is searched for
  // on the whole map as a robot switched on anywhere is; meanwhile nothing of it is drawn, and of its waiting
  // keyframes only the latest placement_max_keyframes are kept (older ones are dropped with their
  // observations: where they were is unknown). It is not given up on. 0: never lost.
  int lost_after_unmatched = 4;
  int lost_window = 6;  // at most 64
  double lost_mean_score = 0.64;
  // Localisation only, on a map given and kept fixed (a building mapped once, loaded): every robot
  // is searched for on it (as global_localisation, even the first, and never placed by its odometry
  // instead), then tracked against it. A match against a fixed map is as good as a tie to old
  // keyframes, so there are no ties, closures or optimisations, and a robot keeps one pose-graph
  // node (its latest keyframe, without points): memory follows the fleet, not the hours driven.
  bool localise_only = false;
  int optimise_every = 40;         // keyframes tied to the old map between optimisations
  double rerender_shift_m = 0.02;  // keyframe moves smaller than this are not re-rendered
  ScheduleOptions schedule;
  int match_threads = 0;  // 0: match inside process() (deterministic: tests, offline); 1: on a worker
};

}  // namespace slam::correction
