// `stereo_experiments sigma-sweep SIGMA...`: the table of docs/sigma-sweep.md. Bad-pixel
// percentages of the model (CA on) on the Middlebury 2003 pairs for each sigma; the default sigma
// is the one with the lowest mean of nonocc, all and disc over the pairs.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli_command.hpp"
#include "cli_matcher_options.hpp"
#include "experiments.hpp"
#include "stereo_io/data_dir.hpp"
#include "stereo_io/middlebury.hpp"

namespace stereo::experiments {
namespace {
namespace fs = std::filesystem;

struct SweepOptions {
    std::string data_dir = io::data_dir().string();
    int window = fx::kDefaultWindow;
    std::vector<double> sigmas;
};

// The model with CA on; the registry checks window and sigma when the matcher is made.
std::unique_ptr<Matcher> model(int ndisp, int window, double sigma) {
    MatchConfig config;
    config.pipeline = {ndisp, window, sigma, true};
    return cli::matchers().create("pipeline", "model", config);
}

std::string header(std::size_t scene_count) {
    std::ostringstream md;
    md << "| sigma |";
    for (const auto& scene : io::middlebury2003_scenes()) {
        md << ' ' << scene.name << " nonocc/all/disc |";
    }
    md << " mean nonocc | mean all | mean disc | mean of the three |\n|---|";
    for (std::size_t i = 0; i < scene_count + 4; ++i) {
        md << "---|";
    }
    md << '\n';
    return md.str();
}

void run_sweep(const SweepOptions& options) {
    // Parameters first (exit 2), then files (exit 1), whatever is wrong with both.
    for (const double sigma : options.sigmas) {
        (void)model(fx::kDefaultDisparities, options.window, sigma);
    }
    const fs::path folder = fs::path(options.data_dir) / "middlebury2003";
    if (!fs::is_directory(folder)) {
        throw std::runtime_error("cannot read '" + folder.string() + "': no such folder");
    }
    const std::vector<io::SceneData> scenes = load_2003_scenes(options.data_dir);
    if (scenes.empty()) {
        throw std::runtime_error("no Middlebury 2003 scene found under " + options.data_dir);
    }
    std::cout << header(io::middlebury2003_scenes().size());
    for (const double sigma : options.sigmas) {
        double sums[3] = {0, 0, 0};
        std::ostringstream md;
        md << "| " << sigma << " |";
        for (const auto& data : scenes) {
            const MatchResult result = model(data.scene.ndisp, options.window, sigma)
                                           ->compute(data.pair.left, data.pair.right);
            const io::EvalResult r =
                io::evaluate_scene(data, io::to_float_disparity(result.disparity));
            const double values[3] = {*r.nonocc->percent(), *r.all.percent(), *r.disc->percent()};
            char cell[64];
            std::snprintf(cell, sizeof cell, " %.2f / %.2f / %.2f |", values[0], values[1],
                          values[2]);
            md << cell;
            for (int i = 0; i < 3; ++i) {
                sums[i] += values[i] / scenes.size();
            }
        }
        char tail[96];
        std::snprintf(tail, sizeof tail, " %.2f | %.2f | %.2f | %.2f |\n", sums[0], sums[1],
                      sums[2], (sums[0] + sums[1] + sums[2]) / 3.0);
        std::cout << md.str() << tail << std::flush;  // one row at a time: the sweep is slow
    }
}

}  // namespace

void add_sigma_sweep_command(CLI::App& app) {
    const auto [command, options] = cli::add_command<SweepOptions>(
        app, "sigma-sweep",
        "Sweep the aggregation sigma on the Middlebury 2003 pairs (docs/sigma-sweep.md).",
        run_sweep);
    command->add_option("SIGMA", options->sigmas, "The sigmas to try, in pixels")->required();
    cli::add_data_option(*command, options->data_dir);
    command->add_option("--window", options->window, "Odd aggregation window side")
        ->capture_default_str();
}

}  // namespace stereo::experiments
