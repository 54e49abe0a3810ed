#include "stereo_robot/overlay.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "stereo_io/io.hpp"
#include "stereo_io/mjpeg_avi.hpp"
#include "stereo_io/output.hpp"
#include "stereo_robot/ground.hpp"

namespace stereo::robot {
namespace {

const cv::Scalar kNear{0, 0, 255};        // red: nearer than the safety distance
const cv::Scalar kWindow{255, 255, 255};  // window frames
const cv::Scalar kArrow{0, 255, 0};

const cv::Scalar kGround{255, 0, 0};  // blue: near, but ground the model ignores

// The key of the overlay's colours (issue 47), in a dark box at the top right, below the
// occupancy labels: one swatch and
// name per colour the picture uses. Drawn inside the picture, so that its size (and a video's)
// stays the map's; left out of images too small to hold it.
void draw_legend(cv::Mat& out, bool ground, double font, int thick) {
    std::vector<std::pair<std::string, cv::Scalar>> entries = {{"near (closer than safe)", kNear}};
    if (ground) {
        entries.emplace_back("near ground (ignored)", kGround);
    }
    entries.emplace_back("window, occupancy", kWindow);
    entries.emplace_back("direction", kArrow);
    const double scale = 0.5 * font;
    int baseline = 0;
    int width = 0;
    for (const auto& entry : entries) {
        width = std::max(
            width,
            cv::getTextSize(entry.first, cv::FONT_HERSHEY_SIMPLEX, scale, thick, &baseline).width);
    }
    const int line = static_cast<int>(22 * scale) + 6;
    const int swatch = line - 6;
    // Below the windows' occupancy labels (drawn 28 * font below their top).
    const cv::Rect box(out.cols - (width + swatch + 16) - 4, static_cast<int>(50 * font) + 8,
                       width + swatch + 16, line * static_cast<int>(entries.size()) + 6);
    if (box.x < out.cols / 2 || box.y + box.height > out.rows / 2) {
        return;
    }
    cv::Mat region = out(box);
    region *= 0.35;  // darkened, the picture still visible through it
    int y = box.y + 4;
    for (const auto& [name, colour] : entries) {
        cv::rectangle(out, cv::Rect(box.x + 4, y, swatch, swatch), colour, cv::FILLED);
        cv::putText(out, name, cv::Point(box.x + swatch + 10, y + swatch - 1),
                    cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar::all(255), thick, cv::LINE_AA);
        y += line;
    }
}

constexpr int kSheetColumns = 4;
constexpr int kThumbWidth = 320;

}  // namespace

cv::Mat draw_overlay(const cv::Mat& left, const DisparityMap& map, double threshold, int border,
                     const OverlayInfo& info, const GroundModel* ground) {
    if (left.cols != map.width || left.rows != map.height) {
        throw std::invalid_argument("overlay image and disparity map differ in size");
    }
    cv::Mat out;
    if (left.channels() == 1) {
        cv::cvtColor(left, out, cv::COLOR_GRAY2BGR);
    } else {
        out = left.clone();
    }
    // Tint near pixels half-way to red; the ground model's ground (and overhead) pixels in blue.
    for (int y = 0; y < map.height; ++y) {
        auto* row = out.ptr<cv::Vec3b>(y);
        for (int x = 0; x < map.width; ++x) {
            const std::size_t i = map.index(x, y);
            if (map.valid[i] == 0 || !(map.disparity[i] > threshold)) {
                continue;
            }
            if (ground != nullptr && !ground->obstacle(y, map.disparity[i])) {
                row[x] = cv::Vec3b(static_cast<std::uint8_t>(128 + row[x][0] / 2), row[x][1] / 2,
                                   row[x][2] / 2);
            } else {
                row[x] = cv::Vec3b(row[x][0] / 2, row[x][1] / 2,
                                   static_cast<std::uint8_t>(128 + row[x][2] / 2));
            }
        }
    }
    const auto windows = split_windows(map.width, map.height, border);
    const double font = std::max(0.4, map.height / 500.0);
    const int thick = std::max(1, map.height / 250);
    for (int i = 0; i < 3; ++i) {
        const Rect& w = windows[i];
        cv::rectangle(out, cv::Point(w.x0, w.y0), cv::Point(w.x1 - 1, w.y1 - 1), kWindow, thick);
        char text[32];
        std::snprintf(text, sizeof text, "%.0f%%", 100.0 * info.occupancy[i]);
        cv::putText(out, text, cv::Point(w.x0 + 6, w.y0 + static_cast<int>(28 * font)),
                    cv::FONT_HERSHEY_SIMPLEX, font, kWindow, thick + 1);
    }
    // Direction arrow from the bottom centre; angle 0 points up, negative to the left.
    const cv::Point base(map.width / 2, map.height - border - 4);
    const double length = 0.35 * map.height;
    if (info.direction == Direction::backwards) {
        cv::arrowedLine(out, base - cv::Point(0, static_cast<int>(length)), base, kArrow, thick + 2,
                        cv::LINE_AA, 0, 0.2);
    } else {
        const double a = info.angle_deg * std::numbers::pi / 180.0;
        const cv::Point tip(base.x + static_cast<int>(std::lround(length * std::sin(a))),
                            base.y - static_cast<int>(std::lround(length * std::cos(a))));
        cv::arrowedLine(out, base, tip, kArrow, thick + 2, cv::LINE_AA, 0, 0.2);
    }
    const std::string label =
        to_string(info.direction) + (info.caption.empty() ? std::string() : "  " + info.caption);
    cv::putText(out, label, cv::Point(border + 6, map.height - border - 8),
                cv::FONT_HERSHEY_SIMPLEX, font, kArrow, thick + 1);
    draw_legend(out, ground != nullptr, font, thick);
    return out;
}

struct SequenceWriter::State {
    std::filesystem::path path;
    double fps = 10.0;
    bool video = false;
    std::vector<cv::Mat> frames;
};

namespace {

std::string lower_extension(const std::filesystem::path& path) {
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return extension;
}

}  // namespace

void check_overlay_path(const std::filesystem::path& path, bool sequence) {
    const std::string extension = lower_extension(path);
    if (extension == ".png" || (sequence && extension == ".avi")) {
        return;
    }
    throw std::invalid_argument(
        "--overlay " + path.string() +
        (sequence ? " must end in .png (contact sheet) or .avi (video)" : " must end in .png"));
}

SequenceWriter::SequenceWriter(std::filesystem::path path, double fps)
    : state_(std::make_unique<State>()) {
    state_->video = lower_extension(path) == ".avi";
    state_->path = std::move(path);
    state_->fps = fps;
}

SequenceWriter::~SequenceWriter() = default;

void SequenceWriter::add(const cv::Mat& overlay) {
    if (state_->video) {
        state_->frames.push_back(overlay.clone());
        return;
    }
    const double scale = std::min(1.0, static_cast<double>(kThumbWidth) / overlay.cols);
    cv::Mat thumb;
    cv::resize(overlay, thumb, cv::Size(), scale, scale, cv::INTER_AREA);
    state_->frames.push_back(thumb);
}

void SequenceWriter::finish() {
    auto& frames = state_->frames;
    if (frames.empty()) {
        return;
    }
    if (state_->video) {
        io::write_file_atomic(state_->path, io::mjpeg_avi(frames, state_->fps));  // atomic
        return;
    }
    const int cols = std::min<int>(kSheetColumns, static_cast<int>(frames.size()));
    const int rows = (static_cast<int>(frames.size()) + cols - 1) / cols;
    const cv::Size cell = frames.front().size();
    cv::Mat sheet(rows * cell.height, cols * cell.width, CV_8UC3, cv::Scalar(0, 0, 0));
    for (std::size_t i = 0; i < frames.size(); ++i) {
        const int r = static_cast<int>(i) / cols;
        const int c = static_cast<int>(i) % cols;
        cv::Mat fitted;
        cv::resize(frames[i], fitted, cell, 0, 0, cv::INTER_AREA);
        fitted.copyTo(sheet(cv::Rect(c * cell.width, r * cell.height, cell.width, cell.height)));
    }
    io::write_png(state_->path, sheet);  // atomic
}

}  // namespace stereo::robot
