// The SLAM loop of thesis Sec. 4.2, one stereo frame at a time: sparse disparities, motion from
// the previous frame, the local map from the v-disparity ground line, and its placement in the
// global map refined by the map-merging search. Two trajectories are kept: the motion chain
// alone (odometry) and the one with the merge corrections, so the refinement can be measured.
#pragma once

#include <optional>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "stereo_robot/slam/evaluation.hpp"
#include "stereo_robot/slam/frontend.hpp"
#include "stereo_robot/slam/maps.hpp"
#include "stereo_robot/slam/motion.hpp"

namespace stereo::robot::slam {

struct SlamParams {
    FrontendParams frontend;
    MotionParams motion;
    GroundParams ground;
    LocalMapParams local;
    MergeParams merge;
    double cell_size = 0.25;    // metres
    double ray_bin_deg = 0.5;   // bearing bins of the free-space rays
    bool merge_enabled = true;  // false: place local maps with the odometry alone
    // Row bands of the front end matched in parallel (bit-exact, stereo_robot/bands.hpp), and
    // the ORB detection run beside the front end; 1 = everything on the calling thread.
    int threads = 1;
};

// Throws std::invalid_argument for impossible parameters (image size from the first frame).
void validate(const SlamParams& params, int width, int height);
// Throws std::invalid_argument (one line) for a camera no real rig has: focal length outside
// [1, 1e6] px, principal point more than one image size outside the image, baseline outside
// [1 mm, 1 km], or any value not finite.
void validate_camera(const Camera& camera, int width, int height);

struct StageTimes {
    double frontend_ms = 0.0;
    double motion_ms = 0.0;
    double local_map_ms = 0.0;
    double global_map_ms = 0.0;
};

struct FrameReport {
    double valid_fraction = 0.0;  // of the sparse disparity map
    MotionEstimate motion;        // identity for the first frame
    bool ground_found = false;    // this frame's own line (else the previous one was used)
    std::optional<GroundLine> ground;
    int obstacle_points = 0;
    MergeResult merge;
    StageTimes ms;
};

class Slam {
  public:
    // `camera` is that of the images given to process() (already downscaled).
    Slam(const Camera& camera, const SlamParams& params);

    // One frame: 8-bit grey rectified left and right images of equal size.
    FrameReport process(const cv::Mat& left, const cv::Mat& right);

    const Trajectory& odometry() const { return odometry_; }      // motion chain only
    const Trajectory& trajectory() const { return trajectory_; }  // with merge corrections
    const EvidenceGrid& map() const { return map_; }
    const SparseDisparity& last_disparity() const { return disparity_; }
    const VDisparity& last_v_disparity() const { return vdisp_; }

  private:
    Camera camera_;
    SlamParams params_;
    Trajectory odometry_;
    Trajectory trajectory_;
    EvidenceGrid map_;
    Features features_;
    SparseDisparity disparity_;
    VDisparity vdisp_;
    std::optional<GroundLine> ground_;
    Eigen::Isometry3d last_motion_ = Eigen::Isometry3d::Identity();
};

// Camera positions (x, z) of a trajectory, for render_map.
std::vector<Eigen::Vector2d> plane_path(const Trajectory& poses);

}  // namespace stereo::robot::slam
