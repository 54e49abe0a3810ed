#include "stereo_robot/slam/dataset.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <yaml-cpp/yaml.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "stereo_io/io.hpp"
#include "stereo_io/limits.hpp"
#include "stereo_io/text_file.hpp"

namespace stereo::robot::slam {

namespace fs = std::filesystem;

namespace {

std::vector<FramePair> list_frames(const fs::path& left, const fs::path& right) {
    const auto left_names = io::image_file_names(left);
    const auto right_names = io::image_file_names(right);
    if (left_names.empty()) {
        throw std::runtime_error("no images in " + left.string());
    }
    if (left_names != right_names) {
        std::vector<std::string> only_left;
        std::vector<std::string> only_right;
        std::set_difference(left_names.begin(), left_names.end(), right_names.begin(),
                            right_names.end(), std::back_inserter(only_left));
        std::set_difference(right_names.begin(), right_names.end(), left_names.begin(),
                            left_names.end(), std::back_inserter(only_right));
        const std::string example =
            !only_left.empty() ? only_left.front() + " has no partner in " + right.string()
                               : only_right.front() + " has no partner in " + left.string();
        throw std::invalid_argument("unequal frame counts: " + left.string() + " has " +
                                    std::to_string(left_names.size()) + " images, " +
                                    right.string() + " has " + std::to_string(right_names.size()) +
                                    " (" + example + ")");
    }
    return pairs_from_folders(left, right);
}

int parse_index(const std::string& text, const std::string& whole) {
    int value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size()) {
        throw std::invalid_argument("--frames must be A:B with integers, got \"" + whole + "\"");
    }
    return value;
}

// OpenCV's YAML dialect read with yaml-cpp: OpenCV 4.6's own parser can spin forever on a few
// malformed bytes (`%YAML:1.` then `---[]R:.-`). OpenCV writes a non-standard `%YAML:1.0`
// directive first, which yaml-cpp does not accept, so that line is dropped.
YAML::Node load_opencv_yaml(const fs::path& path) {
    constexpr std::uintmax_t kMaxBytes = 1 << 20;  // a rectification file is a few kilobytes
    std::string text = io::read_text_file(path, "rectification file", kMaxBytes);
    if (text.rfind("%YAML:", 0) == 0) {
        const auto end_of_line = text.find('\n');
        text.erase(0, end_of_line == std::string::npos ? text.size() : end_of_line + 1);
    }
    try {
        YAML::Node root = YAML::Load(text);
        if (!root.IsMap()) {
            throw YAML::Exception(YAML::Mark::null_mark(), "not a map");
        }
        return root;
    } catch (const YAML::Exception&) {
        throw std::invalid_argument("rectification file " + path.string() +
                                    " is not an OpenCV YAML file");
    }
}

// An `!!opencv-matrix` entry of rows x cols finite values, as CV_64F.
cv::Mat read_matrix(const YAML::Node& root, const std::string& name, int rows, int cols,
                    const fs::path& path) {
    const auto fail = [&]() {
        return std::invalid_argument("rectification file " + path.string() + " has no " +
                                     std::to_string(rows) + "x" + std::to_string(cols) +
                                     " matrix " + name);
    };
    try {
        const YAML::Node node = root[name];
        if (!node || !node.IsMap() || node["rows"].as<int>() != rows ||
            node["cols"].as<int>() != cols) {
            throw fail();
        }
        const auto data = node["data"].as<std::vector<double>>();
        if (data.size() != static_cast<std::size_t>(rows) * cols ||
            !std::all_of(data.begin(), data.end(), [](double v) { return std::isfinite(v); })) {
            throw fail();
        }
        cv::Mat m(rows, cols, CV_64F);
        std::copy(data.begin(), data.end(), m.begin<double>());
        return m;
    } catch (const YAML::Exception&) {
        throw fail();
    }
}

int read_size(const YAML::Node& root, const char* name, const fs::path& path) {
    try {
        return root[name] ? root[name].as<int>() : 0;
    } catch (const YAML::Exception&) {
        throw std::invalid_argument("rectification file " + path.string() + ": " + name +
                                    " is not a whole number");
    }
}

void load_euroc_rectification(const fs::path& path, Sequence& sequence) {
    const YAML::Node storage = load_opencv_yaml(path);
    const cv::Mat k0 = read_matrix(storage, "K0", 3, 3, path);
    const cv::Mat k1 = read_matrix(storage, "K1", 3, 3, path);
    const cv::Mat d0 = read_matrix(storage, "D0", 1, 4, path);
    const cv::Mat d1 = read_matrix(storage, "D1", 1, 4, path);
    const cv::Mat r1 = read_matrix(storage, "R1", 3, 3, path);
    const cv::Mat r2 = read_matrix(storage, "R2", 3, 3, path);
    const cv::Mat p1 = read_matrix(storage, "P1", 3, 4, path);
    const cv::Mat p2 = read_matrix(storage, "P2", 3, 4, path);
    const int width = read_size(storage, "image_width", path);
    const int height = read_size(storage, "image_height", path);
    // The rectification maps are allocated from this size: bound it like any image.
    if (width > 0 && height > 0 &&
        static_cast<std::int64_t>(width) * height > io::max_image_pixels()) {
        throw std::invalid_argument("rectification file " + path.string() + " declares " +
                                    std::to_string(width) + "x" + std::to_string(height) +
                                    " images, more than the limit of " +
                                    std::to_string(io::max_image_pixels()) + " pixels");
    }
    const double focal = p1.at<double>(0, 0);
    const double baseline = focal > 0.0 ? -p2.at<double>(0, 3) / p2.at<double>(0, 0) : 0.0;
    if (width <= 0 || height <= 0 || !(focal > 0.0) || !(baseline > 0.0)) {
        throw std::invalid_argument("rectification file " + path.string() +
                                    " gives no image size, positive focal length and baseline");
    }
    sequence.camera = {focal, p1.at<double>(0, 2), p1.at<double>(1, 2), baseline};
    sequence.size = cv::Size(width, height);
    cv::initUndistortRectifyMap(k0, d0, r1, p1, sequence.size, CV_32FC1, sequence.left_map_x,
                                sequence.left_map_y);
    cv::initUndistortRectifyMap(k1, d1, r2, p2, sequence.size, CV_32FC1, sequence.right_map_x,
                                sequence.right_map_y);
}

}  // namespace

