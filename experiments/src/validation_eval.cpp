// `stereo_experiments validation-eval`: the tables and the error-versus-coverage figure of
// docs/results.md "Validated output". On every scene with ground truth (the four Middlebury 2003
// pairs, Reindeer, Cloth3, Wood2, Aloe at half size) it runs the pipeline without stage 6, with
// each validation step alone, with every step (the defaults of `stereo match --validate`), and
// OpenCV StereoBM and StereoSGBM in the same run; then it sweeps the uniqueness ratio (with the
// left-right check on) for the curve, and the speckle filter's size and range over that sweep
// (the rule that chose the defaults). Scores are over every pixel with known ground truth.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "cli_command.hpp"
#include "cli_matcher_options.hpp"
#include "experiments.hpp"
#include "stereo/asw.hpp"
#include "stereo/defaults.hpp"
#include "stereo/speckle.hpp"
#include "stereo/stages.hpp"
#include "stereo_io/data_dir.hpp"
#include "stereo_io/disparity_files.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/middlebury.hpp"
#include "stereo_io/output.hpp"
#include "stereo_io/versioned_json.hpp"

namespace stereo::experiments {
namespace {
namespace fs = std::filesystem;
using json = nlohmann::json;

struct EvalOptions : cli::ReportOptions {
    static constexpr std::string_view kName = "validation-eval";
    static constexpr std::string_view kDescription =
        "Coverage and error of the validated output on every scene with ground truth, beside "
        "OpenCV BM and SGBM, and the uniqueness sweep (docs/results.md).";
    std::string figure;  // the error-versus-coverage PNG
    // The defaults row: stereo match's for the cost unless given (-1; stereo/defaults.hpp).
    int uniqueness = -1;
    int lr_tolerance = -1;
    std::vector<int> sweep = {0, 1, 2, 3, 4, 5, 6, 8, 10, 12, 15, 20, 30, 45, 70, 100};
    speckle::Params speckle = speckle::Params::defaults();
    std::vector<int> speckle_sizes = {0, 25, 50, 100, 200, 400};
    std::vector<int> speckle_ranges = {1, 2};
    std::string cost{defaults::kCost};       // the pipeline's cost plug-in (stereo::cost_names())
    std::string method = "pipeline";         // or "asw" (stage 6 on the ASW volume)
    bool separable = false;                  // asw: the separable variant
    int asw_window = asw::kDefaultDiameter;  // asw: the diameter w (the hardware sweep)
};

// The error goal of issue 16: bad > 1 among the output at most this times SGBM's, every scene.
constexpr double kErrorGoalRatio = 1.2;

struct Score {
    double coverage = 0.0;   // percent of known pixels that are valid
    double bad_valid = 0.0;  // bad > 1 among the valid ones, percent
    double bad_all = 0.0;    // bad > 1 with invalid counted bad, percent
    double bad_half = 0.0;   // bad > 0.5 among the valid ones, percent
    double nmse = 0.0;
};

// `disparity`: CV_32FC1 with NaN where invalid.
Score score(const io::SceneData& data, const cv::Mat& disparity) {
    io::EvalInput input{.disparity = {disparity, "disparity"},
                        .ground_truth = data.ground_truth,
                        .threshold = 1.0,
                        .zero_is_invalid = false};
    const io::EvalResult one = io::evaluate(input);
    input.threshold = 0.5;
    const io::EvalResult half = io::evaluate(input);
    return {100.0 * one.coverage.value_or(0.0), one.valid.percent().value_or(0.0),
            one.all.percent().value_or(0.0), half.valid.percent().value_or(0.0),
            one.nmse.value_or(0.0)};
}

// OpenCV's 0 = invalid maps into NaN = invalid.
cv::Mat opencv_map(cv::Mat map) {
    map.setTo(std::numeric_limits<float>::quiet_NaN(), map <= 0.0F);
    return map;
}

ValidatedDisparity run_model(const io::SceneData& data, const ValidationParams& validation,
                             const EvalOptions& options) {
    MatchConfig config;
    config.pipeline.ndisp = data.scene.ndisp;
    config.pipeline.cost = options.cost;
    config.pipeline.validation = validation;
    config.asw.separable = options.separable;
    config.asw.diameter = options.asw_window;
    const auto matcher = cli::matchers().create(options.method, "model", config);
    return matcher->compute(data.pair.left, data.pair.right).validated;
}

// The score of `validated` after the speckle filter (off: as it is).
Score score_filtered(const io::SceneData& data, ValidatedDisparity validated,
                     const speckle::Params& speckles) {
    speckle::filter(validated, speckles);
    return score(data, io::to_float_disparity(validated));
}

json score_json(const Score& s) {
    return {{"coverage", s.coverage},
            {"bad_valid", s.bad_valid},
            {"bad_all", s.bad_all},
            {"bad_half_valid", s.bad_half},
            {"nmse", s.nmse}};
}

// One panel per scene: bad > 1 among valid pixels (y) against coverage (x), our sweep as a
// polyline with its points, SGBM as a red square, BM as a blue one.
cv::Mat curve_figure(const json& report) {
    const auto& scenes = report["scenes"];
    const int columns = 4;
    const int rows = static_cast<int>((scenes.size() + columns - 1) / columns);
    const int panel_w = 300;
    const int panel_h = 240;
    cv::Mat figure(std::max(rows, 1) * panel_h + 24, columns * panel_w, CV_8UC3,
                   cv::Scalar::all(255));
    const cv::Scalar black(0, 0, 0);
    const cv::Scalar grey(200, 200, 200);
    for (std::size_t i = 0; i < scenes.size(); ++i) {
        const json& scene = scenes[i];
        const int ox = static_cast<int>(i % columns) * panel_w;
        const int oy = static_cast<int>(i / columns) * panel_h;
        const cv::Rect plot(ox + 45, oy + 25, panel_w - 60, panel_h - 65);
        double y_max = 5.0;
        for (const auto& point : scene["sweep"]) {
            y_max = std::max(y_max, point["bad_valid"].get<double>());
        }
        for (const char* method : {"sgbm", "bm", "plain"}) {
            y_max = std::max(y_max, scene[method]["bad_valid"].get<double>());
        }
        y_max = std::ceil(y_max / 5.0) * 5.0;
        const auto at = [&](double coverage, double bad) {
            return cv::Point(plot.x + static_cast<int>(coverage / 100.0 * plot.width),
                             plot.y + plot.height - static_cast<int>(bad / y_max * plot.height));
        };
        for (int tick = 0; tick <= 4; ++tick) {
            const double bad = y_max * tick / 4.0;
            cv::line(figure, at(0, bad), at(100, bad), grey, 1);
            cv::putText(figure, std::to_string(static_cast<int>(bad)),
                        at(0, bad) + cv::Point(-30, 4), cv::FONT_HERSHEY_SIMPLEX, 0.35, black, 1,
                        cv::LINE_AA);
            const double coverage = 25.0 * tick;
            cv::putText(figure, std::to_string(static_cast<int>(coverage)),
                        at(coverage, 0) + cv::Point(-8, 14), cv::FONT_HERSHEY_SIMPLEX, 0.35, black,
                        1, cv::LINE_AA);
        }
        cv::rectangle(figure, plot, black, 1);
        cv::putText(figure, scene["name"].get<std::string>(), cv::Point(ox + 45, oy + 18),
                    cv::FONT_HERSHEY_SIMPLEX, 0.5, black, 1, cv::LINE_AA);
        cv::putText(figure, "coverage %", cv::Point(ox + panel_w / 2 - 30, oy + panel_h - 12),
                    cv::FONT_HERSHEY_SIMPLEX, 0.35, black, 1, cv::LINE_AA);
        std::vector<cv::Point> line;
        for (const auto& point : scene["sweep"]) {
            line.push_back(at(point["coverage"], point["bad_valid"]));
        }
        cv::polylines(figure, line, false, cv::Scalar(0, 140, 0), 1, cv::LINE_AA);
        for (const auto& p : line) {
            cv::circle(figure, p, 2, cv::Scalar(0, 140, 0), cv::FILLED, cv::LINE_AA);
        }
        const auto mark = [&](const json& s, const cv::Scalar& colour) {
            const cv::Point p = at(s["coverage"], s["bad_valid"]);
            cv::rectangle(figure, p - cv::Point(4, 4), p + cv::Point(4, 4), colour, cv::FILLED);
        };
        mark(scene["sgbm"], cv::Scalar(0, 0, 220));
        mark(scene["bm"], cv::Scalar(220, 0, 0));
        const cv::Point plain = at(scene["plain"]["coverage"], scene["plain"]["bad_valid"]);
        cv::drawMarker(figure, plain, black, cv::MARKER_TILTED_CROSS, 9, 1);
        const cv::Point chosen = at(scene["defaults"]["coverage"], scene["defaults"]["bad_valid"]);
        cv::drawMarker(figure, chosen, cv::Scalar(0, 140, 0), cv::MARKER_DIAMOND, 11, 2);
    }
    // Legend, bottom right of the last row.
    const int lx = 10;
    const int ly = figure.rows - 8;
    cv::putText(figure,
                "y: bad>1 % among output pixels. green: uniqueness sweep (left-right on), diamond "
                "= defaults; x: no validation; red: SGBM; blue: BM",
                cv::Point(lx, ly), cv::FONT_HERSHEY_SIMPLEX, 0.38, black, 1, cv::LINE_AA);
    return figure;
}

std::string markdown(const json& report) {
    std::ostringstream md;
    char line[400];
    const json& defaults = report["defaults"];
    if (defaults["method"] == "pipeline") {
        md << "# Validated output: every configuration on every scene\n\nGenerated by "
              "`./build/experiments/stereo_experiments validation-eval --json "
              "docs/figures/validation.json --figure docs/figures/validation_curves.png "
              "--markdown docs/results-validation-tables.md`; read with "
              "[results.md](results.md#validated-output-stage-6-coverage-against-error-beside-"
              "opencv).";
    } else {
        md << "# Validated output of adaptive support weights ("
           << defaults["cost"].get<std::string>()
           << (defaults["separable"].get<bool>() ? ", separable" : ", full circle")
           << "): every configuration on every scene\n\nGenerated by "
              "`./build/experiments/stereo_experiments validation-eval --method asw"
           << (defaults["separable"].get<bool>() ? " --separable" : "")
           << (defaults["asw_window"].get<int>() == asw::kDefaultDiameter
                   ? std::string()
                   : " --asw-window " + std::to_string(defaults["asw_window"].get<int>()))
           << " --sweep 0 --speckle-sizes 100 --speckle-ranges 1 --markdown "
              "docs/results-validation-asw"
           << (defaults["separable"].get<bool>() ? "" : "-full")
           << "-tables.md`; read with "
              "[results-asw.md](results-asw.md#validated-output).";
    }
    md << " Rows: `plain` no stage 6; `uniqueness` (U = "
       << report["defaults"]["uniqueness"].get<int>()
       << "), `left_right` (T = " << report["defaults"]["lr_tolerance"].get<int>()
       << "), `subpixel`, `speckle` (size " << report["defaults"]["speckle_size"].get<int>()
       << ", range " << report["defaults"]["speckle_range"].get<int>()
       << ") alone; `defaults_integer` all but sub-pixel; `defaults` all four; OpenCV `bm` and "
          "`sgbm`.\n\n";
    md << "| scene | method | coverage % | bad>1 % of output | bad>1 % all (invalid = bad) | "
          "bad>0.5 % of output | NMSE |\n|---|---|---|---|---|---|---|\n";
    for (const auto& scene : report["scenes"]) {
        for (const char* method : {"plain", "uniqueness", "left_right", "subpixel", "speckle",
                                   "defaults_integer", "defaults", "bm", "sgbm"}) {
            const json& s = scene[method];
            std::snprintf(line, sizeof line, "| %s | %s | %.1f | %.2f | %.2f | %.2f | %.4f |\n",
                          scene["name"].get<std::string>().c_str(), method,
                          s["coverage"].get<double>(), s["bad_valid"].get<double>(),
                          s["bad_all"].get<double>(), s["bad_half_valid"].get<double>(),
                          s["nmse"].get<double>());
            md << line;
        }
    }
    md << "\n| scene | defaults: coverage % / bad>1 % of output | SGBM: coverage % / bad>1 % "
          "| ratio to SGBM | sub-pixel lowers bad>0.5 / NMSE (defaults vs defaults_integer) |\n"
          "|---|---|---|---|---|\n";
    for (const auto& scene : report["scenes"]) {
        const json& ours = scene["defaults"];
        const json& sgbm = scene["sgbm"];
        // Sub-pixel against the same validated output without it: gross errors are gone there,
        // so bad > 0.5 and NMSE measure the refinement, not the outliers.
        const json& plain = scene["defaults_integer"];
        const json& subpixel = scene["defaults"];
        const auto yes_no = [&](const char* key) {
            return subpixel[key].get<double>() < plain[key].get<double>() ? "yes" : "no";
        };
        std::snprintf(line, sizeof line, "| %s | %.1f / %.2f | %.1f / %.2f | %.2fx | %s / %s |\n",
                      scene["name"].get<std::string>().c_str(), ours["coverage"].get<double>(),
                      ours["bad_valid"].get<double>(), sgbm["coverage"].get<double>(),
                      sgbm["bad_valid"].get<double>(),
                      ours["bad_valid"].get<double>() / sgbm["bad_valid"].get<double>(),
                      yes_no("bad_half_valid"), yes_no("nmse"));
        md << line;
    }
    md << "\nThe speckle filter, applied to every point of the sweep below: for each size and "
          "range, the smallest uniqueness ratio U whose error among the output is at most "
       << kErrorGoalRatio
       << "x SGBM's on every scene, with the mean and lowest coverage and the worst ratio there "
          "(`-`: no ratio of the sweep meets it).\n\n| speckle size | range | U | mean coverage % "
          "| lowest coverage % | worst ratio to SGBM |\n|---|---|---|---|---|---|\n";
    for (const auto& setting : report["speckle_grid"]) {
        md << "| " << setting["size"].get<int>() << " | " << setting["range"].get<int>() << " |";
        if (setting["ratio"].is_null()) {
            md << " - | - | - | - |\n";
            continue;
        }
        std::snprintf(line, sizeof line, " %d | %.1f | %.1f | %.2fx |\n",
                      setting["ratio"].get<int>(), setting["mean_coverage"].get<double>(),
                      setting["lowest_coverage"].get<double>(),
                      setting["worst_ratio"].get<double>());
        md << line;
    }
    md << "\nUniqueness sweep (left-right on, the defaults' speckle filter), coverage % / bad>1 % "
          "of output:\n\n| scene |";
    for (const int ratio : report["sweep_ratios"]) {
        md << " U=" << ratio << " |";
    }
    md << "\n|---|";
    for (std::size_t i = 0; i < report["sweep_ratios"].size(); ++i) {
        md << "---|";
    }
    md << '\n';
    for (const auto& scene : report["scenes"]) {
        md << "| " << scene["name"].get<std::string>() << " |";
        for (const auto& point : scene["sweep"]) {
            std::snprintf(line, sizeof line, " %.1f / %.2f |", point["coverage"].get<double>(),
                          point["bad_valid"].get<double>());
            md << line;
        }
        md << '\n';
    }
    return md.str();
}

// For one speckle setting: the smallest ratio of the sweep that meets the error goal on every
// scene, with the coverage there; null ratio when none does.
json choose_ratio(const json& scenes, std::size_t setting, const std::vector<int>& ratios) {
    for (std::size_t r = 0; r < ratios.size(); ++r) {
        double worst = 0.0;
        double sum = 0.0;
        double lowest = 100.0;
        for (const auto& scene : scenes) {
            const json& point = scene["speckle_grid"][setting][r];
            const double sgbm = scene["sgbm"]["bad_valid"].get<double>();
            worst = std::max(worst, point["bad_valid"].get<double>() / sgbm);
            sum += point["coverage"].get<double>();
            lowest = std::min(lowest, point["coverage"].get<double>());
        }
        if (worst <= kErrorGoalRatio) {
            return {{"ratio", ratios[r]},
                    {"mean_coverage", sum / static_cast<double>(scenes.size())},
                    {"lowest_coverage", lowest},
                    {"worst_ratio", worst}};
        }
    }
    return {{"ratio", nullptr}};
}

void run_validation_eval(const EvalOptions& given) {
    EvalOptions options = given;
    const defaults::Validation cost_defaults = defaults::validation_for(options.cost);
    options.uniqueness = options.uniqueness >= 0 ? options.uniqueness : cost_defaults.uniqueness;
    options.lr_tolerance =
        options.lr_tolerance >= 0 ? options.lr_tolerance : cost_defaults.lr_tolerance;
    const ValidationParams defaults{true, options.uniqueness, true, options.lr_tolerance, true};
    speckle::validate(options.speckle);
    std::vector<speckle::Params> grid;
    for (const int size : options.speckle_sizes) {
        for (const int range : options.speckle_ranges) {
            grid.push_back({size, range});
            speckle::validate(grid.back());
        }
    }
    // The single-step rows use the same ratio and tolerance.
    {
        MatchParams check;
        check.validation = defaults;
        validate_params(check);
        for (const int ratio : options.sweep) {
            check.validation.uniqueness_ratio = ratio;
            validate_params(check);
        }
    }
    check_report_outputs({options.markdown, options.json_path, options.figure}, {},
                         options.data_dir);
    const std::vector<io::SceneData> scenes = load_ground_truth_scenes(options.data_dir);
    if (scenes.empty()) {
        throw std::runtime_error("no scene with ground truth under '" + options.data_dir + "'");
    }
    json report = {{"sweep_ratios", options.sweep},
                   {"defaults",
                    {{"cost", options.cost},
                     {"method", options.method},
                     {"separable", options.separable},
                     {"asw_window", options.asw_window},
                     {"uniqueness", options.uniqueness},
                     {"lr_tolerance", options.lr_tolerance},
                     {"subpixel", true},
                     {"speckle_size", options.speckle.max_size},
                     {"speckle_range", options.speckle.range}}},
                   {"scenes", json::array()}};
    for (const io::SceneData& data : scenes) {
        std::cerr << "validation-eval: " << data.scene.name << '\n';
        json scene = {{"name", data.scene.name}, {"ndisp", data.scene.ndisp}};
        const auto run = [&](const ValidationParams& v, const speckle::Params& speckles) {
            return score_json(score_filtered(data, run_model(data, v, options), speckles));
        };
        const auto run_unfiltered = [&](const ValidationParams& v) { return run(v, {}); };
        scene["plain"] = run_unfiltered({});
        scene["uniqueness"] =
            run_unfiltered({true, options.uniqueness, false, options.lr_tolerance, false});
        scene["left_right"] =
            run_unfiltered({false, options.uniqueness, true, options.lr_tolerance, false});
        scene["subpixel"] =
            run_unfiltered({false, options.uniqueness, false, options.lr_tolerance, true});
        scene["speckle"] = run({}, options.speckle);
        scene["defaults"] = run(defaults, options.speckle);
        ValidationParams integer = defaults;
        integer.subpixel = false;
        scene["defaults_integer"] = run(integer, options.speckle);
        scene["bm"] = score_json(score(data, opencv_map(io::run_stereo_bm(data, 11))));
        scene["sgbm"] = score_json(score(data, opencv_map(io::run_stereo_sgbm(data))));
        json sweep = json::array();
        json speckle_grid(grid.size(), json::array());
        for (const int ratio : options.sweep) {
            const ValidatedDisparity validated =
                run_model(data, {true, ratio, true, options.lr_tolerance, true}, options);
            json point = score_json(score_filtered(data, validated, options.speckle));
            point["ratio"] = ratio;
            sweep.push_back(point);
            for (std::size_t g = 0; g < grid.size(); ++g) {
                speckle_grid[g].push_back(score_json(score_filtered(data, validated, grid[g])));
            }
        }
        scene["sweep"] = sweep;
        scene["speckle_grid"] = speckle_grid;
        report["scenes"].push_back(scene);
    }
    report["speckle_grid"] = json::array();
    for (std::size_t g = 0; g < grid.size(); ++g) {
        json setting = choose_ratio(report["scenes"], g, options.sweep);
        setting["size"] = grid[g].max_size;
        setting["range"] = grid[g].range;
        report["speckle_grid"].push_back(setting);
    }
    const std::string md = markdown(report);
    OutputFiles files;
    add_report_files(files, options.markdown, md, options.json_path, report);
    if (!options.figure.empty()) {
        files.emplace_back(options.figure, io::encode_png(curve_figure(report), options.figure));
    }
    io::write_files_atomic(files);
    std::cout << md;  // after the files: no report on stdout for a run that then fails
}

}  // namespace

void add_validation_eval_command(CLI::App& app) {
    const auto [command, options] = cli::add_report_command<EvalOptions>(app, run_validation_eval);
    command->add_option("--figure", options->figure, "Write the error-versus-coverage PNG");
    cli::add_number_options(*command,
                            {{"--uniqueness", &options->uniqueness,
                              "Ratio of the defaults row (-1: stereo match's for the cost)"},
                             {"--lr-check", &options->lr_tolerance,
                              "Tolerance of the defaults row and the sweep (-1: stereo match's)"}});
    command->add_option("--sweep", options->sweep, "Uniqueness ratios of the curve")
        ->capture_default_str();
    cli::add_number_options(
        *command,
        {{"--speckle-size", &options->speckle.max_size, "Speckle size of the defaults row"},
         {"--speckle-range", &options->speckle.range, "Speckle range of the defaults row"}});
    command->add_option("--speckle-sizes", options->speckle_sizes, "Speckle sizes of the grid")
        ->capture_default_str();
    command->add_option("--speckle-ranges", options->speckle_ranges, "Speckle ranges of the grid")
        ->capture_default_str();
    // Each a choice among names, its default shown in --help.
    const std::vector<std::string> methods = {"pipeline", "asw"};
    for (const auto& [name, value, help, names] :
         {std::tuple{"--cost", &options->cost, "Cost plug-in of every model row", cost_names()},
          std::tuple{"--method", &options->method,
                     "Matcher of every model row: pipeline, or asw (adaptive support weights, "
                     "default window; stage 6 on its volume)",
                     methods}}) {
        command->add_option(name, *value, help)->check(CLI::IsMember(names))->capture_default_str();
    }
    command->add_flag("--separable", options->separable, "asw: the separable variant");
    command
        ->add_option("--asw-window", options->asw_window,
                     "asw: the support diameter w (odd; docs/results-asw.md, hardware sweep)")
        ->check(CLI::Range(asw::kMinDiameter, asw::kMaxDiameter))
        ->capture_default_str();
}

}  // namespace stereo::experiments
