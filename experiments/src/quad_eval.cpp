// `stereo_experiments quad-eval`: docs/results-quad.md. On the antinous light field (a 9 x 9
// camera grid with the centre view's ground truth) it takes 2 x 2 squares of baseline n = 4 and
// n = 2 with the centre view as the upper-left reference, runs the three pairs and the fused
// quad matcher (stereo/quad.hpp), the equivalent two-camera matcher (23 x 23), the two-camera
// 13 x 13 matcher with stage 6 and OpenCV SGBM on the horizontal pair, all in the same run,
// scores them against masks derived from the ground truth, and draws a Fig. 3.6-like montage
// and a rendering of the fused point cloud.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "cli_command.hpp"
#include "experiments.hpp"
#include "stereo/catalogue.hpp"
#include "stereo/defaults.hpp"
#include "stereo/quad.hpp"
#include "stereo_io/data_dir.hpp"
#include "stereo_io/disparity_files.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/metrics.hpp"
#include "stereo_io/point_cloud.hpp"
#include "stereo_io/versioned_json.hpp"

namespace stereo::experiments {
namespace {
namespace fs = std::filesystem;
using json = nlohmann::json;
using quad::Pair;

constexpr int kCentreView = 40;  // row 4, column 4 of the 9 x 9 grid
constexpr int kGridSide = 9;
constexpr int kQuadWindow = 13;        // thesis Sec. 3.2
constexpr int kEquivalentWindow = 23;  // 3 x 13^2 = 507 ~ 23^2 = 529 costs per pixel and label
// Masks (docs/results-quad.md "Masks"): a reference pixel is occluded in a partner view when a
// pixel of larger disparity lands within half a pixel of its own projection there and is nearer
// by more than kOcclusionMargin; a discontinuity is a jump of more than kJump between 4-neighbours
// of the ground truth, widened by kDiscRadius.
constexpr double kOcclusionMargin = 0.5;
constexpr double kJump = 1.0;
constexpr int kDiscRadius = 4;

struct Options : cli::ReportOptions {
    static constexpr std::string_view kName = "quad-eval";
    static constexpr std::string_view kDescription =
        "Quad-camera fusion on the antinous light field against each pair, the two-camera "
        "23 x 23 matcher and SGBM (docs/results-quad.md).";
    std::string figures;  // folder for quad_*.png
    std::string ply;      // also write the fused n = 4 cloud here
    std::vector<int> baselines = {4, 2};
    // `stereo match`'s default cost first (the figures), then the thesis' AD cost.
    std::vector<std::string> costs = {std::string(defaults::kCost), "ad"};
};

struct Views {
    std::array<Image, 4> images;  // reference, horizontal, vertical, diagonal
    std::array<cv::Mat, 4> bgr;
};

Views load_views(const fs::path& folder, int n) {
    Views views;
    const std::array<int, 4> index = {kCentreView, kCentreView + n, kCentreView + kGridSide * n,
                                      kCentreView + (kGridSide + 1) * n};
    for (std::size_t v = 0; v < index.size(); ++v) {
        char name[32];
        std::snprintf(name, sizeof name, "input_Cam%03d.png", index[v]);
        views.images[v] = io::load_image(folder / name);
        views.bgr[v] = io::load_bgr(folder / name);
    }
    return views;
}

cv::Mat mask_of(const cv::Mat& flags) {
    cv::Mat out;
    flags.convertTo(out, CV_8UC1, 255.0);
    return out;
}

// 1 where the reference pixel is seen by the partner along `step` (docs/results-quad.md).
cv::Mat visible_in(const cv::Mat& gt, quad::Step s) {
    const int width = gt.cols;
    const int height = gt.rows;
    cv::Mat nearest(height, width, CV_32FC1, cv::Scalar(-std::numeric_limits<float>::infinity()));
    // Forward warp: every reference pixel splats its disparity on the partner cells around its
    // projection (both neighbours along each moving axis), keeping the largest.
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const float d = gt.at<float>(y, x);
            const double px = x - d * s.x;
            const double py = y - d * s.y;
            for (int j = 0; j <= s.y; ++j) {
                for (int i = 0; i <= s.x; ++i) {
                    const int cx = static_cast<int>(std::floor(px)) + i;
                    const int cy = static_cast<int>(std::floor(py)) + j;
                    if (cx >= 0 && cy >= 0 && cx < width && cy < height) {
                        float& cell = nearest.at<float>(cy, cx);
                        cell = std::max(cell, d);
                    }
                }
            }
        }
    }
    cv::Mat visible(height, width, CV_8UC1, cv::Scalar(0));
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const float d = gt.at<float>(y, x);
            const int cx = static_cast<int>(std::lround(x - d * s.x));
            const int cy = static_cast<int>(std::lround(y - d * s.y));
            if (cx < 0 || cy < 0 || cx >= width || cy >= height) {
                continue;  // outside the partner view
            }
            visible.at<std::uint8_t>(y, x) = nearest.at<float>(cy, cx) <= d + kOcclusionMargin;
        }
    }
    return visible;
}

struct Masks {
    cv::Mat nonocc;
    cv::Mat all;
    cv::Mat disc;
    int frame = 0;
};

