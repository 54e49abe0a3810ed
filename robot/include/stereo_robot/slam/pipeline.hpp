// The SLAM loop of thesis Sec. 4.2, one stereo frame at a time: sparse disparities, motion from
// the previous frame, the local map from the v-disparity ground line, and its placement in the
// global map refined by the map-merging search. Two trajectories are kept: the motion chain
// alone (odometry) and the one with the merge corrections, so the refinement can be measured.
#pragma once

#include <deque>
#include <optional>
#include <unordered_map>
#include <utility>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "stereo_robot/slam/bundle.hpp"
#include "stereo_robot/slam/evaluation.hpp"
#include "stereo_robot/slam/frontend.hpp"
#include "stereo_robot/slam/maps.hpp"
#include "stereo_robot/slam/motion.hpp"
#include "stereo_robot/slam/self_calibration.hpp"

namespace stereo::robot::slam {

struct SlamParams {
    FrontendParams frontend;
    MotionParams motion;
    GroundParams ground;
    LocalMapParams local;
    MergeParams merge;
    BundleParams bundle;
    // Windowed bundle adjustment (docs/slam.md §2b); off by default: it did not lower the ATE
    // of either KITTI clip at their calibration (docs/results-slam.md, issue 50).
    bool bundle_enabled = false;
    double cell_size = 0.25;    // metres
    double ray_bin_deg = 0.5;   // bearing bins of the free-space rays
    bool merge_enabled = true;  // false: place local maps with the odometry alone
    // The disparity offset measured from the images while moving (self_calibration.hpp),
    // applied from the frame it is first known; false keeps the camera's offset.
    bool self_calibration_enabled = true;
    SelfCalibrationParams self_calibration;
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
    double bundle_ms = 0.0;
    double local_map_ms = 0.0;
    double global_map_ms = 0.0;
};

struct FrameReport {
    double valid_fraction = 0.0;  // of the sparse disparity map
    MotionEstimate motion;        // identity for the first frame
    BundleReport bundle;          // the window's adjustment (zeros when off or first frame)
    bool ground_found = false;    // this frame's own line (else the previous one was used)
    std::optional<GroundLine> ground;
    int obstacle_points = 0;
    MergeResult merge;
    StageTimes ms;
    double disparity_offset = 0.0;  // the camera's, after this frame (px of the images)
};

class Slam {
  public:
    // `camera` is that of the images given to process() (already downscaled).
    Slam(const Camera& camera, const SlamParams& params);

    // One frame: 8-bit grey rectified left and right images of equal size.
    FrameReport process(const cv::Mat& left, const cv::Mat& right);

    // process() in two parts, for a caller that overlaps frames: frontend() (the sparse disparity
    // map and the ORB features) reads only the parameters, so it may run for the next frame on
    // another thread while integrate() takes this one (motion, bundle adjustment, maps).
    // integrate(frontend(l, r)) is process(l, r).
    struct FrontendFrame {
        SparseDisparity disparity;
        Features features;
        double ms = 0.0;
    };
    FrontendFrame frontend(const cv::Mat& left, const cv::Mat& right) const;
    FrameReport integrate(FrontendFrame frame);

    const Trajectory& odometry() const { return odometry_; }  // frame-to-frame motion chain only
    // The motion chain refined by the windowed bundle adjustment (= odometry() when it is off).
    const Trajectory& adjusted() const { return adjusted_; }
    const Trajectory& trajectory() const { return trajectory_; }  // adjusted + merge corrections
    const EvidenceGrid& map() const { return map_; }
    const SparseDisparity& last_disparity() const { return disparity_; }
    const Camera& camera() const { return camera_; }  // its offset may be self-calibrated
    int self_calibration_pairs() const { return offset_estimator_.pairs_seen(); }
    const VDisparity& last_v_disparity() const { return vdisp_; }

  private:
    // A key frame of the bundle-adjustment window (every frame is one).
    struct KeyFrame {
        int frame = 0;                 // index in the run
        bool linked = false;           // its motion was estimated (not a fallback)
        std::vector<int> landmark_of;  // per ORB keypoint: landmark id, or -1
        std::vector<std::pair<int, Eigen::Vector3d>> observations;  // (landmark id, (u, v, d))
    };
    void add_key_frame(const MotionEstimate& motion, std::size_t keypoints);
    // The global-map stage of one frame: the merge search, then the local map (camera-frame
    // points) into the map at trajectory_[frame], which the correction found updates.
    MergeResult place_local_map(std::size_t frame, const std::vector<Eigen::Vector3d>& obstacles,
                                const std::vector<Eigen::Vector3d>& ground);
    bool set_disparity_offset(double offset);  // true when it changed
    void resolve_steps();
    void rebuild_map();

    // A frame's local map, thinned, with the offset it was lifted at.
    struct KeptLocalMap {
        std::vector<Eigen::Vector3f> obstacles;
        std::vector<Eigen::Vector3f> ground;
        double offset = 0.0;
    };
    void keep_local_map(KeptLocalMap local);
    // Its points at the camera's offset.
    static std::pair<std::vector<Eigen::Vector3d>, std::vector<Eigen::Vector3d>> relifted(
        const KeptLocalMap& local, const Camera& camera);
    std::deque<KeptLocalMap> local_maps_;  // of frames first_step_ .. (with steps_)

    // A frame-to-frame motion kept for solving again when the disparity offset changes.
    struct Step {
        Eigen::Isometry3d motion;
        bool fallback = false;
        std::vector<KeypointPair> inliers;
    };
    std::deque<Step> steps_;  // the most recent resolve_steps, leading to frames first_step_ + 1..
    std::size_t first_step_ = 0;
    BundleReport adjust_window();

    Camera camera_;
    SlamParams params_;
    Trajectory odometry_;
    Trajectory trajectory_;
    Trajectory adjusted_;
    Trajectory merge_corrections_;  // per frame: the product of the merge corrections so far
    std::deque<KeyFrame> window_;
    std::unordered_map<int, Eigen::Vector3d> landmarks_;  // world positions
    int next_landmark_ = 0;
    EvidenceGrid map_;
    Features features_;
    SparseDisparity disparity_;
    VDisparity vdisp_;
    std::optional<GroundLine> ground_;
    Eigen::Isometry3d last_motion_ = Eigen::Isometry3d::Identity();
    DisparityOffsetEstimator offset_estimator_;
    double calibrated_offset_;  // the camera's offset as given
};

// Camera positions (x, z) of a trajectory, for render_map.
std::vector<Eigen::Vector2d> plane_path(const Trajectory& poses);

}  // namespace stereo::robot::slam
