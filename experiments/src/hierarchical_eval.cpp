// `stereo_experiments hierarchical-eval`: every number and figure of docs/results-hierarchical.md.
// The hierarchical search, the 1-D pipeline and OpenCV StereoSGBM on the Middlebury 2003 pairs,
// original and decalibrated (lens distortion, vertical shift, rotation of the right image), and
// the cost count / run time of the hierarchical search against the full D x V search.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "cli_command.hpp"
#include "cli_matcher_options.hpp"
#include "experiments.hpp"
#include "stereo/hierarchical.hpp"
#include "stereo/pipeline.hpp"
#include "stereo_io/data_dir.hpp"
#include "stereo_io/distortion.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/middlebury.hpp"
#include "stereo_io/output.hpp"
#include "stereo_io/versioned_json.hpp"

namespace stereo::experiments {

namespace {
namespace fs = std::filesystem;
using nlohmann::json;

struct EvalOptions : cli::ReportOptions {
    static constexpr std::string_view kName = "hierarchical-eval";
    static constexpr std::string_view kDescription =
        "Evaluate the hierarchical 2-D search on decalibrated Middlebury pairs "
        "(docs/results-hierarchical.md).";
    std::string figures;
    bool skip_full_search = false;
};

// The thesis' Table 3.4 (NMSE distorted 10 % / original) and Table 3.5 (Tsukuba sweep), quoted.
const std::map<std::string, std::pair<double, double>> kThesisPairs = {
    {"tsukuba", {0.0712, 0.0781}},
    {"venus", {0.0491, 0.0461}},
    {"teddy", {0.1098, 0.0976}},
    {"cones", {0.0500, 0.0519}}};
const std::vector<std::pair<double, double>> kThesisSweep = {
    {0.0, 0.0781},  {2.5, 0.0712},  {5.0, 0.0708}, {7.5, 0.0663},
    {10.0, 0.0712}, {12.5, 0.0723}, {15.0, 0.0761}};
const std::vector<std::string> kMethods = {"hierarchical", "pipeline", "sgbm"};

double milliseconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

hierarchical::Params hierarchical_params(int ndisp) {
    hierarchical::Params params = hierarchical::Params::thesis();
    params.ndisp = (ndisp + 3) / 4 * 4;  // the Middlebury ranges are multiples of 4 already
    return params;
}

struct MethodOutput {
    cv::Mat disparity;  // float, 0 = invalid
    hierarchical::Result hierarchical;
};

MethodOutput run_method(const std::string& method, const io::SceneData& data) {
    if (method == "hierarchical") {
        hierarchical::Result result = hierarchical::match(data.pair.left, data.pair.right,
                                                          hierarchical_params(data.scene.ndisp));
        cv::Mat disparity = io::to_float_disparity(result.disparity);
        return {disparity, std::move(result)};
    }
    if (method == "pipeline") {
        MatchConfig config;
        config.pipeline.ndisp = data.scene.ndisp;
        const MatchResult result = cli::matchers()
                                       .create("pipeline", "model", config)
                                       ->compute(data.pair.left, data.pair.right);
        return {io::to_float_disparity(result.disparity), {}};
    }
    return {io::run_stereo_sgbm(data), {}};
}

json score(const io::EvalResult& result) {
    return {
        {"nmse", result.nmse ? json(*result.nmse) : json(nullptr)},
        {"bad_nonocc", result.nonocc && result.nonocc->percent() ? json(*result.nonocc->percent())
                                                                 : json(nullptr)},
        {"coverage", result.coverage ? json(*result.coverage) : json(nullptr)}};
}

// One case: all three methods on a (warped) scene, scored against the thesis-style GT and, for
// warped scenes, against the exact GT as well.
json run_case(const io::SceneData& original, const io::PairWarp& warp, const std::string& tag,
              cv::Mat* hierarchical_disparity = nullptr, cv::Mat* hierarchical_vertical = nullptr,
              cv::Mat* left_view = nullptr) {
    const io::WarpedScene warped = io::warp_scene(original, warp);
    json row = {{"scene", original.scene.name},
                {"case", tag},
                {"distortion", warp.distortion_percent},
                {"shift_y", warp.right_shift_y},
                {"rotation_deg", warp.right_rotation_deg}};
    for (const auto& method : kMethods) {
        const auto start = std::chrono::steady_clock::now();
        const MethodOutput out = run_method(method, warped.data);
        const double ms = milliseconds_since(start);
        json entry = score(io::evaluate_scene(warped.data, out.disparity));
        io::SceneData exact = warped.data;
        exact.ground_truth = warped.exact_ground_truth;
        entry["exact"] = score(io::evaluate_scene(exact, out.disparity));
        entry["ms"] = ms;
        row[method] = entry;
        if (method == "hierarchical" && hierarchical_disparity != nullptr) {
            *hierarchical_disparity = out.disparity;
            const auto& full = out.hierarchical.levels[hierarchical::kLevels - 1];
            cv::Mat vertical(full.height, full.width, CV_32FC1,
                             cv::Scalar(std::numeric_limits<float>::quiet_NaN()));
            for (std::size_t p = 0; p < full.valid.size(); ++p) {
                if (full.valid[p] != 0) {
                    reinterpret_cast<float*>(vertical.data)[p] = full.vertical[p];
                }
            }
            *hierarchical_vertical = vertical;
            *left_view = warped.data.left_bgr;
        }
    }
    std::cerr << original.scene.name << " " << tag << ": nmse hierarchical "
              << row["hierarchical"]["nmse"] << ", pipeline " << row["pipeline"]["nmse"]
              << ", sgbm " << row["sgbm"]["nmse"] << '\n';
    return row;
}

json count_row(const std::string& name, const Image& left, const Image& right, int ndisp,
               bool run_full_search) {
    const hierarchical::Params params = hierarchical_params(ndisp);
    auto start = std::chrono::steady_clock::now();
    const hierarchical::Result fast = hierarchical::match(left, right, params);
    const double fast_ms = milliseconds_since(start);
    const double pixels = static_cast<double>(left.width) * left.height;
    const int d = params.ndisp;
    const int v = params.vertical_range();
    json row = {{"scene", name},
                {"width", left.width},
                {"height", left.height},
                {"ndisp", d},
                {"vrange", v},
                {"hierarchical_per_pixel", fast.cost_evaluations.total() / pixels},
                {"hierarchical_levels",
                 {fast.cost_evaluations.level[0], fast.cost_evaluations.level[1],
                  fast.cost_evaluations.level[2]}},
                {"hierarchical_ms", fast_ms},
                {"thesis_formula_per_pixel", (d / 4) * (v / 4) + 9 + 9},
                {"full_per_pixel", static_cast<double>(d) * v}};
    if (run_full_search) {
        start = std::chrono::steady_clock::now();
        const hierarchical::Result full = hierarchical::full_search(left, right, params);
        row["full_ms"] = milliseconds_since(start);
        row["full_per_pixel"] = full.cost_evaluations.total() / pixels;
        row["full_vs_hierarchical_disagreement"] = io::disagreement(full.disparity, fast.disparity);
    }
    std::cerr << name << " D=" << d << ": " << row.dump() << '\n';
    return row;
}

// ---- figures -------------------------------------------------------------------------------

cv::Mat plot_sweep(const json& sweep) {
    const int width = 840;
    const int height = 460;
    const cv::Rect area(80, 30, 520, 360);
    cv::Mat canvas(height, width, CV_8UC3, cv::Scalar(255, 255, 255));
    double max_nmse = 0.0;
    for (const auto& row : sweep) {
        for (const auto& method : kMethods) {
            if (row[method]["nmse"].is_number()) {
                max_nmse = std::max(max_nmse, row[method]["nmse"].get<double>());
            }
        }
    }
    for (const auto& [p, nmse] : kThesisSweep) {
        max_nmse = std::max(max_nmse, nmse);
    }
    max_nmse = std::ceil(max_nmse * 20.0) / 20.0;  // axis to the next 0.05
    auto to_pixel = [&](double distortion, double nmse) {
        return cv::Point(area.x + static_cast<int>(distortion / 15.0 * area.width),
                         area.y + area.height - static_cast<int>(nmse / max_nmse * area.height));
    };
    const auto font = cv::FONT_HERSHEY_SIMPLEX;
    const cv::Scalar black(0, 0, 0);
    const cv::Scalar grey(210, 210, 210);
    for (int i = 0; i <= 6; ++i) {
        const cv::Point bottom = to_pixel(2.5 * i, 0);
        cv::line(canvas, bottom, {bottom.x, area.y}, grey, 1);
        char label[16];
        std::snprintf(label, sizeof label, "%.1f", 2.5 * i);
        cv::putText(canvas, label, {bottom.x - 14, bottom.y + 20}, font, 0.45, black, 1,
                    cv::LINE_AA);
    }
    const int ticks = static_cast<int>(std::lround(max_nmse / 0.05));
    for (int i = 0; i <= ticks; ++i) {
        const cv::Point leftmost = to_pixel(0, 0.05 * i);
        cv::line(canvas, leftmost, {area.x + area.width, leftmost.y}, grey, 1);
        char label[16];
        std::snprintf(label, sizeof label, "%.2f", 0.05 * i);
        cv::putText(canvas, label, {leftmost.x - 45, leftmost.y + 5}, font, 0.45, black, 1,
                    cv::LINE_AA);
    }
    cv::rectangle(canvas, area, black, 1);
    cv::putText(canvas, "radial distortion (%)", {area.x + 180, height - 25}, font, 0.5, black, 1,
                cv::LINE_AA);
    cv::putText(canvas, "NMSE, Tsukuba", {10, 20}, font, 0.5, black, 1, cv::LINE_AA);

    struct Series {
        std::string label;
        cv::Scalar colour;  // BGR
        std::vector<std::pair<double, double>> points;
    };
    std::vector<Series> series = {{"hierarchical (ours)", {200, 80, 0}, {}},
                                  {"1-D pipeline (ours)", {0, 140, 0}, {}},
                                  {"StereoSGBM", {0, 0, 220}, {}},
                                  {"thesis (quoted)", {120, 120, 120}, kThesisSweep}};
    for (const auto& row : sweep) {
        for (std::size_t m = 0; m < kMethods.size(); ++m) {
            if (row[kMethods[m]]["nmse"].is_number()) {
                series[m].points.emplace_back(row["distortion"].get<double>(),
                                              row[kMethods[m]]["nmse"].get<double>());
            }
        }
    }
    for (std::size_t s = 0; s < series.size(); ++s) {
        const auto& line = series[s];
        for (std::size_t i = 0; i < line.points.size(); ++i) {
            const cv::Point point = to_pixel(line.points[i].first, line.points[i].second);
            cv::circle(canvas, point, 4, line.colour, cv::FILLED, cv::LINE_AA);
            if (i > 0) {
                cv::line(canvas, to_pixel(line.points[i - 1].first, line.points[i - 1].second),
                         point, line.colour, 2, cv::LINE_AA);
            }
        }
        const cv::Point key(area.x + area.width + 15, area.y + 20 + 25 * static_cast<int>(s));
        cv::line(canvas, key, {key.x + 25, key.y}, line.colour, 2, cv::LINE_AA);
        cv::putText(canvas, line.label, {key.x + 30, key.y + 5}, font, 0.42, black, 1, cv::LINE_AA);
    }
    return canvas;
}

// Left image, disparity (turbo, 0..ndisp-1) and vertical offset (turbo, -4..+4 px) side by side.
cv::Mat maps_figure(const cv::Mat& left, const cv::Mat& disparity, const cv::Mat& vertical,
                    int ndisp) {
    const cv::Mat disparity_view = io::float_disparity_to_colour(disparity, ndisp);
    cv::Mat vertical_grey(vertical.size(), CV_8UC1, cv::Scalar(0));
    cv::Mat unknown(vertical.size(), CV_8UC1, cv::Scalar(0));
    for (int y = 0; y < vertical.rows; ++y) {
        for (int x = 0; x < vertical.cols; ++x) {
            const float v = vertical.at<float>(y, x);
            if (std::isnan(v)) {
                unknown.at<std::uint8_t>(y, x) = 255;
            } else {
                vertical_grey.at<std::uint8_t>(y, x) =
                    cv::saturate_cast<std::uint8_t>(128 + v * 255.0 / 8.0);
            }
        }
    }
    cv::Mat vertical_view;
    cv::applyColorMap(vertical_grey, vertical_view, cv::COLORMAP_TURBO);
    vertical_view.setTo(cv::Scalar(0, 0, 0), unknown);
    cv::Mat strip;
    cv::hconcat(std::vector<cv::Mat>{left, disparity_view, vertical_view}, strip);
    return strip;
}

// ---- markdown ------------------------------------------------------------------------------

std::string number(const json& value, const char* format = "%.4f") {
    if (!value.is_number()) {
        return "–";
    }
    char text[32];
    std::snprintf(text, sizeof text, format, value.get<double>());
    return text;
}

std::string markdown_report(const json& report) {
    std::ostringstream md;
    md << "### NMSE on the four pairs, original and 10 % lens distortion\n\n"
          "NMSE against the thesis-style ground truth (the original map distorted like the left "
          "image); in brackets against the exact ground truth (every pixel followed through the "
          "warp). bad = bad_nonocc % (> 1 px). Thesis values quoted from its Table 3.4.\n\n"
          "| pair | case | hierarchical NMSE | thesis NMSE (quoted) | hierarchical bad % | "
          "1-D pipeline NMSE | 1-D bad % | SGBM NMSE | SGBM bad % |\n"
          "|---|---|---|---|---|---|---|---|---|\n";
    for (const auto& row : report["pairs"]) {
        const std::string name = row["scene"];
        const bool distorted = row["distortion"].get<double>() > 0;
        const auto thesis = kThesisPairs.at(name);
        auto cell = [&](const std::string& method) {
            return number(row[method]["nmse"]) + " (" + number(row[method]["exact"]["nmse"]) + ")";
        };
        md << "| " << name << " | " << (distorted ? "10 %" : "original") << " | "
           << cell("hierarchical") << " | "
           << number(json(distorted ? thesis.first : thesis.second)) << " | "
           << number(row["hierarchical"]["bad_nonocc"], "%.2f") << " | " << cell("pipeline")
           << " | " << number(row["pipeline"]["bad_nonocc"], "%.2f") << " | " << cell("sgbm")
           << " | " << number(row["sgbm"]["bad_nonocc"], "%.2f") << " |\n";
    }
    md << "\n### Tsukuba, NMSE against lens distortion\n\n"
          "| distortion % | hierarchical | thesis (quoted, Table 3.5) | 1-D pipeline | SGBM | "
          "hierarchical, exact GT | hierarchical bad % | 1-D bad % | SGBM bad % |\n"
          "|---|---|---|---|---|---|---|---|---|\n";
    for (std::size_t i = 0; i < report["sweep"].size(); ++i) {
        const auto& row = report["sweep"][i];
        md << "| " << number(row["distortion"], "%.1f") << " | "
           << number(row["hierarchical"]["nmse"]) << " | " << number(json(kThesisSweep[i].second))
           << " | " << number(row["pipeline"]["nmse"]) << " | " << number(row["sgbm"]["nmse"])
           << " | " << number(row["hierarchical"]["exact"]["nmse"]) << " | "
           << number(row["hierarchical"]["bad_nonocc"], "%.2f") << " | "
           << number(row["pipeline"]["bad_nonocc"], "%.2f") << " | "
           << number(row["sgbm"]["bad_nonocc"], "%.2f") << " |\n";
    }
    md << "\n### Tsukuba, right image shifted vertically or rotated\n\n"
          "Scored against the exact ground truth (the horizontal disparity after the move).\n\n"
          "| case | hierarchical NMSE | hierarchical bad % | 1-D NMSE | 1-D bad % | SGBM NMSE | "
          "SGBM bad % |\n|---|---|---|---|---|---|---|\n";
    for (const auto& row : report["misalignment"]) {
        md << "| " << row["case"].get<std::string>() << " | "
           << number(row["hierarchical"]["exact"]["nmse"]) << " | "
           << number(row["hierarchical"]["exact"]["bad_nonocc"], "%.2f") << " | "
           << number(row["pipeline"]["exact"]["nmse"]) << " | "
           << number(row["pipeline"]["exact"]["bad_nonocc"], "%.2f") << " | "
           << number(row["sgbm"]["exact"]["nmse"]) << " | "
           << number(row["sgbm"]["exact"]["bad_nonocc"], "%.2f") << " |\n";
    }
    md << "\n### Cost evaluations per pixel and run time\n\n"
          "Cost evaluations = DSI cells computed (one AD of a pixel and a candidate), counted in "
          "the model, divided by the full-size pixel count. Run times of the same run, one "
          "thread.\n\n"
          "| pair | D x V | hierarchical per pixel | per-level sum (D/4)(V/4)+9+9 | full D x V "
          "per pixel | ratio (per pixel) | ratio (per-level sum) | hierarchical ms | full "
          "search ms | speed-up |\n|---|---|---|---|---|---|---|---|---|---|\n";
    for (const auto& row : report["counts"]) {
        const double hier = row["hierarchical_per_pixel"];
        const double formula = row["thesis_formula_per_pixel"];
        const double full = row["full_per_pixel"];
        md << "| " << row["scene"].get<std::string>() << " | " << row["ndisp"].get<int>() << " x "
           << row["vrange"].get<int>() << " | " << number(json(hier), "%.2f") << " | "
           << number(json(formula), "%.0f") << " | " << number(json(full), "%.0f") << " | "
           << number(json(full / hier), "%.1f") << " | " << number(json(full / formula), "%.1f")
           << " | " << number(row["hierarchical_ms"], "%.0f") << " | "
           << number(row.value("full_ms", json(nullptr)), "%.0f") << " | "
           << (row.contains("full_ms") ? number(json(row["full_ms"].get<double>() /
                                                     row["hierarchical_ms"].get<double>()),
                                                "%.1f")
                                       : std::string("–"))
           << " |\n";
    }
    return md.str();
}

void run_eval(const EvalOptions& options) {
    check_report_outputs({options.markdown, options.json_path}, {options.figures},
                         options.data_dir);
    std::vector<io::SceneData> scenes;
    for (const auto& scene : io::middlebury2003_scenes()) {
        auto data = io::load_scene(options.data_dir, scene);
        if (!data) {
            throw std::runtime_error("Middlebury 2003 scene \"" + scene.name +
                                     "\" not found under " +
                                     io::scene_dir(options.data_dir, scene).string());
        }
        scenes.push_back(std::move(*data));
    }
    json report = {{"pairs", json::array()},
                   {"sweep", json::array()},
                   {"misalignment", json::array()},
                   {"counts", json::array()}};
    cv::Mat figure_disparity;
    cv::Mat figure_vertical;
    cv::Mat figure_left;
    for (const auto& scene : scenes) {
        report["pairs"].push_back(run_case(scene, {0.0, 0.0, 0.0}, "original"));
        report["pairs"].push_back(run_case(scene, {10.0, 0.0, 0.0}, "distortion 10 %"));
    }
    const io::SceneData& tsukuba = scenes.front();
    for (int step = 0; step <= 6; ++step) {
        const double percent = 2.5 * step;
        if (step == 4) {
            report["sweep"].push_back(run_case(tsukuba, {percent, 0, 0}, "distortion 10 %",
                                               &figure_disparity, &figure_vertical, &figure_left));
        } else {
            report["sweep"].push_back(
                run_case(tsukuba, {percent, 0, 0}, "distortion " + number(json(percent), "%.1f")));
        }
    }
    for (const double shift : {1.0, 2.0, 4.0, 8.0}) {
        report["misalignment"].push_back(
            run_case(tsukuba, {0, shift, 0}, "shift " + number(json(shift), "%.0f") + " px"));
    }
    for (const double degrees : {0.5, 1.0, 2.0}) {
        report["misalignment"].push_back(run_case(
            tsukuba, {0, 0, degrees}, "rotation " + number(json(degrees), "%.1f") + " deg"));
    }
    report["counts"].push_back(
        count_row("tsukuba", tsukuba.pair.left, tsukuba.pair.right, 32, !options.skip_full_search));
    for (const auto& scene : scenes) {
        report["counts"].push_back(count_row(scene.scene.name, scene.pair.left, scene.pair.right,
                                             scene.scene.ndisp, !options.skip_full_search));
    }

    const std::string md = markdown_report(report);
    // Reports and figures together, all or nothing, before the tables are printed.
    OutputFiles files;
    add_report_files(files, options.markdown, md, options.json_path, report);
    if (!options.figures.empty()) {
        const fs::path dir(options.figures);
        const fs::path sweep = dir / "nmse_vs_distortion.png";
        const fs::path maps = dir / "tsukuba_distorted_10_maps.png";
        files.emplace_back(sweep, io::encode_png(plot_sweep(report["sweep"]), sweep));
        files.emplace_back(
            maps,
            io::encode_png(maps_figure(figure_left, figure_disparity, figure_vertical, 16), maps));
    }
    io::write_files_atomic(files);
    std::cout << md;
}

}  // namespace

void add_hierarchical_eval_command(CLI::App& app) {
    const auto [command, options] = cli::add_report_command<EvalOptions>(app, run_eval);
    command->add_option("--figures", options->figures, "Write the figures into this folder");
    command->add_flag("--skip-full-search", options->skip_full_search,
                      "Count the full D x V search without running it (no run time)");
}

}  // namespace stereo::experiments
