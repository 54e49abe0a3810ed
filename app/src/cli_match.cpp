// `stereo match LEFT RIGHT -o DISP.png [options]`: run one engine on a rectified pair.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cli.hpp"
#include "stereo/edge_frontend.hpp"
#include "stereo/hierarchical.hpp"
#include "stereo/hierarchical_reference.hpp"
#include "stereo/hls/match.hpp"
#include "stereo/pipeline.hpp"
#include "stereo/reference.hpp"
#include "stereo_io/io.hpp"

namespace stereo::cli {

namespace {

struct MatchOptions {
    std::string left;
    std::string right;
    std::string output;
    std::string colour;  // empty: no colour view
    MatchParams params;
    bool no_ca = false;
    int scale = 1;
    int downscale = 1;
    std::string engine = "model";
    bool json = false;
    std::string frontend = "model";  // or "edges": the Sec. 4.1.1 variant
    // --method hierarchical: the Sec. 3.3 2-D search (docs/hierarchical.md)
    std::string method = "pipeline";
    int vrange = 0;             // 0 = ndisp
    std::string vertical;       // vertical offset PNG, empty: none
    std::string dump_levels;    // folder for the per-level maps, empty: none
    bool window_given = false;  // --window / --sigma do not apply to the hierarchical levels
};

double valid_fraction(const DisparityMap& map);

// The vertical offset map as a PNG byte: 128 + v where valid, 0 where invalid.
cv::Mat vertical_to_mat(const std::vector<std::int16_t>& vertical,
                        const std::vector<std::uint8_t>& valid, int width, int height) {
    cv::Mat out(height, width, CV_8UC1, cv::Scalar(0));
    for (std::size_t p = 0; p < valid.size(); ++p) {
        if (valid[p] != 0) {
            out.data[p] = static_cast<std::uint8_t>(128 + vertical[p]);
        }
    }
    return out;
}

void run_hierarchical(const MatchOptions& options, bool use_ca) {
    if (options.engine != "model" && options.engine != "naive") {
        throw std::invalid_argument("--method hierarchical runs with --engine model or naive");
    }
    if (options.frontend != "model") {
        throw std::invalid_argument("--method hierarchical runs only with --frontend model");
    }
    if (options.window_given) {
        throw std::invalid_argument(
            "--window and --sigma apply to --method pipeline; the hierarchical levels use "
            "9, 15 and 23 (docs/hierarchical.md)");
    }
    if (options.scale < 1) {
        throw std::invalid_argument("--scale must be >= 1, got " + std::to_string(options.scale));
    }
    if (options.downscale < 1) {
        throw std::invalid_argument("--downscale must be >= 1, got " +
                                    std::to_string(options.downscale));
    }
    hierarchical::Params params;
    params.ndisp = options.params.ndisp;
    params.vrange = options.vrange;
    params.use_ca = use_ca;
    io::check_disparity_scale(params.ndisp, options.scale);
    io::check_writable_location(options.output);
    if (!options.colour.empty()) {
        io::check_writable_location(options.colour);
    }
    if (!options.vertical.empty()) {
        io::check_writable_location(options.vertical);
    }
    const std::filesystem::path dump(options.dump_levels);
    if (!options.dump_levels.empty()) {
        std::error_code error;
        const std::filesystem::path parent =
            dump.parent_path().empty() ? std::filesystem::path(".") : dump.parent_path();
        if (std::filesystem::exists(dump, error) ? !std::filesystem::is_directory(dump, error)
                                                 : !std::filesystem::is_directory(parent, error)) {
            throw std::runtime_error("cannot write level maps into \"" + options.dump_levels +
                                     "\": not a folder, and its parent folder does not exist");
        }
    }
    const io::ImagePair pair = io::load_pair(options.left, options.right, options.downscale);
    hierarchical::validate(params, pair.left.width, pair.left.height);

    const auto start = std::chrono::steady_clock::now();
    const hierarchical::Result result =
        options.engine == "naive" ? hierarchical::naive::match(pair.left, pair.right, params)
                                  : hierarchical::match(pair.left, pair.right, params);
    const std::chrono::duration<double, std::milli> elapsed =
        std::chrono::steady_clock::now() - start;

    // Every output is encoded before the first one is written.
    const DisparityMap& map = result.disparity;
    const cv::Mat stored = io::disparity_to_mat(map, params.ndisp, options.scale);
    const cv::Mat colour =
        options.colour.empty() ? cv::Mat() : io::disparity_to_colour(map, params.ndisp);
    const hierarchical::LevelMap& full = result.levels[hierarchical::kLevels - 1];
    const cv::Mat vertical = vertical_to_mat(full.vertical, full.valid, map.width, map.height);
    std::vector<std::pair<std::string, cv::Mat>> level_files;
    if (!options.dump_levels.empty()) {
        constexpr std::array<const char*, hierarchical::kLevels> kNames = {"quarter", "half",
                                                                           "full"};
        for (int l = 0; l < hierarchical::kLevels; ++l) {
            const auto& level = result.levels[static_cast<std::size_t>(l)];
            const int ndisp =
                params.ndisp / hierarchical::kLevelFactor[static_cast<std::size_t>(l)];
            DisparityMap level_map(level.width, level.height);
            for (std::size_t p = 0; p < level.valid.size(); ++p) {
                level_map.valid[p] = level.valid[p];
                level_map.disparity[p] =
                    level.valid[p] != 0 ? static_cast<std::uint8_t>(level.disparity[p]) : 0;
            }
            const std::string name = kNames[static_cast<std::size_t>(l)];
            level_files.emplace_back(name + "_disparity.png",
                                     io::disparity_to_mat(level_map, ndisp, options.scale));
            level_files.emplace_back(name + "_color.png",
                                     io::disparity_to_colour(level_map, ndisp));
            level_files.emplace_back(
                name + "_vertical.png",
                vertical_to_mat(level.vertical, level.valid, level.width, level.height));
        }
    }
    io::write_png(options.output, stored);
    if (!colour.empty()) {
        io::write_png(options.colour, colour);
    }
    if (!options.vertical.empty()) {
        io::write_png(options.vertical, vertical);
    }
    if (!level_files.empty()) {
        std::filesystem::create_directories(dump);
        for (const auto& [name, mat] : level_files) {
            io::write_png(dump / name, mat);
        }
    }

    const double valid = valid_fraction(map);
    const auto& count = result.cost_evaluations.level;
    const double per_pixel =
        static_cast<double>(result.cost_evaluations.total()) / (map.width * map.height);
    if (options.json) {
        const nlohmann::json summary = {
            {"width", map.width},
            {"height", map.height},
            {"method", "hierarchical"},
            {"ndisp", params.ndisp},
            {"vrange", params.vertical_range()},
            {"windows",
             {params.levels[0].window, params.levels[1].window, params.levels[2].window}},
            {"ca", params.use_ca},
            {"engine", options.engine},
            {"valid_fraction", valid},
            {"cost_evaluations", {{"quarter", count[0]}, {"half", count[1]}, {"full", count[2]}}},
            {"cost_evaluations_per_pixel", per_pixel},
            {"ms", elapsed.count()},
        };
        std::cout << summary.dump() << '\n';
    } else {
        std::printf(
            "%dx%d ndisp %d vrange %d windows %d/%d/%d ca %s method hierarchical engine %s: "
            "%.1f%% valid, %.1f ms, %.2f cost evaluations per pixel\n",
            map.width, map.height, params.ndisp, params.vertical_range(), params.levels[0].window,
            params.levels[1].window, params.levels[2].window, params.use_ca ? "on" : "off",
            options.engine.c_str(), 100.0 * valid, elapsed.count(), per_pixel);
    }
}

DisparityMap run_engine(const std::string& engine, const io::ImagePair& pair,
                        const MatchParams& params) {
    if (engine == "naive") {
        return naive::match(pair.left, pair.right, params);
    }
    if (engine == "float") {
        return floating::match(pair.left, pair.right, params);
    }
    if (engine == "hls") {  // the HLS kernels in C simulation, bit-exact with the model
        return hls::match(pair.left, pair.right, params);
    }
    return match(pair.left, pair.right, params);
}

double valid_fraction(const DisparityMap& map) {
    std::size_t valid = 0;
    for (const auto flag : map.valid) {
        valid += flag != 0 ? 1 : 0;
    }
    return map.valid.empty() ? 0.0 : static_cast<double>(valid) / map.valid.size();
}

void run_match(const MatchOptions& options) {
    if (options.method == "hierarchical") {
        run_hierarchical(options, !options.no_ca);
        return;
    }
    if (options.vrange != 0 || !options.vertical.empty() || !options.dump_levels.empty()) {
        throw std::invalid_argument(
            "--vrange, --vertical and --dump-levels need --method hierarchical");
    }
    MatchParams params = options.params;
    params.use_ca = !options.no_ca;
    if (options.frontend == "edges") {  // LoG edges + truncated AD, never CA (thesis Sec. 4.1.1)
        if (options.engine != "model") {
            throw std::invalid_argument("--frontend edges runs only with --engine model");
        }
        params.use_ca = false;
    }

    if (options.scale < 1) {
        throw std::invalid_argument("--scale must be >= 1, got " + std::to_string(options.scale));
    }
    if (options.downscale < 1) {
        throw std::invalid_argument("--downscale must be >= 1, got " +
                                    std::to_string(options.downscale));
    }
    // Everything that can be checked cheaply is checked before loading and matching, and all
    // outputs are encoded before the first file is written.
    io::check_disparity_scale(params.ndisp, options.scale);
    io::check_writable_location(options.output);
    if (!options.colour.empty()) {
        io::check_writable_location(options.colour);
    }
    const io::ImagePair pair = io::load_pair(options.left, options.right, options.downscale);
    validate(params, pair.left.width, pair.left.height);

    const auto start = std::chrono::steady_clock::now();
    const DisparityMap map = options.frontend == "edges"
                                 ? edge_frontend::match(pair.left, pair.right, params)
                                 : run_engine(options.engine, pair, params);
    const std::chrono::duration<double, std::milli> elapsed =
        std::chrono::steady_clock::now() - start;

    const cv::Mat stored = io::disparity_to_mat(map, params.ndisp, options.scale);
    const cv::Mat colour =
        options.colour.empty() ? cv::Mat() : io::disparity_to_colour(map, params.ndisp);
    io::write_png(options.output, stored);
    if (!colour.empty()) {
        io::write_png(options.colour, colour);
    }

    const double valid = valid_fraction(map);
    if (options.json) {
        const nlohmann::json summary = {
            {"width", map.width},       {"height", map.height},    {"ndisp", params.ndisp},
            {"window", params.window},  {"sigma", params.sigma},   {"ca", params.use_ca},
            {"engine", options.engine}, {"valid_fraction", valid}, {"ms", elapsed.count()},
        };
        std::cout << summary.dump() << '\n';
    } else {
        std::printf("%dx%d ndisp %d window %d sigma %g ca %s engine %s: %.1f%% valid, %.1f ms\n",
                    map.width, map.height, params.ndisp, params.window, params.sigma,
                    params.use_ca ? "on" : "off", options.engine.c_str(), 100.0 * valid,
                    elapsed.count());
    }
}

}  // namespace

void add_match_command(CLI::App& app) {
    // Shared with the callback, which outlives this function.
    auto options = std::make_shared<MatchOptions>();
    CLI::App* command =
        app.add_subcommand("match", "Compute a disparity map from a rectified left/right pair.");
    command->add_option("LEFT", options->left, "Left image (8-bit grey, RGB or RGBA)")->required();
    command->add_option("RIGHT", options->right, "Right image, same size as LEFT")->required();
    command
        ->add_option("-o,--output", options->output,
                     "Disparity PNG: disparity * scale, 0 = invalid")
        ->required();
    command->add_option("--ndisp", options->params.ndisp, "Number of disparity labels 0..N-1")
        ->capture_default_str();
    CLI::Option* window =
        command->add_option("--window", options->params.window, "Odd aggregation window side")
            ->capture_default_str();
    CLI::Option* sigma =
        command->add_option("--sigma", options->params.sigma, "Gaussian sigma in pixels")
            ->capture_default_str();
    command
        ->add_option("--method", options->method,
                     "pipeline (1-D, rectified pairs) or hierarchical (2-D, uncalibrated pairs)")
        ->check(CLI::IsMember({"pipeline", "hierarchical"}))
        ->capture_default_str();
    command
        ->add_option("--vrange", options->vrange,
                     "hierarchical: vertical labels V (offsets -V/2..V/2-1), 0 = ndisp")
        ->capture_default_str();
    command->add_option("--vertical", options->vertical,
                        "hierarchical: write the vertical offsets (128 + v, 0 = invalid)");
    command->add_option("--dump-levels", options->dump_levels,
                        "hierarchical: write each level's maps into this folder");
    command->add_flag("--no-ca", options->no_ca, "Skip the cellular-automata rules");
    command
        ->add_option("--scale", options->scale,
                     "Multiply disparities by K in the PNG (16-bit when (N-1)*K > 255)")
        ->capture_default_str();
    command->add_option("--color", options->colour, "Also write a colour-mapped view");
    command->add_option("--downscale", options->downscale, "Shrink both images by integer F first")
        ->capture_default_str();
    command
        ->add_option("--engine", options->engine,
                     "model (bit-exact), naive, float or hls (C-simulated HLS kernels, bit-exact)")
        ->check(CLI::IsMember({"model", "naive", "float", "hls"}))
        ->capture_default_str();
    command->add_flag("--json", options->json, "Print the summary as one JSON object");
    command->add_option("--frontend", options->frontend, "model, or edges (LoG + truncated AD)")
        ->check(CLI::IsMember({"model", "edges"}))
        ->capture_default_str();
    command->callback([options, window, sigma] {
        options->window_given = window->count() > 0 || sigma->count() > 0;
        run_match(*options);
    });
}

}  // namespace stereo::cli