Masks make_masks(const cv::Mat& gt, int frame) {
    const int width = gt.cols;
    const int height = gt.rows;
    cv::Mat inside(height, width, CV_8UC1, cv::Scalar(0));
    inside(cv::Rect(frame, frame, width - 2 * frame, height - 2 * frame)).setTo(1);
    cv::Mat visible = inside.clone();
    for (const Pair pair : quad::kPairs) {
        visible &= visible_in(gt, quad::step(pair));
    }
    cv::Mat jump(height, width, CV_8UC1, cv::Scalar(0));
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const float d = gt.at<float>(y, x);
            const bool right = x + 1 < width && std::abs(gt.at<float>(y, x + 1) - d) > kJump;
            const bool below = y + 1 < height && std::abs(gt.at<float>(y + 1, x) - d) > kJump;
            if (right || below) {
                jump.at<std::uint8_t>(y, x) = 1;
                jump.at<std::uint8_t>(std::min(y + (below ? 1 : 0), height - 1),
                                      std::min(x + (right ? 1 : 0), width - 1)) = 1;
            }
        }
    }
    cv::Mat wide;
    cv::dilate(jump, wide,
               cv::getStructuringElement(cv::MORPH_RECT,
                                         cv::Size(2 * kDiscRadius + 1, 2 * kDiscRadius + 1)));
    return {mask_of(visible), mask_of(inside), mask_of(wide & visible), frame};
}

struct Row {
    std::string name;
    cv::Mat disparity;  // CV_32FC1, NaN invalid
    double ms = 0.0;
    std::string note;
};

// A float map (NaN invalid) against the light field's signed GT, on the three masks.
io::EvalInput eval_input(const cv::Mat& disparity, const std::string& name, const cv::Mat& gt,
                         const Masks& masks) {
    return {.disparity = {disparity, name},
            .ground_truth = {gt, "gt"},
            .nonocc = io::NamedMat{masks.nonocc, "nonocc"},
            .all = io::NamedMat{masks.all, "all"},
            .disc = io::NamedMat{masks.disc, "disc"},
            .threshold = 1.0,
            .zero_is_invalid = false,
            .gt_zero_is_unknown = false};
}

json score(const Row& row, const cv::Mat& gt, const Masks& masks) {
    const io::EvalResult r = io::evaluate(eval_input(row.disparity, row.name, gt, masks));
    std::int64_t valid_inside = 0;
    std::int64_t inside = 0;
    for (int y = 0; y < gt.rows; ++y) {
        for (int x = 0; x < gt.cols; ++x) {
            if (masks.all.at<std::uint8_t>(y, x) == 255) {
                ++inside;
                valid_inside += std::isfinite(row.disparity.at<float>(y, x)) ? 1 : 0;
            }
        }
    }
    return {{"name", row.name},
            {"bad_nonocc", r.nonocc->percent().value_or(0.0)},
            {"bad_all", r.all.percent().value_or(0.0)},
            {"bad_disc", r.disc->percent().value_or(0.0)},
            {"bad_nonocc_pixels", r.nonocc->bad},
            {"coverage", 100.0 * static_cast<double>(valid_inside) / inside},
            {"ms", row.ms},
            {"note", row.note}};
}

template <typename F>
auto timed(double& ms, F run) {
    const auto start = std::chrono::steady_clock::now();
    auto result = run();
    ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return result;
}

cv::Mat run_sgbm(const Views& views, int min_disp, int ndisp) {
    // The parameters of io::run_stereo_sgbm (OpenCV's stereo_match sample, block 5), with the
    // signed range.
    constexpr int kBlock = 5;
    constexpr int kChannels = 3;
    const int range = (ndisp + 15) / 16 * 16;
    const auto sgbm = cv::StereoSGBM::create(
        min_disp, range, kBlock, 8 * kChannels * kBlock * kBlock, 32 * kChannels * kBlock * kBlock,
        1, 63, 10, 100, 32, cv::StereoSGBM::MODE_SGBM);
    cv::Mat raw;
    sgbm->compute(views.bgr[0], views.bgr[1], raw);
    cv::Mat out(raw.size(), CV_32FC1);
    for (int y = 0; y < raw.rows; ++y) {
        for (int x = 0; x < raw.cols; ++x) {
            const short v = raw.at<short>(y, x);
            out.at<float>(y, x) =
                v >= min_disp * 16 ? v / 16.0F : std::numeric_limits<float>::quiet_NaN();
        }
    }
    return out;
}

// ---- figures ------------------------------------------------------------------------------

constexpr int kTile = 224;
constexpr int kTitle = 22;

cv::Mat colour_disparity(const cv::Mat& d, double lo, double hi) {
    cv::Mat scaled(d.size(), CV_8UC1);
    for (int y = 0; y < d.rows; ++y) {
        for (int x = 0; x < d.cols; ++x) {
            const float v = d.at<float>(y, x);
            scaled.at<std::uint8_t>(y, x) = std::isfinite(v)
                                                ? static_cast<std::uint8_t>(std::clamp(
                                                      255.0 * (v - lo) / (hi - lo), 0.0, 255.0))
                                                : 0;
        }
    }
    cv::Mat colour;
    cv::applyColorMap(scaled, colour, cv::COLORMAP_TURBO);
    for (int y = 0; y < d.rows; ++y) {
        for (int x = 0; x < d.cols; ++x) {
            if (!std::isfinite(d.at<float>(y, x))) {
                colour.at<cv::Vec3b>(y, x) = cv::Vec3b(0, 0, 0);
            }
        }
    }
    return colour;
}

cv::Mat grey_tile(const std::vector<std::uint8_t>& bytes, int width, int height) {
    cv::Mat grey(height, width, CV_8UC1);
    std::copy(bytes.begin(), bytes.end(), grey.data);
    cv::Mat bgr;
    cv::cvtColor(grey, bgr, cv::COLOR_GRAY2BGR);
    return bgr;
}

const std::array<cv::Vec3b, 4> kSourceColours = {cv::Vec3b(0, 0, 0), cv::Vec3b(40, 40, 230),
                                                 cv::Vec3b(40, 200, 40), cv::Vec3b(230, 120, 30)};

cv::Mat source_tile(const std::vector<std::uint8_t>& source, int width, int height) {
    cv::Mat out(height, width, CV_8UC3);
    for (std::size_t p = 0; p < source.size(); ++p) {
        out.at<cv::Vec3b>(static_cast<int>(p)) = kSourceColours[source[p]];
    }
    return out;
}