Layout parse_layout(const std::string& text, const fs::path& sequence) {
    if (text == "kitti") {
        return Layout::kitti;
    }
    if (text == "euroc") {
        return Layout::euroc;
    }
    if (text == "auto") {
        return fs::is_directory(sequence / "cam0") ? Layout::euroc : Layout::kitti;
    }
    throw std::invalid_argument("--layout must be auto, kitti or euroc, got " + text);
}

FrameRange parse_frames(const std::string& text, int count) {
    FrameRange range{0, count};
    if (!text.empty()) {
        const auto colon = text.find(':');
        if (colon == std::string::npos) {
            throw std::invalid_argument("--frames must be A:B (half-open, 0-based), got \"" + text +
                                        "\"");
        }
        const std::string a = text.substr(0, colon);
        const std::string b = text.substr(colon + 1);
        if (!a.empty()) {
            range.begin = parse_index(a, text);
        }
        if (!b.empty()) {
            range.end = parse_index(b, text);
        }
    }
    if (range.begin < 0 || range.end > count || range.begin >= range.end) {
        throw std::invalid_argument("--frames " + text + " is not a non-empty range of the " +
                                    std::to_string(count) + " frames (0-based, half-open A:B)");
    }
    return range;
}

Camera load_kitti_camera(const fs::path& path) {
    const StereoGeometry geometry = load_calibration(path);  // f, B and every format check
    // The principal point, from the same matrix load_calibration took as the left one.
    std::istringstream in(io::read_text_file(path, "calibration file"));
    std::vector<std::pair<std::string, std::vector<double>>> matrices;
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream tokens(line);
        std::string first;
        if (!(tokens >> first)) {
            continue;
        }
        std::string label;
        if (first.back() == ':') {
            label = first.substr(0, first.size() - 1);
        } else {
            tokens.clear();
            tokens.str(line);
        }
        std::vector<double> values;
        double value = 0.0;
        while (values.size() < 12 && tokens >> value) {
            values.push_back(value);
        }
        std::string rest;
        if (values.size() == 12 && !(tokens >> rest)) {
            matrices.emplace_back(label, values);
        }
    }
    const auto labelled = std::find_if(matrices.begin(), matrices.end(),
                                       [](const auto& m) { return m.first == "P0"; });
    const bool has_right = std::any_of(matrices.begin(), matrices.end(),
                                       [](const auto& m) { return m.first == "P1"; });
    const std::vector<double>& left =
        labelled != matrices.end() && has_right ? labelled->second : matrices.front().second;
    return {geometry.focal_px, left[2], left[6], geometry.baseline};
}

