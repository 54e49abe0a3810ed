#include "stereo_robot/calibration.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "stereo_io/io.hpp"
#include "stereo_io/text_file.hpp"

namespace stereo::robot {
namespace fs = std::filesystem;
namespace {

using Projection = std::array<double, 12>;

// io::image_file_names with this function's own message for a missing folder.
std::vector<std::string> image_names(const fs::path& folder) {
    if (!fs::is_directory(folder)) {
        throw std::runtime_error("cannot read folder " + folder.string());
    }
    return io::image_file_names(folder);
}

}  // namespace

StereoGeometry load_calibration(const fs::path& path) {
    std::istringstream in(io::read_text_file(path, "calibration file"));
    std::vector<std::pair<std::string, Projection>> matrices;
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream tokens(line);
        std::string label;
        std::string first;
        if (!(tokens >> first)) {
            continue;
        }
        if (first.back() == ':') {
            label = first.substr(0, first.size() - 1);
        } else {
            tokens.clear();
            tokens.str(line);
        }
        Projection p{};
        int count = 0;
        double value = 0.0;
        while (count < 12 && tokens >> value) {
            p[count++] = value;
        }
        std::string rest;
        if (count == 12 && !(tokens >> rest)) {
            matrices.emplace_back(label, p);
        }
    }
    const auto find = [&](const std::string& name) -> const Projection* {
        for (const auto& [label, p] : matrices) {
            if (label == name) {
                return &p;
            }
        }
        return nullptr;
    };
    const Projection* left = find("P0");
    const Projection* right = find("P1");
    if (left == nullptr || right == nullptr) {
        if (matrices.size() < 2) {
            throw std::invalid_argument("calibration file " + path.string() +
                                        " holds fewer than two 3x4 projection matrices");
        }
        left = &matrices[0].second;
        right = &matrices[1].second;
    }
    const double focal = (*left)[0];
    const double baseline = focal != 0.0 ? ((*left)[3] - (*right)[3]) / focal : 0.0;
    if (!(focal > 0.0) || !(baseline > 0.0) || !std::isfinite(baseline)) {
        throw std::invalid_argument("calibration file " + path.string() +
                                    " gives no positive focal length and baseline");
    }
    return {focal, baseline, (*left)[2], (*left)[6]};
}

double disparity_threshold(const StereoGeometry& geometry, double safe_distance, int downscale) {
    // A real rig and a distance a robot can see: also rejects inf and NaN, and keeps the
    // threshold f B / Z a finite number of pixels (focal 1e-300 or Z = inf gave 0 or inf).
    if (!(geometry.focal_px >= 1.0 && geometry.focal_px <= 1e6) ||
        !(geometry.baseline >= 1e-3 && geometry.baseline <= 1e3)) {
        throw std::invalid_argument(
            "focal length must be in [1, 1e6] px and baseline in [0.001, 1000] m");
    }
    if (!(safe_distance >= 1e-3 && safe_distance <= 1e4)) {
        char text[96];
        std::snprintf(text, sizeof text, "safe distance must be in [0.001, 10000] m, got %g",
                      safe_distance);
        throw std::invalid_argument(text);
    }
    if (downscale < 1) {
        throw std::invalid_argument("downscale must be >= 1");
    }
    return geometry.focal_px * geometry.baseline / (safe_distance * downscale);
}

std::vector<FramePair> pairs_from_folders(const fs::path& left, const fs::path& right) {
    const auto left_names = image_names(left);
    const auto right_names = image_names(right);
    std::vector<std::string> common;
    std::set_intersection(left_names.begin(), left_names.end(), right_names.begin(),
                          right_names.end(), std::back_inserter(common));
    if (common.empty()) {
        throw std::runtime_error("no image file name is present in both " + left.string() +
                                 " and " + right.string());
    }
    std::vector<FramePair> pairs;
    for (const auto& name : common) {
        pairs.emplace_back(left / name, right / name);
    }
    return pairs;
}

std::vector<FramePair> pairs_from_list(const fs::path& list) {
    std::istringstream in(io::read_text_file(list, "list file"));
    const fs::path base = list.parent_path();
    std::vector<FramePair> pairs;
    std::string line;
    int number = 0;
    while (std::getline(in, line)) {
        ++number;
        std::istringstream tokens(line);
        std::string left;
        std::string right;
        if (!(tokens >> left) || left.front() == '#') {
            continue;
        }
        std::string extra;
        if (!(tokens >> right) || (tokens >> extra)) {
            throw std::invalid_argument("list file " + list.string() + " line " +
                                        std::to_string(number) + ": expected \"LEFT RIGHT\"");
        }
        const auto resolve = [&](const fs::path& p) { return p.is_absolute() ? p : base / p; };
        pairs.emplace_back(resolve(left), resolve(right));
    }
    if (pairs.empty()) {
        throw std::runtime_error("list file " + list.string() + " names no pair");
    }
    return pairs;
}

}  // namespace stereo::robot
