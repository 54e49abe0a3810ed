// Stereo sequences on disk for `stereo slam`: the KITTI layout of ../shared/data/sequence
// (image_l/, image_r/, calib.txt, optional poses.txt) and the EuRoC ASL layout (cam0/data,
// cam1/data, raw images rectified with an OpenCV stereo-rectification YAML).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "stereo_robot/calibration.hpp"
#include "stereo_robot/slam/evaluation.hpp"
#include "stereo_robot/slam/motion.hpp"

namespace stereo::robot::slam {

enum class Layout { kitti, euroc };

// "auto": euroc when SEQ_DIR/cam0 exists, else kitti. Throws std::invalid_argument otherwise.
Layout parse_layout(const std::string& text, const std::filesystem::path& sequence);

// Half-open frame range [begin, end) of the sorted frames.
struct FrameRange {
    int begin = 0;
    int end = 0;
};

// "A:B", "A:" (to the end), ":B" or "" (all), 0-based, half-open. Throws std::invalid_argument
// unless 0 <= A < B <= count and both are integers.
FrameRange parse_frames(const std::string& text, int count);

struct Sequence {
    Layout layout = Layout::kitti;
    std::vector<FramePair> frames;
    Camera camera;                    // of the full-size rectified images
    cv::Size size;                    // every frame's size (frame 0's, or the calibration's)
    std::optional<Trajectory> truth;  // left-camera poses, one per frame (KITTI poses.txt)
    // EuRoC: undistort-rectify maps of the left and right camera (empty for KITTI).
    cv::Mat left_map_x, left_map_y, right_map_x, right_map_y;
};

// Opens a sequence: lists the frames (the same file names in both folders, else
// std::invalid_argument "unequal frame counts" naming the first unpaired file), reads the
// calibration (`calib` overrides SEQ_DIR/calib.txt or SEQ_DIR/stereo_rectification_opencv.yaml)
// and, for KITTI, poses.txt when present (std::invalid_argument when it has fewer lines than
// there are frames). Missing folders or files: std::runtime_error.
Sequence open_sequence(const std::filesystem::path& dir, Layout layout,
                       const std::optional<std::filesystem::path>& calib);

// The KITTI calibration (see load_calibration) with the principal point of the left matrix.
Camera load_kitti_camera(const std::filesystem::path& path);

struct StereoFrame {
    cv::Mat left;  // 8-bit grey, rectified, shrunk by the downscale factor
    cv::Mat right;
};

// Reads frame i as grey (std::runtime_error when unreadable), checks that both images have the
// sequence's size (std::invalid_argument), rectifies (EuRoC) and shrinks by `downscale` with
// area averaging.
StereoFrame load_frame(const Sequence& sequence, int index, int downscale);

}  // namespace stereo::robot::slam