cv::Mat titled(const cv::Mat& image, const std::string& title) {
    cv::Mat small;
    cv::resize(image, small, cv::Size(kTile, kTile), 0, 0, cv::INTER_AREA);
    cv::Mat out(kTile + kTitle, kTile, CV_8UC3, cv::Scalar(255, 255, 255));
    small.copyTo(out(cv::Rect(0, kTitle, kTile, kTile)));
    cv::putText(out, title, cv::Point(4, 16), cv::FONT_HERSHEY_SIMPLEX, 0.42, cv::Scalar(0, 0, 0),
                1, cv::LINE_AA);
    return out;
}

// A horizontal colour bar of `width` with labels at both ends and the middle.
cv::Mat colour_bar(int width, const std::string& title, double lo, double hi, bool grey) {
    cv::Mat ramp(1, width, CV_8UC1);
    for (int x = 0; x < width; ++x) {
        ramp.at<std::uint8_t>(0, x) = static_cast<std::uint8_t>(255 * x / (width - 1));
    }
    cv::Mat colour;
    if (grey) {
        cv::cvtColor(ramp, colour, cv::COLOR_GRAY2BGR);
    } else {
        cv::applyColorMap(ramp, colour, cv::COLORMAP_TURBO);
    }
    cv::Mat bar;
    cv::resize(colour, bar, cv::Size(width, 14), 0, 0, cv::INTER_NEAREST);
    cv::Mat out(44, width, CV_8UC3, cv::Scalar(255, 255, 255));
    bar.copyTo(out(cv::Rect(0, 16, width, 14)));
    cv::putText(out, title, cv::Point(4, 12), cv::FONT_HERSHEY_SIMPLEX, 0.42, cv::Scalar(0, 0, 0),
                1, cv::LINE_AA);
    char text[32];
    for (const double f : {0.0, 0.5, 1.0}) {
        std::snprintf(text, sizeof text, "%.1f", lo + f * (hi - lo));
        const int x = std::clamp(static_cast<int>(f * (width - 1)) - 12, 0, width - 40);
        cv::putText(out, text, cv::Point(x, 42), cv::FONT_HERSHEY_SIMPLEX, 0.4, cv::Scalar(0, 0, 0),
                    1, cv::LINE_AA);
    }
    return out;
}

cv::Mat montage(const Views& views, const quad::QuadResult& result, const cv::Mat& gt,
                const io::EvalInput& fused_input, int n, double lo, double hi) {
    const int w = gt.cols;
    const int h = gt.rows;
    std::vector<cv::Mat> tiles;
    const char* view_names[4] = {"reference (view 40)", "horizontal partner", "vertical partner",
                                 "diagonal partner"};
    for (int v = 0; v < 4; ++v) {
        tiles.push_back(titled(views.bgr[v], view_names[v]));
    }
    for (const Pair pair : quad::kPairs) {
        tiles.push_back(
            titled(grey_tile(result.pairs[static_cast<std::size_t>(pair)].certainty, w, h),
                   "certainty, " + std::string(quad::name(pair))));
    }
    tiles.push_back(titled(grey_tile(result.fused.certainty, w, h), "fused certainty"));
    for (const Pair pair : quad::kPairs) {
        tiles.push_back(titled(
            colour_disparity(io::to_float_disparity(result.pairs[static_cast<std::size_t>(pair)]),
                             lo, hi),
            "disparity, " + std::string(quad::name(pair))));
    }
    tiles.push_back(
        titled(colour_disparity(io::to_float_disparity(result.fused), lo, hi), "fused disparity"));
    tiles.push_back(titled(colour_disparity(gt, lo, hi), "ground truth (n * g)"));
    tiles.push_back(titled(source_tile(result.source, w, h), "source: red H, green V, blue D"));
    {
        cv::Mat masks(h, w, CV_8UC3, cv::Scalar(0, 0, 0));
        masks.setTo(cv::Scalar(90, 90, 90), fused_input.all->mat == 255);
        masks.setTo(cv::Scalar(255, 255, 255), fused_input.nonocc->mat == 255);
        masks.setTo(cv::Scalar(0, 170, 255), fused_input.disc->mat == 255);
        tiles.push_back(titled(masks, "nonocc (white), disc (orange)"));
    }
    tiles.push_back(titled(io::error_map(fused_input), "fused: bad > 1 (red, blue)"));
    constexpr int kColumns = 4;
    const int rows = static_cast<int>((tiles.size() + kColumns - 1) / kColumns);
    cv::Mat grid(rows * (kTile + kTitle), kColumns * kTile, CV_8UC3, cv::Scalar(255, 255, 255));
    for (std::size_t t = 0; t < tiles.size(); ++t) {
        const int r = static_cast<int>(t) / kColumns;
        const int c = static_cast<int>(t) % kColumns;
        tiles[t].copyTo(grid(cv::Rect(c * kTile, r * (kTile + kTitle), kTile, kTile + kTitle)));
    }
    char title[64];
    std::snprintf(title, sizeof title, "disparity (px), baseline n = %d", n);
    cv::Mat bars;
    cv::hconcat(colour_bar(2 * kTile, title, lo, hi, false),
                colour_bar(2 * kTile, "certainty (0..255)", 0, 255, true), bars);
    cv::Mat out;
    cv::vconcat(grid, bars, out);
    return out;
}

