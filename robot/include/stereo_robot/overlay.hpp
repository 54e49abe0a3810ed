// Pictures of a decision: the left image with the three windows, the pixels nearer than the
// safety distance, each window's occupancy and the chosen direction.
#pragma once

#include <array>
#include <filesystem>
#include <memory>
#include <string>

#include <opencv2/core/mat.hpp>

#include "stereo/image.hpp"
#include "stereo_robot/decision.hpp"

namespace stereo::robot {

struct OverlayInfo {
    std::array<double, 3> occupancy{};  // per window, [0, 1]
    Direction direction = Direction::forward;
    double angle_deg = 0.0;  // drawn as an arrow; the threshold method uses -20 / 0 / +20
    std::string caption;     // e.g. frame name and method
};

// `left` is the left image in OpenCV BGR (or grey) order, of the map's size.
// Near pixels are tinted red, near pixels that the ground model ignores (optional) blue.
cv::Mat draw_overlay(const cv::Mat& left, const DisparityMap& map, double threshold, int border,
                     const OverlayInfo& info, const GroundModel* ground = nullptr);

// Throws std::invalid_argument unless `path` can hold the overlay: a .png file, or for a sequence
// also an .avi video (any case). Called before the first frame is processed.
void check_overlay_path(const std::filesystem::path& path, bool sequence);

// Collects the overlays of a sequence: an MJPG .avi when the path ends in .avi, otherwise a
// PNG contact sheet of thumbnails (4 per row, at most 320 pixels wide each). Nothing is
// written until finish(), which throws std::runtime_error when the file cannot be written;
// both kinds are written to a temporary file and renamed, so a failure leaves no partial file.
class SequenceWriter {
  public:
    SequenceWriter(std::filesystem::path path, double fps);
    ~SequenceWriter();
    SequenceWriter(const SequenceWriter&) = delete;
    SequenceWriter& operator=(const SequenceWriter&) = delete;

    void add(const cv::Mat& overlay);
    void finish();

  private:
    struct State;
    std::unique_ptr<State> state_;
};

}  // namespace stereo::robot