Sequence open_sequence(const fs::path& dir, Layout layout, const std::optional<fs::path>& calib) {
    if (!fs::is_directory(dir)) {
        throw std::runtime_error("cannot read sequence folder " + dir.string());
    }
    Sequence sequence;
    sequence.layout = layout;
    if (layout == Layout::kitti) {
        sequence.frames = list_frames(dir / "image_l", dir / "image_r");
        sequence.camera = load_kitti_camera(calib.value_or(dir / "calib.txt"));
        const fs::path first = sequence.frames.front().first;
        sequence.size = io::load_grey(first).size();
        const fs::path poses = dir / "poses.txt";
        if (fs::exists(poses)) {
            Trajectory truth = load_kitti_poses(poses);
            if (truth.size() != sequence.frames.size()) {
                throw std::invalid_argument("pose file " + poses.string() + " has " +
                                            std::to_string(truth.size()) + " poses for " +
                                            std::to_string(sequence.frames.size()) + " frames");
            }
            sequence.truth = std::move(truth);
        }
    } else {
        sequence.frames = list_frames(dir / "cam0" / "data", dir / "cam1" / "data");
        load_euroc_rectification(calib.value_or(dir / "stereo_rectification_opencv.yaml"),
                                 sequence);
    }
    return sequence;
}

StereoFrame load_frame(const Sequence& sequence, int index, int downscale) {
    const auto& [left_path, right_path] = sequence.frames.at(static_cast<std::size_t>(index));
    StereoFrame frame;
    cv::Mat* const targets[] = {&frame.left, &frame.right};
    const fs::path* const paths[] = {&left_path, &right_path};
    for (int side = 0; side < 2; ++side) {
        cv::Mat image = io::load_grey(*paths[side]);
        if (image.size() != sequence.size) {
            throw std::invalid_argument(
                "image " + paths[side]->string() + " is " + std::to_string(image.cols) + "x" +
                std::to_string(image.rows) + ", the sequence's frames are " +
                std::to_string(sequence.size.width) + "x" + std::to_string(sequence.size.height));
        }
        if (!sequence.left_map_x.empty()) {
            cv::Mat rectified;
            if (side == 0) {
                cv::remap(image, rectified, sequence.left_map_x, sequence.left_map_y,
                          cv::INTER_LINEAR);
            } else {
                cv::remap(image, rectified, sequence.right_map_x, sequence.right_map_y,
                          cv::INTER_LINEAR);
            }
            image = rectified;
        }
        if (downscale > 1) {
            image = io::shrink_area(image, downscale);
        }
        *targets[side] = image;
    }
    return frame;
}

}  // namespace stereo::robot::slam