// The cloud seen from a camera turned by `yaw` about the vertical axis through the cloud's
// median point, 1.6 median depths away: points projected nearest first (a z-buffer), two-pixel
// splats.
cv::Mat render_cloud(const std::vector<io::CloudPoint>& points, int size, double yaw) {
    cv::Mat out(size, size, CV_8UC3, cv::Scalar(30, 30, 30));
    if (points.empty()) {
        return out;
    }
    const auto median = [&](auto member) {
        std::vector<float> values;
        values.reserve(points.size());
        for (const auto& p : points) {
            values.push_back(p.*member);
        }
        std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
        return static_cast<double>(values[values.size() / 2]);
    };
    const double mx = median(&io::CloudPoint::x);
    const double my = median(&io::CloudPoint::y);
    const double mz = median(&io::CloudPoint::z);
    const double c = std::cos(yaw);
    const double s = std::sin(yaw);
    const double focal = 0.9 * size;
    cv::Mat zbuffer(size, size, CV_32FC1, cv::Scalar(std::numeric_limits<float>::infinity()));
    for (const auto& p : points) {
        const double x0 = p.x - mx;
        const double z0 = p.z - mz;
        const double x = c * x0 + s * z0;
        const double z = -s * x0 + c * z0 + 1.6 * mz;
        if (z <= 0) {
            continue;
        }
        const int u = static_cast<int>(size / 2 + focal * x / z);
        const int v = static_cast<int>(size / 2 + focal * (p.y - my) / z);
        for (int dv = 0; dv < 2; ++dv) {
            for (int du = 0; du < 2; ++du) {
                const int uu = u + du;
                const int vv = v + dv;
                if (uu < 0 || vv < 0 || uu >= size || vv >= size) {
                    continue;
                }
                float& depth = zbuffer.at<float>(vv, uu);
                if (z < depth) {
                    depth = static_cast<float>(z);
                    out.at<cv::Vec3b>(vv, uu) = cv::Vec3b(p.blue, p.green, p.red);
                }
            }
        }
    }
    return out;
}

// ---- the report ---------------------------------------------------------------------------

// The heading of a cost's tables.
std::string cost_title(const std::string& cost) {
    if (cost == "ad") {
        return "AD cost (the thesis')";
    }
    return cost + " cost" + (cost == defaults::kCost ? " (`stereo match`'s default)" : "");
}

