// `stereo match LEFT RIGHT -o DISP.png [options]`: run one engine on a rectified pair.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cli.hpp"
#include "stereo/edge_frontend.hpp"
#include "stereo/hls/match.hpp"
#include "stereo/pipeline.hpp"
#include "stereo/reference.hpp"
#include "stereo_app/io.hpp"

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
};

DisparityMap run_engine(const std::string& engine, const app::ImagePair& pair,
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
    app::check_disparity_scale(params.ndisp, options.scale);
    app::check_writable_location(options.output);
    if (!options.colour.empty()) {
        app::check_writable_location(options.colour);
    }
    const app::ImagePair pair = app::load_pair(options.left, options.right, options.downscale);
    validate(params, pair.left.width, pair.left.height);

    const auto start = std::chrono::steady_clock::now();
    const DisparityMap map = options.frontend == "edges"
                                 ? edge_frontend::match(pair.left, pair.right, params)
                                 : run_engine(options.engine, pair, params);
    const std::chrono::duration<double, std::milli> elapsed =
        std::chrono::steady_clock::now() - start;

    const cv::Mat stored = app::disparity_to_mat(map, params.ndisp, options.scale);
    const cv::Mat colour =
        options.colour.empty() ? cv::Mat() : app::disparity_to_colour(map, params.ndisp);
    app::write_png(options.output, stored);
    if (!colour.empty()) {
        app::write_png(options.colour, colour);
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
    command->add_option("--window", options->params.window, "Odd aggregation window side")
        ->capture_default_str();
    command->add_option("--sigma", options->params.sigma, "Gaussian sigma in pixels")
        ->capture_default_str();
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
    command->callback([options] { run_match(*options); });
}

}  // namespace stereo::cli
