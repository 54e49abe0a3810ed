// `stereo relight IN OUT [options]`: write a copy of an image under different illumination (a
// uniform HSL lightness change, a camera gain / offset / gamma, a lightness gradient or
// vignette), for the evaluation of illumination-invariant costs (docs/results-illumination.md).
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <opencv2/core/mat.hpp>

#include "cli.hpp"
#include "cli_command.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/lighting.hpp"
#include "stereo_io/output.hpp"

namespace stereo::cli {

namespace {
namespace fs = std::filesystem;

struct RelightOptions {
    std::string input;
    std::string output;
    io::Lighting lighting;
    std::vector<double> gradient;
    bool equalise = false;

    static constexpr std::string_view kName = "relight";
    static constexpr std::string_view kDescription =
        "Write a copy of a colour image under changed illumination (HSL lightness, camera "
        "gain/offset/gamma, gradient, vignette).";
};

void run_relight(RelightOptions& options) {
    if (!options.gradient.empty()) {
        if (options.gradient.size() != 2) {
            throw std::invalid_argument("--gradient takes two percentages, LEFT,RIGHT");
        }
        options.lighting.gradient_left = options.gradient[0];
        options.lighting.gradient_right = options.gradient[1];
    }
    io::validate(options.lighting);  // before reading anything
    io::check_outputs_distinct({options.output}, {options.input});
    io::check_writable_location(options.output);
    const Image image = io::load_image(options.input);
    if (image.channels != 3) {
        throw std::invalid_argument(
            "relight changes HSL lightness, so it needs a colour image; \"" + options.input +
            "\" is grey");
    }
    cv::Mat out = io::relight(io::to_bgr(image), options.lighting);
    if (options.equalise) {
        out = io::equalise_lightness(out);
    }
    io::write_png(options.output, out);
    std::cout << "wrote " << options.output << " (lightness " << options.lighting.lightness_percent
              << " %, gain " << options.lighting.gain << ", offset " << options.lighting.offset
              << ", gamma " << options.lighting.gamma << ", gradient "
              << options.lighting.gradient_left << ".." << options.lighting.gradient_right
              << " %, vignette " << options.lighting.vignette_percent << " %"
              << (options.equalise ? ", lightness equalised" : "") << ")\n";
}

}  // namespace

void add_relight_command(CLI::App& app) {
    const auto [command, options] =
        add_command<RelightOptions>(app, [](RelightOptions& o) { run_relight(o); });
    command->add_option("IN", options->input, "Colour image to relight")->required();
    command->add_option("OUT", options->output, "Output PNG (written atomically)")
        ->check(checks::png_output())
        ->required();
    command
        ->add_option("--lightness", options->lighting.lightness_percent,
                     "Uniform HSL lightness change P % in [-100, 100] (thesis: -25..25)")
        ->capture_default_str();
    command->add_option("--gain", options->lighting.gain, "Camera gain in (0, 16]")
        ->capture_default_str();
    command->add_option("--offset", options->lighting.offset, "Camera offset in grey levels")
        ->capture_default_str();
    command->add_option("--gamma", options->lighting.gamma, "Camera gamma in [0.1, 10]")
        ->capture_default_str();
    command
        ->add_option("--gradient", options->gradient,
                     "Horizontal lightness gradient LEFT,RIGHT in % (thesis: -50,50)")
        ->delimiter(',')
        ->expected(2);
    command
        ->add_option("--vignette", options->lighting.vignette_percent,
                     "Vignette: the corners lose P % lightness, falling off as r^2")
        ->capture_default_str();
    command->add_flag("--equalise", options->equalise,
                      "Histogram-equalise the HSL lightness afterwards (hue, saturation kept)");
}

}  // namespace stereo::cli