std::string markdown(const json& report) {
    std::ostringstream md;
    md << "# Quad-camera results (issue 22)\n\n"
       << "Generated by `stereo_experiments quad-eval` (experiments/src/quad_eval.cpp); do not "
          "edit by hand. Reproduce (a few seconds on two cores):\n\n"
       << "```\ncmake --build build -j2 --target stereo_experiments\n"
          "./build/experiments/stereo_experiments quad-eval --markdown docs/results-quad.md \\\n"
          "    --json docs/figures/quad_results.json --figures docs/figures\n```\n\n"
       << "Method and hardware note: [quad.md](quad.md). Scene: `lightfield/antinous` (HCI 4D "
          "light field, 512 x 512, a 9 x 9 grid); reference view 40, partners 40 + n (right), "
          "40 + 9n (below), 40 + 10n (below right); ground truth `d = n * g` from "
          "`gt_disp_lowres.pfm`. Every matcher here searches the same signed range, derived from "
          "the ground truth's extremes: `min_disp = floor(min d) - 1`, `ndisp` up to "
          "`ceil(max d) + 1`. The quad pairs use the Sec. 3.1 pipeline with a 13 x 13 window, "
          "sigma 3 (the default), CA rules on, stage 6 without uniqueness or left-right check "
          "(dense, as in the thesis' Table 3.3; only the border rule invalidates). Every table "
          "is given twice: with the thesis' AD cost, and with the 5x5 census cost, which "
          "`stereo match` and `stereo quad` use by default (chosen on the Middlebury scenes, "
          "[results.md](results.md#defaults), not here). The two-camera rows use the same cost "
          "as the pairs above them.\n\n";
    md << "## Masks\n\n"
       << "The light field has no occlusion masks; these are derived from the reference view's "
          "ground truth (`experiments/src/quad_eval.cpp`, `make_masks`):\n\n"
       << "* **frame**: a pixel is scored only at least `reach(23 x 23) + max |d|` pixels from "
          "every image edge (the same frame for every row, so that no matcher is scored where "
          "its window or its search leaves the image; given "
          "per baseline below).\n"
       << "* **all** = the frame (the ground truth is dense).\n"
       << "* **nonocc** = pixels of `all` visible in all three partner views. Visibility by "
          "forward warping: every reference pixel `p` with disparity `d` projects to "
          "`p - d * step` in the partner (`step` = (1, 0), (0, 1), (1, 1)) and writes `d` on the "
          "cells next to its projection (floor and floor + 1 along each moving axis), keeping "
          "the largest; `p` is occluded when the cell nearest its own projection holds a "
          "disparity larger than `d + 0.5` (a nearer surface covers it), and out of view when "
          "that cell lies outside the image. One mask for every row, so that the pair-wise, "
          "fused and two-camera rows are scored on the same pixels.\n"
       << "* **disc** = pixels of `nonocc` within 4 pixels (a 9 x 9 box dilation) of a "
          "discontinuity: a ground-truth jump of more than 1 px between 4-neighbours (the "
          "bad-pixel threshold, so that a jump counts when it is larger than the error scored; "
          "Middlebury's disc masks are made the same way: a disparity-jump threshold and a "
          "dilation).\n\n"
       << "A pixel is bad when it is invalid or `|d - gt| > 1`; coverage is the share of `all` "
          "with a valid output. Times: one run each, on the machine of the run (two cores), "
          "the quad row with its three pairs on three threads.\n\n";
    for (const json& block : report["baselines"]) {
        const int n = block["n"];
        const std::string cost = block["cost"];
        md << "## Baseline n = " << n << ", " << cost_title(cost) << " (views 40 / " << 40 + n
           << " / " << 40 + 9 * n << " / " << 40 + 10 * n << ")\n\n"
           << "Search range " << block["min_disp"].get<int>() << " .. "
           << block["min_disp"].get<int>() + block["ndisp"].get<int>() - 1 << " ("
           << block["ndisp"].get<int>() << " labels); frame " << block["frame"].get<int>()
           << " px; ground truth " << fmt(block["gt_min"].get<double>()) << " .. "
           << fmt(block["gt_max"].get<double>()) << " px; scored pixels: all "
           << block["pixels_all"].get<long long>() << ", nonocc "
           << block["pixels_nonocc"].get<long long>() << ", disc "
           << block["pixels_disc"].get<long long>() << ".\n\n"
           << "| matcher | bad > 1 nonocc % | all % | disc % | coverage % | time ms |\n"
           << "|---|---|---|---|---|---|\n";
        for (const json& row : block["rows"]) {
            md << "| " << row["name"].get<std::string>();
            if (!row["note"].get<std::string>().empty()) {
                md << " (" << row["note"].get<std::string>() << ")";
            }
            md << " | " << fmt(row["bad_nonocc"]) << " | " << fmt(row["bad_all"]) << " | "
               << fmt(row["bad_disc"]) << " | " << fmt(row["coverage"]) << " | " << fmt(row["ms"])
               << " |\n";
        }
        const json& src = block["source_share"];
        md << "\nSource of the fused pixels (share of all pixels): horizontal "
           << fmt(src["horizontal"]) << " %, vertical " << fmt(src["vertical"]) << " %, diagonal "
           << fmt(src["diagonal"]) << " %, none " << fmt(src["none"]) << " %.\n\n";
        const json& goals = block["goals"];
        md << "Goals at n = " << n << ", " << cost << " cost:\n\n"
           << "* fused at or below the best single pair on nonocc (" << fmt(goals["fused_nonocc"])
           << " vs " << fmt(goals["best_pair_nonocc"]) << "): **"
           << (goals["nonocc_met"].get<bool>() ? "met" : "not met") << "**\n"
           << "* fused at or below the best single pair on all (" << fmt(goals["fused_all"])
           << " vs " << fmt(goals["best_pair_all"]) << "): **"
           << (goals["all_met"].get<bool>() ? "met" : "not met") << "**\n"
           << "* at least 25 % fewer bad nonocc pixels than the equivalent two-camera 23 x 23 "
              "matcher (sigma 3: "
           << fmt(goals["reduction_vs_23"])
           << " % fewer; sigma scaled: " << fmt(goals["reduction_vs_23_scaled"]) << " % fewer): **"
           << (goals["reduction_met"].get<bool>() ? "met" : "not met")
           << "** (met only when the fused map has at least 25 % fewer than both rows)\n"
           << "* the same with `--fuse-by cost`: nonocc " << fmt(goals["cost_fused_nonocc"])
           << " (**" << (goals["cost_nonocc_met"].get<bool>() ? "met" : "not met") << "**), all "
           << fmt(goals["cost_fused_all"]) << " (**"
           << (goals["cost_all_met"].get<bool>() ? "met" : "not met") << "**), "
           << fmt(goals["cost_reduction_vs_23"]) << " % / "
           << fmt(goals["cost_reduction_vs_23_scaled"])
           << " % fewer bad nonocc pixels than the two 23 x 23 rows (**"
           << (goals["cost_reduction_met"].get<bool>() ? "met" : "not met") << "**)\n"
           << "* not a goal, for completeness: disc, fused " << fmt(goals["fused_disc"])
           << " vs best pair " << fmt(goals["best_pair_disc"]) << "\n\n";
    }
    md << "## The fusion keys with the reference at each corner\n\n"
       << "The reference view 40 at each corner of the square (the views and the ground truth "
          "flipped so that the partners lie right, below and below right; the same scene, with "
          "its occlusions on other sides), bad > 1 %, fused by certainty (the default) and by "
          "cost; `fewer`: bad nonocc pixels fewer than the two-camera 23 x 23 (sigma 3) matcher "
          "on the reference and its horizontal partner.\n\n"
       << "| matching cost | corner | n | best pair nonocc | 23 x 23 nonocc | certainty nonocc / "
          "all | fewer % | cost nonocc / all | fewer % |\n|---|---|---|---|---|---|---|---|---|\n";
    for (const json& row : report["orientations"]) {
        md << "| " << row["cost"].get<std::string>() << " | " << row["corner"].get<std::string>()
           << " | " << row["n"].get<int>() << " | " << fmt(row["best_pair_nonocc"]) << " | "
           << fmt(row["two_camera_nonocc"]) << " | " << fmt(row["certainty_nonocc"]) << " / "
           << fmt(row["certainty_all"]) << " | " << fmt(row["certainty_fewer"]) << " | "
           << fmt(row["cost_nonocc"]) << " / " << fmt(row["cost_all"]) << " | "
           << fmt(row["cost_fewer"]) << " |\n";
    }
    md << "\n";
    md << "## Reading the tables\n\n"
       << "* Nothing here is tuned to this scene: the window (13 x 13) is the thesis', sigma 3 "
          "was chosen on the Middlebury 2003 pairs ([sigma-sweep.md](sigma-sweep.md)), the "
          "fusion has no numeric parameter (its key is a switch: the certainty by default, the "
          "winner cost as the alternative reported beside it; this is the only 2 x 2 scene, so "
          "it does not choose the default, [quad.md](quad.md#the-fusion-key)), the census cost "
          "is `stereo match`'s default, chosen on the eight Middlebury scenes, and the mask "
          "thresholds (0.5 px occlusion margin, 1 px "
          "jump, 4 px dilation) were fixed before the first run from the bad-pixel threshold "
          "and Middlebury's practice.\n"
       << "* The equivalent two-camera matcher has the quad's cost budget (23^2 = 529 against "
          "3 x 13^2 = 507 costs per pixel and label). With the default sigma 3 its Gaussian "
          "weights fall to almost nothing beyond radius 9, so a 23 x 23 window weighs nearly "
          "the same pixels as the 13 x 13 one; the second row scales sigma with the window "
          "(3 x 23 / 11), so that the larger window is really used. The goal is judged against "
          "both rows; the sigma-3 row is the harder one.\n"
       << "* The pairs are dense (only the border rule invalidates), as in the thesis' Table "
          "3.3, so coverage inside the frame is 100 % for them and for the fused map; the "
          "two-camera 13 x 13 row with stage 6 shows what `stereo match`'s validation for the "
          "cost (its uniqueness ratio and left-right tolerance, sub-pixel, the speckle filter) "
          "gives on the same pair, every invalid pixel counted as bad: this scene chose none of "
          "those defaults, so it is a held-out check of them. SGBM fills its own holes "
          "differently and is shown for reference.\n"
       << "* For scale, the thesis' Table 3.3 (Tsukuba, bad > 1 nonocc / all / disc): "
          "horizontal 16.2 / 18.1 / 29.9, vertical 12.5 / 13.8 / 35.1, diagonal 10.7 / 12.4 / "
          "32.3, fused 10.8 / 12.6 / 31.5, two-camera 23 x 23 15.8 / 17.6 / 33.9 — there the "
          "fused map was not below the best pair (the diagonal); a different scene, rig and "
          "masks, so only the pattern compares.\n"
       << "* Times are single runs on a shared two-core machine; the fused row runs three "
          "threads on two cores, so it costs about the sum of the three pairs here and would "
          "cost about one pair with three cores (or three hardware pipelines).\n\n";
    md << "## Figures\n\n"
       << "![quad montage, n = 4](figures/quad_montage_n4.png)\n\n"
       << "Fig. 3.6 of the thesis, for antinous at n = 4, with `stereo quad`'s defaults (the "
          "first cost above): the four views; the certainty of each "
          "pair and the fused certainty (black 0, white 255); each pair's disparity and the "
          "fused one (colour bar below, black = invalid); the ground truth; the source map; the "
          "masks (white nonocc, grey all only, orange disc); the fused map's errors (red wrong, "
          "blue invalid, grey right, black not scored).\n\n"
       << "![point cloud](figures/quad_cloud_n4.png)\n\n"
       << "The same fused n = 4 map as a point cloud (`stereo cloud`, binary PLY, read back and "
          "rendered from a camera turned by 25 degrees). "
       << report["cloud_note"].get<std::string>() << "\n";
    return md.str();
}

