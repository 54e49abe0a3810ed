// `stereo quad REF RIGHT BELOW DIAG -o DISP [options]`: the quad-camera matcher of thesis
// Sec. 3.2 (stereo/quad.hpp, docs/quad.md): three pairs fused by maximum certainty.
#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "cli.hpp"
#include "cli_command.hpp"
#include "cli_matcher_options.hpp"
#include "stereo/catalogue.hpp"
#include "stereo/defaults.hpp"
#include "stereo/quad.hpp"
#include "stereo_io/disparity_files.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/output.hpp"
#include "stereo_io/versioned_json.hpp"

namespace stereo::cli {
namespace {

struct QuadOptions {
    std::array<std::string, 4> views;  // reference, right, below, diagonal
    std::string output;
    std::string certainty;  // fused certainty PNG, empty: none
    std::string source;     // source map PNG, empty: none
    MatcherOptions matcher;
    std::string fuse_by{quad::name(quad::FusionKey::certainty)};  // a quad::FusionKey by name
    bool json = false;

    static constexpr std::string_view kName = "quad";
    static constexpr std::string_view kDescription =
        "Quad-camera matching (thesis Sec. 3.2): horizontal, vertical and diagonal pairs fused "
        "pixel by pixel by maximum certainty (or, --fuse-by cost, by the smallest winner cost).";
};

// The source map as a visible 8-bit PNG: 85 * source code (0 none, 85 horizontal, 170
// vertical, 255 diagonal).
constexpr int kSourceStep = 85;

cv::Mat bytes_to_mat(const std::vector<std::uint8_t>& bytes, int width, int height, int step) {
    cv::Mat out(height, width, CV_8UC1);
    for (std::size_t p = 0; p < bytes.size(); ++p) {
        out.data[p] = static_cast<std::uint8_t>(bytes[p] * step);
    }
    return out;
}

double valid_fraction(const ValidatedDisparity& map) {
    std::size_t valid = 0;
    for (std::size_t i = 0; i < map.reason.size(); ++i) {
        valid += map.valid(i) ? 1 : 0;
    }
    return map.reason.empty() ? 0.0 : static_cast<double>(valid) / map.reason.size();
}

// -o (PFM or offset16 PNG), --certainty and --source, all or nothing.
void write_outputs(const QuadOptions& options, const std::string& extension,
                   const quad::QuadResult& result) {
    const ValidatedDisparity& fused = result.fused;
    std::vector<std::pair<std::filesystem::path, std::string>> files;
    files.emplace_back(options.output,
                       extension == ".pfm"
                           ? io::encode_pfm(io::to_float_disparity(fused))
                           : io::encode_disparity_png(io::to_offset16(fused),
                                                      {.encoding = io::DisparityEncoding::offset16},
                                                      options.output));
    if (!options.certainty.empty()) {
        files.emplace_back(
            options.certainty,
            io::encode_png(bytes_to_mat(fused.certainty, fused.width, fused.height, 1),
                           options.certainty));
    }
    if (!options.source.empty()) {
        files.emplace_back(options.source, io::encode_png(bytes_to_mat(result.source, fused.width,
                                                                       fused.height, kSourceStep),
                                                          options.source));
    }
    io::write_files_atomic(files);
}

void run_quad(const QuadOptions& options) {
    const MatchConfig config = options.matcher.resolved();
    const MatchParams& params = config.pipeline;
    validate_params(params);
    std::string extension = std::filesystem::path(options.output).extension().string();
    for (char& c : extension) {
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    }
    if (extension != ".png" && extension != ".pfm") {
        throw std::invalid_argument("-o must name a .png (offset16) or .pfm file, got '" +
                                    options.output + "'");
    }
    const std::vector<std::filesystem::path> inputs(options.views.begin(), options.views.end());
    io::check_outputs_distinct({options.output, options.certainty, options.source}, inputs);
    for (const std::string& path : {options.output, options.certainty, options.source}) {
        if (!path.empty()) {
            io::check_writable_location(path);
        }
    }
    std::array<Image, 4> images;
    for (std::size_t v = 0; v < images.size(); ++v) {
        images[v] = io::load_image(options.views[v]);
    }
    const quad::QuadViews views{images[0], images[1], images[2], images[3]};
    quad::validate_quad(views, params);

    const auto start = std::chrono::steady_clock::now();
    const quad::QuadResult result =
        quad::match_quad(views, params, true, quad::fusion_key(options.fuse_by));
    const std::chrono::duration<double, std::milli> elapsed =
        std::chrono::steady_clock::now() - start;

    const ValidatedDisparity& fused = result.fused;
    write_outputs(options, extension, result);

    std::array<std::int64_t, 4> sources{};
    for (const auto s : result.source) {
        sources[s] += 1;
    }
    nlohmann::json summary = {{"width", fused.width},    {"height", fused.height},
                              {"ndisp", params.ndisp},   {"min_disp", params.min_disp},
                              {"window", params.window}, {"sigma", params.sigma},
                              {"ca", params.use_ca},     {"valid_fraction", valid_fraction(fused)},
                              {"ms", elapsed.count()}};
    summary["fuse_by"] = options.fuse_by;
    summary["cost"] = params.cost;
    for (const quad::Pair pair : quad::kPairs) {
        const std::string name(quad::name(pair));
        summary["pairs"][name]["valid_fraction"] =
            valid_fraction(result.pairs[static_cast<std::size_t>(pair)]);
        summary["source"][name] = sources[quad::source_code(pair)];
    }
    summary["source"]["none"] = sources[quad::kSourceNone];
    if (options.json) {
        std::cout << io::versioned(summary).dump() << '\n';
        return;
    }
    std::printf(
        "%dx%d ndisp %d min-disp %d window %d cost %s: %.1f%% valid (horizontal %.1f%%, vertical "
        "%.1f%%, diagonal %.1f%% of the pixels won), %.1f ms\n",
        fused.width, fused.height, params.ndisp, params.min_disp, params.window,
        params.cost.c_str(), 100.0 * valid_fraction(fused),
        100.0 * sources[1] / static_cast<double>(result.source.size()),
        100.0 * sources[2] / static_cast<double>(result.source.size()),
        100.0 * sources[3] / static_cast<double>(result.source.size()), elapsed.count());
}

}  // namespace

void add_quad_command(CLI::App& app) {
    const auto [command, options] = add_command<QuadOptions>(app, run_quad);
    command->add_option("REF", options->views[0], "Reference view (upper left)")->required();
    command->add_option("RIGHT", options->views[1], "Horizontal partner (upper right)")->required();
    command->add_option("BELOW", options->views[2], "Vertical partner (lower left)")->required();
    command->add_option("DIAG", options->views[3], "Diagonal partner (lower right)")->required();
    command
        ->add_option("-o,--output", options->output,
                     "Fused disparity: .pfm (float, +inf invalid) or .png (16-bit, 32768 + 16 d, "
                     "0 invalid)")
        ->required();
    options->matcher.config.pipeline.window = 13;  // the thesis' quad window
    // `stereo match`'s default cost (chosen on the Middlebury scenes, stereo/defaults.hpp); every
    // pair geometry takes the pixel-pair costs of the catalogue.
    options->matcher.config.pipeline.cost = std::string(defaults::kCost);
    add_matcher_options(*command, options->matcher, MatcherChoice::fixed, {.validation = true});
    command
        ->add_option("--cost", options->matcher.config.pipeline.cost,
                     "Matching cost of the three pairs (default: stereo match's): " +
                         catalogue::cost_help(catalogue::CostUse::pixel_pair))
        ->check(CLI::IsMember(catalogue::cost_names(catalogue::CostUse::pixel_pair)))
        ->capture_default_str();
    std::vector<std::string> keys;  // the model's names of the fusion keys
    for (const quad::FusionKey key : quad::kFusionKeys) {
        keys.emplace_back(quad::name(key));
    }
    command
        ->add_option("--fuse-by", options->fuse_by,
                     "What fusion compares: certainty (stage 6's, the largest wins) or cost (the "
                     "winner's aggregated cost, the smallest wins; docs/quad.md)")
        ->check(CLI::IsMember(keys))
        ->capture_default_str();
    command
        ->add_option("--certainty", options->certainty,
                     "Also write the fused certainty (8-bit PNG, 0..255)")
        ->check(checks::png_output());
    command
        ->add_option("--source", options->source,
                     "Also write the source map (8-bit PNG: 0 none, 85 horizontal, 170 "
                     "vertical, 255 diagonal)")
        ->check(checks::png_output());
    command->add_flag("--json", options->json, "Print the summary as one JSON object");
}

}  // namespace stereo::cli
