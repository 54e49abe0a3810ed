// `stereo_experiments avoid-figures OUTPUT_FOLDER`: draws the figures of docs/avoidance.md with
// OpenCV: the membership functions of the fuzzy system and its control surface.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>
#include <opencv2/imgproc.hpp>

#include "cli_command.hpp"
#include "experiments.hpp"
#include "stereo_io/io.hpp"
#include "stereo_robot/decision.hpp"

namespace stereo::experiments {
namespace {

namespace fs = std::filesystem;
using robot::Direction;
using robot::FisParams;
using robot::Gaussian;

constexpr int kWidth = 560;
constexpr int kHeight = 300;
constexpr int kMargin = 50;
const cv::Scalar kBlack{0, 0, 0};
const cv::Scalar kGrey{190, 190, 190};

struct Curve {
    std::string name;
    std::function<double(double)> f;
    cv::Scalar colour;
};

// Plot area [kMargin, kWidth - 20] x [20, kHeight - kMargin], y from 0 to 1.
cv::Mat line_plot(const std::string& title, double lo, double hi, double tick,
                  const std::vector<Curve>& curves, double vertical_line = NAN) {
    cv::Mat img(kHeight, kWidth, CV_8UC3, cv::Scalar(255, 255, 255));
    const int x0 = kMargin;
    const int x1 = kWidth - 20;
    const int y0 = 30;
    const int y1 = kHeight - kMargin;
    const auto px = [&](double x) {
        return x0 + static_cast<int>((x - lo) / (hi - lo) * (x1 - x0));
    };
    const auto py = [&](double y) { return y1 - static_cast<int>(y * (y1 - y0)); };
    for (double t = lo; t <= hi + 1e-9; t += tick) {
        cv::line(img, {px(t), y0}, {px(t), y1}, kGrey, 1);
        char label[16];
        std::snprintf(label, sizeof label, "%g", std::abs(t) < 1e-12 ? 0.0 : t);
        cv::putText(img, label, {px(t) - 10, y1 + 18}, cv::FONT_HERSHEY_SIMPLEX, 0.4, kBlack, 1,
                    cv::LINE_AA);
    }
    for (double v = 0; v <= 1.0001; v += 0.25) {
        cv::line(img, {x0, py(v)}, {x1, py(v)}, kGrey, 1);
        char label[16];
        std::snprintf(label, sizeof label, "%.2f", v);
        cv::putText(img, label, {4, py(v) + 4}, cv::FONT_HERSHEY_SIMPLEX, 0.4, kBlack, 1,
                    cv::LINE_AA);
    }
    cv::rectangle(img, {x0, y0}, {x1, y1}, kBlack, 1);
    if (!std::isnan(vertical_line)) {
        cv::line(img, {px(vertical_line), y0}, {px(vertical_line), y1}, {0, 0, 200}, 1,
                 cv::LINE_AA);
    }
    int legend_y = y0 + 16;
    for (const auto& curve : curves) {
        std::vector<cv::Point> points;
        for (int i = 0; i <= 600; ++i) {
            const double x = lo + (hi - lo) * i / 600.0;
            points.emplace_back(px(x), py(curve.f(x)));
        }
        cv::polylines(img, points, false, curve.colour, 2, cv::LINE_AA);
        cv::putText(img, curve.name, {x1 - 120, legend_y}, cv::FONT_HERSHEY_SIMPLEX, 0.45,
                    curve.colour, 1, cv::LINE_AA);
        legend_y += 18;
    }
    cv::putText(img, title, {x0, 20}, cv::FONT_HERSHEY_SIMPLEX, 0.5, kBlack, 1, cv::LINE_AA);
    return img;
}

std::function<double(double)> mf(const Gaussian& g) {
    return [g](double x) { return g(x); };
}

// The occupancy plots: kCells x kCells squares (occupancy 0, 0.01, ..., 1) of `cell` pixels,
// drawn at (kLeftPad, kTop) on a white canvas with room for labels and `extra_right` pixels.
constexpr int kCells = 101;
constexpr int kLeftPad = 50;
constexpr int kTop = 30;

cv::Mat blank_plot(int cell, int extra_right) {
    return {kTop + kCells * cell + 45, kLeftPad + kCells * cell + extra_right, CV_8UC3,
            cv::Scalar(255, 255, 255)};
}

// Tick labels 0, 0.25, ..., 1 along the x and y axes of a square plot of cells x cells squares
// of `cell` pixels whose top-left corner is (left, top).
void occupancy_ticks(cv::Mat& img, int left, int top, int cells, int cell) {
    const int side = cells * cell;
    for (int k = 0; k <= 4; ++k) {
        char label[8];
        std::snprintf(label, sizeof label, "%.2f", k / 4.0);
        const int pos = k * (cells - 1) * cell / 4;
        cv::putText(img, label, {left + pos - 12, top + side + 16}, cv::FONT_HERSHEY_SIMPLEX, 0.4,
                    kBlack, 1, cv::LINE_AA);
        cv::putText(img, label, {8, top + side - pos + 4}, cv::FONT_HERSHEY_SIMPLEX, 0.4, kBlack, 1,
                    cv::LINE_AA);
    }
}

// Angle over centre occupancy (x) and left occupancy (y), right occupancy fixed; cells where
// the robot backs off are hatched black.
cv::Mat surface(double right, const FisParams& params) {
    constexpr int kCell = 4;
    cv::Mat img = blank_plot(kCell, 90);
    cv::Mat value(kCells, kCells, CV_8UC1);
    cv::Mat back(kCells, kCells, CV_8UC1);
    for (int i = 0; i < kCells; ++i) {      // centre
        for (int j = 0; j < kCells; ++j) {  // left
            const auto r = stereo::robot::evaluate_fis(j / 100.0, i / 100.0, right, params);
            value.at<std::uint8_t>(kCells - 1 - j, i) =
                static_cast<std::uint8_t>(std::lround((r.angle_deg + 30.0) / 60.0 * 255.0));
            back.at<std::uint8_t>(kCells - 1 - j, i) = r.backwards > params.backwards_threshold;
        }
    }
    cv::Mat colour;
    cv::applyColorMap(value, colour, cv::COLORMAP_JET);
    for (int r = 0; r < kCells; ++r) {
        for (int c = 0; c < kCells; ++c) {
            if (back.at<std::uint8_t>(r, c) != 0 && (r + c) % 4 == 0) {
                colour.at<cv::Vec3b>(r, c) = cv::Vec3b(0, 0, 0);
            }
        }
    }
    cv::Mat big;
    cv::resize(colour, big, cv::Size(kCells * kCell, kCells * kCell), 0, 0, cv::INTER_NEAREST);
    big.copyTo(img(cv::Rect(kLeftPad, kTop, big.cols, big.rows)));
    char title[96];
    std::snprintf(title, sizeof title, "angle (deg); x: centre, y: left occupancy; right = %.1f",
                  right);
    cv::putText(img, title, {kLeftPad, 20}, cv::FONT_HERSHEY_SIMPLEX, 0.5, kBlack, 1, cv::LINE_AA);
    occupancy_ticks(img, kLeftPad, kTop, kCells, kCell);
    cv::putText(img, "centre occupancy (y: left occupancy)",
                {kLeftPad + 130, kTop + kCells * kCell + 36}, cv::FONT_HERSHEY_SIMPLEX, 0.45,
                kBlack, 1, cv::LINE_AA);
    // Colour bar.
    const int bar_x = kLeftPad + kCells * kCell + 15;
    for (int y = 0; y < kCells * kCell; ++y) {
        cv::Mat one(1, 1, CV_8UC1,
                    cv::Scalar(255 - static_cast<int>(y * 255.0 / (kCells * kCell - 1))));
        cv::Mat c;
        cv::applyColorMap(one, c, cv::COLORMAP_JET);
        cv::line(img, {bar_x, kTop + y}, {bar_x + 15, kTop + y}, c.at<cv::Vec3b>(0, 0), 1);
    }
    for (const int deg : {30, 0, -30}) {
        const int y = kTop + static_cast<int>((30 - deg) / 60.0 * (kCells * kCell - 1));
        cv::putText(img, std::to_string(deg), {bar_x + 20, y + 4}, cv::FONT_HERSHEY_SIMPLEX, 0.4,
                    kBlack, 1, cv::LINE_AA);
    }
    return img;
}

// The decision over centre occupancy (x) and left occupancy (y), right occupancy fixed:
// forward green, left blue, right red, backwards black. `before`: the issue-8 rule (10-degree
// band on the Mamdani angle, no default rule); else the current decision.
cv::Mat decision_map(double right, const FisParams& params, bool before) {
    constexpr int kCell = 3;
    cv::Mat img = blank_plot(kCell, 20);
    const auto colour_of = [](Direction d) {
        switch (d) {
            case Direction::forward:
                return cv::Vec3b(60, 180, 60);
            case Direction::left:
                return cv::Vec3b(220, 120, 40);
            case Direction::right:
                return cv::Vec3b(40, 40, 220);
            case Direction::backwards:
                return cv::Vec3b(0, 0, 0);
        }
        return cv::Vec3b(255, 255, 255);
    };
    for (int i = 0; i < kCells; ++i) {      // centre
        for (int j = 0; j < kCells; ++j) {  // left
            const auto r = stereo::robot::evaluate_fis(j / 100.0, i / 100.0, right, params);
            Direction d = r.decision;
            if (before) {
                d = r.backwards > params.backwards_threshold ? Direction::backwards
                    : r.mamdani_angle_deg < -10.0            ? Direction::left
                    : r.mamdani_angle_deg > 10.0             ? Direction::right
                                                             : Direction::forward;
            }
            const cv::Rect cell(kLeftPad + i * kCell, kTop + (kCells - 1 - j) * kCell, kCell,
                                kCell);
            img(cell).setTo(colour_of(d));
        }
    }
    // The rate: from this centre occupancy on, "forward" is unsafe.
    const int x_rate = kLeftPad + static_cast<int>(std::lround(params.rate * 100.0 * kCell));
    cv::line(img, {x_rate, kTop}, {x_rate, kTop + kCells * kCell}, cv::Scalar(0, 200, 255), 1);
    char title[120];
    std::snprintf(title, sizeof title, "%s; right = %.1f", before ? "before" : "after", right);
    cv::putText(img, title, {kLeftPad, 20}, cv::FONT_HERSHEY_SIMPLEX, 0.45, kBlack, 1, cv::LINE_AA);
    occupancy_ticks(img, kLeftPad, kTop, kCells, kCell);
    cv::putText(img, "x: centre, y: left occupancy", {kLeftPad + 40, kTop + kCells * kCell + 36},
                cv::FONT_HERSHEY_SIMPLEX, 0.45, kBlack, 1, cv::LINE_AA);
    return img;
}

void write_figures(const fs::path& out) {
    const FisParams p;
    // Drawn first, written together (all or nothing), then listed.
    std::vector<std::pair<fs::path, cv::Mat>> figures;
    const auto save = [&figures](const fs::path& path, const cv::Mat& img) {
        figures.emplace_back(path, img);
    };
    save(
        out / "mf_input.png",
        line_plot("input MF (every window): fraction of pixels nearer than Z_safe", 0, 1, 0.1,
                  {{"free", mf(p.free), {200, 80, 0}}, {"occupied", mf(p.occupied), {0, 0, 200}}}));
    save(out / "mf_angle.png",
         line_plot("output MF: direction angle (deg), negative = left", -30, 30, 10,
                   {{"left", mf(p.left), {200, 80, 0}},
                    {"forward", mf(p.forward), {0, 150, 0}},
                    {"right", mf(p.right), {0, 0, 200}}}));
    save(out / "mf_backwards.png",
         line_plot("output MF: move backwards (red line: 0.65 threshold)", 0, 1, 0.1,
                   {{"yes", mf(p.backwards_yes), {0, 0, 200}}}, p.backwards_threshold));
    cv::Mat surfaces;
    cv::hconcat(surface(0.0, p), surface(1.0, p), surfaces);
    save(out / "control_surface.png", surfaces);
    // Decisions before and after the default rule, right window free / half / full; legend:
    // green forward, blue left, red right, black backwards, orange line: the rate.
    std::vector<cv::Mat> rows;
    for (const bool before : {true, false}) {
        cv::Mat row;
        cv::hconcat(std::vector<cv::Mat>{decision_map(0.0, p, before), decision_map(0.5, p, before),
                                         decision_map(1.0, p, before)},
                    row);
        rows.push_back(row);
    }
    cv::Mat decisions;
    cv::vconcat(rows, decisions);
    save(out / "decision_surface.png", decisions);
    io::write_pngs(figures);
    for (const auto& [path, img] : figures) {
        std::cout << path.string() << '\n';
    }
}

}  // namespace

void add_avoid_figures_command(CLI::App& app) {
    const auto [command, folder] = cli::add_command<std::string>(
        app, "avoid-figures", "Draw the fuzzy-system figures of docs/avoidance.md into a folder.",
        write_figures);
    command->add_option("OUTPUT_FOLDER", *folder, "Existing folder for the PNGs")->required();
}

}  // namespace stereo::experiments