// What every square is scored with: the search range from the ground truth's extremes, the
// frame, the masks, and the quad's matcher parameters.
struct Setup {
    double gt_min = 0.0;
    double gt_max = 0.0;
    MatchParams params;  // the range min_disp .. min_disp + ndisp - 1, the 13 x 13 window
    Masks masks;         // with their frame
};

Setup setup_for(const cv::Mat& gt) {
    Setup s;
    cv::minMaxLoc(gt, &s.gt_min, &s.gt_max);
    const int lowest = static_cast<int>(std::floor(s.gt_min)) - 1;
    const int highest = static_cast<int>(std::ceil(s.gt_max)) + 1;
    s.params.min_disp = lowest;
    s.params.ndisp = highest - lowest + 1;
    s.params.window = kQuadWindow;
    s.masks = make_masks(gt, (kEquivalentWindow / 2 + 1) + std::max(-lowest, highest));
    return s;
}

// The reference view 40 at each corner of the square: the rig's four mirror images. cv::flip of
// every view and of the ground truth brings each to the arrangement the matcher expects
// (partners right, below, below right); the disparities keep their sign. One scene still, but
// the occlusions fall on other sides of every object, so the fusion keys meet other cases.
struct Orientation {
    const char* corner;
    int dx;    // the horizontal partner's column step
    int dy;    // the vertical partner's row step
    int flip;  // cv::flip code; kNoFlip: none
};
constexpr int kNoFlip = 2;
constexpr std::array<Orientation, 4> kOrientations = {{{"upper left", 1, 1, kNoFlip},
                                                       {"upper right", -1, 1, 1},
                                                       {"lower left", 1, -1, 0},
                                                       {"lower right", -1, -1, -1}}};

cv::Mat flipped(const cv::Mat& mat, int code) {
    if (code == kNoFlip) {
        return mat.clone();
    }
    cv::Mat out;
    cv::flip(mat, out, code);
    return out;
}

json orientation_study(const fs::path& folder, const cv::Mat& g, const std::vector<int>& sides,
                       const std::string& cost_name) {
    json out = json::array();
    for (const int n : sides) {
        for (const Orientation& o : kOrientations) {
            std::cerr << "quad-eval: " << cost_name << ", orientation " << o.corner << ", n = " << n
                      << '\n';
            const std::array<int, 4> index = {kCentreView, kCentreView + o.dx * n,
                                              kCentreView + kGridSide * o.dy * n,
                                              kCentreView + o.dx * n + kGridSide * o.dy * n};
            std::array<Image, 4> images;
            for (std::size_t v = 0; v < index.size(); ++v) {
                char name[32];
                std::snprintf(name, sizeof name, "input_Cam%03d.png", index[v]);
                images[v] = io::to_image(flipped(io::load_bgr(folder / name), o.flip), name);
            }
            const cv::Mat gt = flipped(g * n, o.flip);
            Setup s = setup_for(gt);
            s.params.cost = cost_name;
            const quad::QuadViews views{images[0], images[1], images[2], images[3]};
            const quad::QuadResult by_certainty = quad::match_quad(views, s.params);
            const quad::QuadResult by_cost =
                quad::match_quad(views, s.params, true, quad::FusionKey::cost);
            MatchParams wide = s.params;
            wide.window = kEquivalentWindow;
            const auto two_camera = match_validated(images[0], images[1], wide);
            const auto nonocc = [&](const ValidatedDisparity& map, const std::string& name) {
                return score({name, io::to_float_disparity(map), 0.0, ""}, gt, s.masks);
            };
            double best_pair = 100.0;
            for (const auto& pair : by_certainty.pairs) {
                best_pair = std::min(best_pair, nonocc(pair, "pair")["bad_nonocc"].get<double>());
            }
            const json certainty = nonocc(by_certainty.fused, "certainty");
            const json cost = nonocc(by_cost.fused, "cost");
            const json wide_row = nonocc(two_camera, "23 x 23");
            const auto fewer = [&](const json& fused) {
                return 100.0 *
                       (1.0 -
                        static_cast<double>(fused["bad_nonocc_pixels"].get<long long>()) /
                            static_cast<double>(wide_row["bad_nonocc_pixels"].get<long long>()));
            };
            out.push_back({{"corner", o.corner},
                           {"cost", cost_name},
                           {"n", n},
                           {"best_pair_nonocc", best_pair},
                           {"two_camera_nonocc", wide_row["bad_nonocc"]},
                           {"certainty_nonocc", certainty["bad_nonocc"]},
                           {"certainty_all", certainty["bad_all"]},
                           {"certainty_fewer", fewer(certainty)},
                           {"cost_nonocc", cost["bad_nonocc"]},
                           {"cost_all", cost["bad_all"]},
                           {"cost_fewer", fewer(cost)}});
        }
    }
    return out;
}

