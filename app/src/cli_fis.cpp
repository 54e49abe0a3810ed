// `stereo fis --left L --center C --right R [--json]`: the fuzzy direction decision alone.
#include <cstdio>
#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cli.hpp"
#include "cli_command.hpp"
#include "stereo_io/versioned_json.hpp"
#include "stereo_robot/decision.hpp"

namespace stereo::cli {

namespace {

struct FisOptions {
    double left = 0.0;
    double centre = 0.0;
    double right = 0.0;
    bool json = false;
    robot::FisParams params;

    static constexpr std::string_view kName = "fis";
    static constexpr std::string_view kDescription =
        "Evaluate the fuzzy obstacle-avoidance system on three window occupancies.";
};

void run_fis(const FisOptions& options) {
    const robot::FisResult result =
        robot::evaluate_fis(options.left, options.centre, options.right, options.params);
    if (options.json) {
        const nlohmann::json out = {{"angle_deg", result.angle_deg},
                                    {"backwards", result.backwards},
                                    {"decision", robot::to_string(result.decision)}};
        std::cout << io::versioned(out).dump() << '\n';
    } else {
        std::printf("angle_deg %.3f backwards %.4f decision %s\n", result.angle_deg,
                    result.backwards, robot::to_string(result.decision).c_str());
    }
}

}  // namespace

void add_fis_command(CLI::App& app) {
    const auto [command, options] = add_command<FisOptions>(app, run_fis);
    command->add_option("--left", options->left, "Occupied fraction of the left window, [0, 1]")
        ->required();
    command
        ->add_option("--center,--centre", options->centre,
                     "Occupied fraction of the centre window, [0, 1]")
        ->required();
    command->add_option("--right", options->right, "Occupied fraction of the right window, [0, 1]")
        ->required();
    command->add_flag("--json", options->json, "Print one JSON object");
    add_number_options(*command, {{"--rate", &options->params.rate,
                                   "Centre occupancy from which 'forward' is never the answer"},
                                  {"--forward-band", &options->params.forward_band,
                                   "|angle| up to this (deg) is no turn"}});
}

}  // namespace stereo::cli
