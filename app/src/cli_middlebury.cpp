// `stereo middlebury`: the evaluation behind docs/results.md. Runs the model (with and without
// CA), its float reference and OpenCV's StereoBM / StereoSGBM on the Middlebury 2003 pairs,
// prints a Markdown table and optionally writes JSON and figures. (The sigma sweep of
// docs/sigma-sweep.md is `stereo_experiments sigma-sweep`.)
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "cli.hpp"
#include "cli_command.hpp"
#include "cli_matcher_options.hpp"
#include "cli_progress.hpp"
#include "stereo_io/data_dir.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/middlebury.hpp"
#include "stereo_io/output.hpp"
#include "stereo_io/scene_strip.hpp"
#include "stereo_io/versioned_json.hpp"

namespace stereo::cli {
namespace {
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct Options : ReportOptions {
    static constexpr std::string_view kName = "middlebury";
    static constexpr std::string_view kDescription =
        "Evaluate the model and OpenCV baselines on the Middlebury 2003 pairs.";
    std::string figures;
    MatcherOptions matcher;  // --window, --sigma; ndisp comes from each scene
};

// The registry's pipeline on `engine` (model or float) for one scene and CA setting.
std::unique_ptr<Matcher> pipeline(const Options& options, const std::string& engine, int ndisp,
                                  bool use_ca) {
    MatchConfig config = options.matcher.config;
    config.pipeline.ndisp = ndisp;
    config.pipeline.use_ca = use_ca;
    return matchers().create("pipeline", engine, config);
}

// The thesis' own figures (Tables 3.1 and 3.2), quoted, for the table's last rows.
struct ThesisFigures {
    const char* scene;
    double nonocc, all, disc, nmse_no_ca, nmse_ca;
};
constexpr ThesisFigures kThesis[] = {{"tsukuba", 10.3, 12.3, 23.5, 0.0627, 0.0593},
                                     {"venus", 8.86, 10.2, 35.8, 0.0545, 0.0447},
                                     {"teddy", 24.5, 31.5, 35.2, 0.1149, 0.1108},
                                     {"cones", 20.6, 28.8, 31.1, 0.0809, 0.0768}};

std::string percent(const std::optional<io::RegionScore>& score) {
    if (!score || !score->percent()) {
        return "-";
    }
    char text[32];
    std::snprintf(text, sizeof text, "%.2f", *score->percent());
    return text;
}

std::string number(std::optional<double> value, const char* format) {
    if (!value) {
        return "-";
    }
    char text[32];
    std::snprintf(text, sizeof text, format, *value);
    return text;
}

template <typename Function>
auto timed(Function&& function, double& milliseconds) {
    const auto start = Clock::now();
    auto result = function();
    milliseconds = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    return result;
}

// One strip per scene (io::scene_strip), returned as PNG bytes: the run writes every file at
// the end, all or nothing.
std::string figure_png(const io::SceneData& data, const cv::Mat& ours, const fs::path& path) {
    return io::encode_png(io::scene_strip(data, ours, "ours (model, CA)"), path);
}

struct MethodRow {
    std::string method;
    io::EvalResult result;
    double ms;
};

nlohmann::json row_json(const MethodRow& row) {
    nlohmann::json json = row.result;
    json["method"] = row.method;
    json["ms"] = row.ms;
    return json;
}

// The report as it grows scene by scene: the tables, the JSON and the figure files.
struct Report {
    std::ostringstream md;
    std::ostringstream float_md;
    nlohmann::json json = nlohmann::json::array();
    std::vector<std::pair<fs::path, std::string>> files;
};

// One scene: the model with and without CA, OpenCV's StereoBM and SGBM, the float reference's
// disagreement, the thesis' quoted figures, the figure.
void add_scene(Report& report, const Options& options, const io::MiddleburyScene& scene,
               const io::SceneData& data) {
    // Made outside the timed calls, as the bare functions these replace had nothing to make.
    const auto matcher = [&](const std::string& engine, bool use_ca) {
        return pipeline(options, engine, scene.ndisp, use_ca);
    };
    const auto model_with_ca = matcher("model", true);
    const auto model_without_ca = matcher("model", false);
    const auto compute = [&](const Matcher& m) {
        return m.compute(data.pair.left, data.pair.right).disparity;
    };

    std::vector<MethodRow> rows;
    double ms = 0.0;
    const DisparityMap model_ca = timed([&] { return compute(*model_with_ca); }, ms);
    const cv::Mat model_ca_f = io::to_float_disparity(model_ca);
    rows.push_back({"model, CA", io::evaluate_scene(data, model_ca_f), ms});
    const DisparityMap model_no_ca = timed([&] { return compute(*model_without_ca); }, ms);
    rows.push_back(
        {"model, no CA", io::evaluate_scene(data, io::to_float_disparity(model_no_ca)), ms});
    const cv::Mat bm =
        timed([&] { return io::run_stereo_bm(data, options.matcher.config.pipeline.window); }, ms);
    rows.push_back({"OpenCV StereoBM", io::evaluate_scene(data, bm), ms});
    const cv::Mat sgbm = timed([&] { return io::run_stereo_sgbm(data); }, ms);
    rows.push_back({"OpenCV StereoSGBM", io::evaluate_scene(data, sgbm), ms});

    const DisparityMap float_ca = compute(*matcher("float", true));
    const DisparityMap float_no_ca = compute(*matcher("float", false));
    const double differ_ca = io::disagreement(model_ca, float_ca);
    const double differ_no_ca = io::disagreement(model_no_ca, float_no_ca);
    char line[160];
    std::snprintf(line, sizeof line, "| %s | %.2f %% | %.2f %% |\n", scene.name.c_str(),
                  100.0 * differ_ca, 100.0 * differ_no_ca);
    report.float_md << line;

    nlohmann::json scene_json = {{"pair", scene.name},
                                 {"ndisp", scene.ndisp},
                                 {"float_disagreement_ca", differ_ca},
                                 {"float_disagreement_no_ca", differ_no_ca},
                                 {"methods", nlohmann::json::array()}};
    for (const MethodRow& row : rows) {
        report.md << "| " << scene.name << " | " << row.method << " | "
                  << percent(row.result.nonocc) << " | " << percent(row.result.all) << " | "
                  << percent(row.result.disc) << " | " << number(row.result.nmse, "%.4f") << " | "
                  << number(row.result.coverage, "%.3f") << " | " << number(row.ms, "%.0f")
                  << " |\n";
        scene_json["methods"].push_back(row_json(row));
    }
    for (const ThesisFigures& thesis : kThesis) {
        if (scene.name == thesis.scene) {
            std::snprintf(line, sizeof line,
                          "| %s | thesis (quoted) | %.2f | %.2f | %.2f | %.4f (no CA %.4f) | - "
                          "| - |\n",
                          scene.name.c_str(), thesis.nonocc, thesis.all, thesis.disc,
                          thesis.nmse_ca, thesis.nmse_no_ca);
            report.md << line;
        }
    }
    report.json.push_back(scene_json);
    if (!options.figures.empty()) {
        const fs::path figure = fs::path(options.figures) / (scene.name + ".png");
        report.files.emplace_back(figure, figure_png(data, model_ca_f, figure));
    }
}

// The report files are checked before minutes of matching, not after; none of them, nor a
// figure, may be another or replace a file of the scenes or lie among them (an argument error:
// checked before the data folder is read).
void check_report_outputs(const Options& options) {
    std::vector<fs::path> outputs = {options.markdown, options.json_path};
    if (!options.figures.empty()) {
        for (const auto& scene : io::middlebury2003_scenes()) {
            outputs.push_back(fs::path(options.figures) / (scene.name + ".png"));
        }
    }
    io::check_outputs(outputs, {.folders = {fs::path(options.data_dir) / "middlebury2003"}});
}

void run_report(const Options& options) {
    const fs::path data_dir = options.data_dir;
    for (const std::string& report_file : {options.markdown, options.json_path}) {
        if (!report_file.empty()) {
            io::check_writable_location(report_file);
        }
    }
    if (!options.figures.empty()) {
        // Created at the end, with the figures in it; its parent must exist now.
        io::check_output_folder(options.figures);
    }
    // Every output file (figures, Markdown, JSON), written together at the end: all or nothing.
    Report report;
    report.md
        << "| pair | method | bad nonocc % | bad all % | bad disc % | NMSE | coverage | ms |\n"
        << "|---|---|---|---|---|---|---|---|\n";
    report.float_md
        << "| pair | pixels differing, CA on | pixels differing, CA off |\n|---|---|---|\n";
    int scenes_found = 0;
    const auto& scenes = io::middlebury2003_scenes();
    const ProgressBar progress("middlebury", static_cast<int>(scenes.size()));
    int scenes_done = 0;
    std::string skipped;  // printed once the run succeeded: a failure is one line
    for (const auto& scene : scenes) {
        progress.update(scenes_done++, scene.name);
        const auto data = io::load_scene(data_dir, scene);
        if (!data) {
            skipped += "stereo middlebury: " + scene.name + " not found under " +
                       io::scene_dir(data_dir, scene).string() + ", skipped\n";
            continue;
        }
        ++scenes_found;
        add_scene(report, options, scene, *data);
    }
    if (scenes_found == 0) {
        throw std::runtime_error("no Middlebury 2003 scene found under " +
                                 (data_dir / "middlebury2003").string());
    }
    const std::string text =
        report.md.str() + "\nFixed point against the float reference:\n\n" + report.float_md.str();
    if (!options.markdown.empty()) {
        report.files.emplace_back(options.markdown, text);
    }
    if (!options.json_path.empty()) {
        report.files.emplace_back(options.json_path,
                                  io::versioned({{"scenes", report.json}}).dump(2) + '\n');
    }
    if (!options.figures.empty()) {
        fs::create_directories(options.figures);
    }
    io::write_files_atomic(report.files);
    std::cout << text;  // after the files: no report on stdout for a run that then fails
    std::cerr << skipped;
}

void run_middlebury(const Options& options) {
    // Parameters first (exit 2), then files (exit 1), whatever is wrong with both.
    (void)pipeline(options, "model", fx::kDefaultDisparities, true);
    check_report_outputs(options);
    const fs::path folder = fs::path(options.data_dir) / "middlebury2003";
    if (!fs::is_directory(folder)) {
        throw std::runtime_error("cannot read '" + folder.string() + "': no such folder");
    }
    run_report(options);
}

}  // namespace

void add_middlebury_command(CLI::App& app) {
    const auto [command, options] = add_report_command<Options>(app, run_middlebury);
    command->add_option("--figures", options->figures, "Write one figure strip per pair here");
    // The scenes set ndisp, and the report runs both CA settings: only --window and --sigma.
    add_matcher_options(*command, options->matcher, MatcherChoice::fixed,
                        {.ndisp = false, .no_ca = false});
}

}  // namespace stereo::cli