void run_quad_eval(const Options& options) {
    check_report_outputs({options.markdown, options.json_path}, {options.figures},
                         options.data_dir);
    const fs::path folder = fs::path(options.data_dir) / "lightfield" / "antinous";
    const fs::path gt_path = folder / "gt_disp_lowres.pfm";
    if (!fs::exists(gt_path)) {
        throw std::runtime_error("no antinous light field under '" + options.data_dir + "'");
    }
    const cv::Mat g = io::load_disparity_file(gt_path, io::DisparityEncoding::pfm, 1.0);
    json report = {{"baselines", json::array()}};
    OutputFiles files;
    for (const std::string& cost_name : options.costs) {
        for (const int n : options.baselines) {
            std::cerr << "quad-eval: " << cost_name << ", n = " << n << '\n';
            const Views views = load_views(folder, n);
            const cv::Mat gt = g * n;
            const Setup setup = setup_for(gt);
            // Named references, not a structured binding: lambdas below capture them (clang 14).
            const double gt_min = setup.gt_min;
            const double gt_max = setup.gt_max;
            MatchParams cost_params = setup.params;
            cost_params.cost = cost_name;
            const MatchParams& params = cost_params;
            const int min_disp = params.min_disp;
            const int ndisp = params.ndisp;
            const int max_disp = min_disp + ndisp - 1;
            const Masks& masks = setup.masks;
            const int frame = masks.frame;
            std::vector<Row> rows;
            std::array<double, 3> pair_ms{};
            for (const Pair pair : quad::kPairs) {
                const auto p = static_cast<std::size_t>(pair);
                const auto map = timed(pair_ms[p], [&] {
                    return quad::match_pair(pair, views.images[0], views.images[p + 1], params);
                });
                rows.push_back({std::string(quad::name(pair)) + " 13 x 13",
                                io::to_float_disparity(map), pair_ms[p], ""});
            }
            double quad_ms = 0.0;
            const quad::QuadResult result = timed(quad_ms, [&] {
                return quad::match_quad(
                    {views.images[0], views.images[1], views.images[2], views.images[3]}, params);
            });
            rows.push_back({"fused (quad)", io::to_float_disparity(result.fused), quad_ms,
                            "three pairs on three threads"});
            double cost_ms = 0.0;
            const quad::QuadResult by_cost = timed(cost_ms, [&] {
                return quad::match_quad(
                    {views.images[0], views.images[1], views.images[2], views.images[3]}, params,
                    true, quad::FusionKey::cost);
            });
            rows.push_back({"fused (quad, --fuse-by cost)", io::to_float_disparity(by_cost.fused),
                            cost_ms, "the smallest winner cost wins"});
            for (const double sigma : {params.sigma, params.sigma * kEquivalentWindow / 11.0}) {
                MatchParams wide = params;
                wide.window = kEquivalentWindow;
                wide.sigma = sigma;
                double ms = 0.0;
                const auto map = timed(
                    ms, [&] { return match_validated(views.images[0], views.images[1], wide); });
                rows.push_back(
                    {"two-camera 23 x 23", io::to_float_disparity(map), ms, "sigma " + fmt(sigma)});
            }
            {
                // `stereo match`'s validation for this cost: its uniqueness ratio and left-right
                // tolerance (stereo/defaults.hpp), sub-pixel, then the speckle filter.
                const defaults::Validation chosen = defaults::validation_for(cost_name);
                double ms = 0.0;
                const auto map = timed(ms, [&] {
                    return match_as_stereo_match(views.images[0], views.images[1], params);
                });
                rows.push_back({"two-camera 13 x 13", io::to_float_disparity(map), ms,
                                "stereo match's stage 6 for the cost: uniqueness " +
                                    std::to_string(chosen.uniqueness) + ", left-right " +
                                    std::to_string(chosen.lr_tolerance) +
                                    ", sub-pixel, speckle filter"});
            }
            {
                double ms = 0.0;
                const cv::Mat map = timed(ms, [&] { return run_sgbm(views, min_disp, ndisp); });
                rows.push_back({"OpenCV SGBM", map, ms, "horizontal pair, block 5"});
            }
            json block = {{"n", n},
                          {"cost", cost_name},
                          {"min_disp", min_disp},
                          {"ndisp", ndisp},
                          {"gt_min", gt_min},
                          {"gt_max", gt_max},
                          {"frame", frame},
                          {"pixels_all", cv::countNonZero(masks.all)},
                          {"pixels_nonocc", cv::countNonZero(masks.nonocc)},
                          {"pixels_disc", cv::countNonZero(masks.disc)},
                          {"rows", json::array()}};
            for (const Row& row : rows) {
                block["rows"].push_back(score(row, gt, masks));
            }
            std::array<double, 4> share{};
            for (const auto s : result.source) {
                share[s] += 100.0 / static_cast<double>(result.source.size());
            }
            block["source_share"] = {{"none", share[0]},
                                     {"horizontal", share[1]},
                                     {"vertical", share[2]},
                                     {"diagonal", share[3]}};
            const json& r = block["rows"];
            const double best_nonocc =
                std::min({r[0]["bad_nonocc"].get<double>(), r[1]["bad_nonocc"].get<double>(),
                          r[2]["bad_nonocc"].get<double>()});
            const double best_all =
                std::min({r[0]["bad_all"].get<double>(), r[1]["bad_all"].get<double>(),
                          r[2]["bad_all"].get<double>()});
            const double fused_nonocc = r[3]["bad_nonocc"];
            const double fused_all = r[3]["bad_all"];
            // How many fewer bad nonocc pixels a fused row has than a two-camera row, in %.
            const auto reduction = [](const json& fused, const json& wide) {
                return 100.0 *
                       (1.0 - static_cast<double>(fused["bad_nonocc_pixels"].get<long long>()) /
                                  static_cast<double>(wide["bad_nonocc_pixels"].get<long long>()));
            };
            const double red = reduction(r[3], r[5]);
            const double red_scaled = reduction(r[3], r[6]);
            const double cost_red = reduction(r[4], r[5]);
            const double cost_red_scaled = reduction(r[4], r[6]);
            const double best_disc =
                std::min({r[0]["bad_disc"].get<double>(), r[1]["bad_disc"].get<double>(),
                          r[2]["bad_disc"].get<double>()});
            block["goals"] = {{"fused_disc", r[3]["bad_disc"].get<double>()},
                              {"best_pair_disc", best_disc},
                              {"fused_nonocc", fused_nonocc},
                              {"best_pair_nonocc", best_nonocc},
                              {"nonocc_met", fused_nonocc <= best_nonocc},
                              {"fused_all", fused_all},
                              {"best_pair_all", best_all},
                              {"all_met", fused_all <= best_all},
                              {"reduction_vs_23", red},
                              {"reduction_vs_23_scaled", red_scaled},
                              {"reduction_met", red >= 25.0 && red_scaled >= 25.0},
                              {"cost_fused_nonocc", r[4]["bad_nonocc"].get<double>()},
                              {"cost_fused_all", r[4]["bad_all"].get<double>()},
                              {"cost_nonocc_met", r[4]["bad_nonocc"].get<double>() <= best_nonocc},
                              {"cost_all_met", r[4]["bad_all"].get<double>() <= best_all},
                              {"cost_reduction_vs_23", cost_red},
                              {"cost_reduction_vs_23_scaled", cost_red_scaled},
                              {"cost_reduction_met", cost_red >= 25.0 && cost_red_scaled >= 25.0}};
            report["baselines"].push_back(block);

            if (n == options.baselines.front() && cost_name == options.costs.front() &&
                !options.figures.empty()) {
                const io::EvalInput fused_input = eval_input(rows[3].disparity, "fused", gt, masks);
                const fs::path dir(options.figures);
                const std::string suffix = "_n" + std::to_string(n) + ".png";
                files.emplace_back(
                    dir / ("quad_montage" + suffix),
                    io::encode_png(montage(views, result, gt, fused_input, n, min_disp, max_disp),
                                   dir / ("quad_montage" + suffix)));
                // The light field's camera constants are not in the data folder: a nominal focal
                // length of 512 px, one unit of baseline per view step, and a disparity offset of
                // 8 n (cloud_note), so the cloud's shape is right up to that projective choice.
                const io::CloudGeometry geometry{512.0, static_cast<double>(n), 255.5, 255.5,
                                                 8.0 * n};
                const std::string ply = io::encode_ply(
                    io::disparity_to_points(rows[3].disparity, views.bgr[0], geometry), true);
                const auto points = io::decode_ply(ply, "fused cloud");
                files.emplace_back(dir / ("quad_cloud" + suffix),
                                   io::encode_png(render_cloud(points, 640, 25.0 * CV_PI / 180.0),
                                                  dir / ("quad_cloud" + suffix)));
                if (!options.ply.empty()) {
                    files.emplace_back(options.ply, ply);
                }
                report["cloud_note"] =
                    "The light field's camera constants are not in the data folder, so the cloud "
                    "uses "
                    "a nominal focal length of 512 px, one unit of baseline per view step and a "
                    "disparity offset of 8 n (`--doffs`; any offset beyond the scene's most "
                    "negative "
                    "g = -3.13 gives positive depths, 8 keeps the depth range of the bust and the "
                    "wall "
                    "within a factor of two so that both are visible): the shape is right up to "
                    "that "
                    "projective choice. " +
                    std::to_string(points.size()) + " points.";
            }
        }
    }
    if (!report.contains("cloud_note")) {
        report["cloud_note"] = "";
    }
    report["orientations"] = json::array();
    for (const std::string& cost_name : options.costs) {
        for (json& row : orientation_study(folder, g, options.baselines, cost_name)) {
            report["orientations"].push_back(std::move(row));
        }
    }
    print_and_write_report(std::move(files), options.markdown, markdown(report), options.json_path,
                           report);
}

}  // namespace

void add_quad_eval_command(CLI::App& app) {
    const auto [command, options] = cli::add_report_command<Options>(app, run_quad_eval);
    command->add_option("--figures", options->figures, "Folder for quad_montage / quad_cloud PNGs");
    command->add_option("--ply", options->ply, "Also write the fused n = 4 cloud (binary PLY)");
    command->add_option("--baselines", options->baselines, "Square sides n (first: figures)")
        ->capture_default_str();
    command
        ->add_option("--costs", options->costs,
                     "Matching costs of the pairs and the two-camera rows (first: figures)")
        ->check(CLI::IsMember(catalogue::cost_names(catalogue::CostUse::pixel_pair)))
        ->capture_default_str();
}

}  // namespace stereo::experiments
