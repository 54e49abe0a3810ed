// The disparity offset of a stereo rig, measured from its own images while it moves
// (docs/slam.md §2c, docs/results-slam.md, issue 50).
//
// A constant error d_off in every disparity (a rectification or capture offset the calibration
// does not know) makes depth Z = f B / (d + d_off) wrong by more the farther the point: under
// the true motion, far points seem to travel more than near ones. The rotation R and the
// translation direction t^ of each frame pair come from the left images alone (the essential
// matrix of the ORB matches, no depth involved); for each candidate offset every matched point
// with a disparity in both frames gives its travel along t^, (C - R P) . t^, with P and C lifted
// at that offset, divided by the pair's median travel. At the right offset that ratio is the
// same at every depth: the estimate is the candidate whose three depth bands (up to a quarter,
// a half and all of max_depth) have the closest medians (the least largest |band median /
// median of all - 1|), pooled over the pairs seen. The camera takes it only when it differs from
// the calibration's offset by at least `gate`: a well-calibrated rig keeps its calibration.
#pragma once

#include <array>
#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "stereo_robot/slam/motion.hpp"

namespace stereo::robot::slam {

struct SelfCalibrationParams {
    double min_offset = -3.0;  // px of the matched images: the candidates' range
    double max_offset = 3.0;
    double step = 0.125;       // between candidates
    int min_pairs = 20;        // frame pairs with travel before an estimate exists
    int window = 100;          // the most recent pairs kept (0 = every pair of the run)
    double min_travel = 0.2;   // m: a pair's median travel below this observes nothing
    int min_points = 20;       // points with a disparity in both frames, per pair
    double epipolar_px = 1.0;  // Sampson distance of an inlier to the epipolar geometry
    double max_depth = 40.0;   // m: farther points (at offset 0) are left out (Slam: the motion's)
    double gate = 0.5;         // px: a smaller difference from the calibration is not applied
    double hysteresis = 0.25;  // px: a smaller change of the applied offset is not made
    int every = 5;             // pairs between estimates after the first
    // When the offset changes, the motions of this many most recent frame pairs are solved
    // again at the new offset (their inliers are kept: about 10 KB a pair).
    int resolve_steps = 500;
};

// Feeds on the matches of each frame pair (MotionEstimate::matched_pairs) and estimates the
// offset over the pairs kept. The samples keep the disparities as matched, so an estimate is the
// rig's whole offset, whatever offset the caller's camera used so far.
class DisparityOffsetEstimator {
  public:
    explicit DisparityOffsetEstimator(const SelfCalibrationParams& params);

    // One frame pair: (u, v, d) in the previous and the current frame, d < 0 where a frame has
    // no disparity. Returns false when the pair was not kept (too few points, no essential
    // matrix, too little travel at every candidate).
    bool add_pair(const std::vector<KeypointPair>& pairs, const Camera& camera,
                  const Eigen::Isometry3d& motion);

    // The least-spread offset over the pairs kept once min_pairs of them travelled; none before,
    // or when the least spread lies at either end of the range (not measured).
    std::optional<double> estimate() const;

    // The offset a camera calibrated with `calibrated` and now using `applied` should use: the
    // target is the estimate when there is one at least `gate` away from the calibration, else
    // the calibration; it replaces `applied` only when at least `hysteresis` away from it (a
    // change costs solving the kept motions and the map again).
    double offset_for(double calibrated, double applied) const;

    int pairs() const { return static_cast<int>(pairs_.size()); }
    int pairs_seen() const { return seen_; }  // kept over the run, the window's dropped included

    // Whether to estimate after the pair just added: at min_pairs and every `every` pairs after.
    bool due() const;

  private:
    // One pair's travel ratios per candidate and depth band.
    using Bands = std::array<std::vector<float>, 3>;
    struct Pair {
        std::vector<Bands> candidates;
        std::vector<bool> moving;  // per candidate: its median travel reached min_travel
    };
    int candidates() const;
    double offset_of(int candidate) const;
    SelfCalibrationParams params_;
    std::vector<Pair> pairs_;
    int seen_ = 0;
};

}  // namespace stereo::robot::slam
