// `stereo eval DISP.png GT.png [options]`: Middlebury-style scores (see stereo_io/metrics.hpp).
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cli.hpp"
#include "cli_command.hpp"
#include "stereo_io/colour_key.hpp"
#include "stereo_io/disparity_files.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/metrics.hpp"
#include "stereo_io/output.hpp"
#include "stereo_io/versioned_json.hpp"

namespace stereo::cli {

namespace {

struct EvalOptions {
    std::string disparity;
    std::string ground_truth;
    double scale = 1.0;
    double gt_scale = 1.0;
    int gt_downscale = 1;  // GT and masks are at F times the disparity's size
    std::string nonocc;    // empty: no mask
    std::string all;
    std::string disc;
    double threshold = 1.0;
    std::string error_map;  // empty: not written
    bool json = false;
    std::string encoding = "scaled";  // of a PNG DISP: scaled or offset16 (.pfm: by extension)
    std::string same_pixels;          // another disparity file: score where both are valid
    bool any_gt_range = false;        // score even a ground truth far outside the map's range
    bool legend = true;               // the --error-map's legend strip (io::with_error_legend)
    // Given on the command line (a PNG's own tag applies otherwise, and must agree with them).
    bool scale_given = false;
    bool gt_scale_given = false;
    bool encoding_given = false;

    static constexpr std::string_view kName = "eval";
    static constexpr std::string_view kDescription =
        "Score a disparity PNG against ground truth (Middlebury bad-pixel %, NMSE).";
};

// How to read a disparity file: its extension (.pfm), else its tag (a PNG the tools wrote,
// io::read_disparity_tag), else the options. An option given on the command line that
// contradicts the tag is an error, not a silent choice.
struct FileReading {
    io::DisparityEncoding encoding;
    double scale;
};

FileReading file_reading(const std::string& path, const char* scale_option, double scale,
                         bool scale_given, io::DisparityEncoding png_encoding,
                         bool encoding_given) {
    const io::DisparityEncoding encoding = io::encoding_of(path, png_encoding);
    if (encoding == io::DisparityEncoding::pfm) {
        return {encoding, scale};
    }
    const std::optional<io::DisparityTag> tag = io::read_disparity_tag(path);
    if (!tag) {
        return {encoding, scale};
    }
    const std::string recorded =
        "'" + path + "' records " + io::disparity_tag_text(*tag) + " (written by stereo)";
    if (encoding_given && tag->encoding != png_encoding) {
        throw std::invalid_argument(recorded + " but --encoding says otherwise: drop --encoding");
    }
    if (scale_given && tag->encoding == io::DisparityEncoding::scaled && tag->scale != scale) {
        throw std::invalid_argument(recorded + " but " + scale_option + " says otherwise: drop " +
                                    scale_option);
    }
    return {tag->encoding, tag->encoding == io::DisparityEncoding::scaled ? tag->scale : 1.0};
}

std::string quoted(const std::string& path) {
    return "'" + path + "'";
}

std::optional<io::NamedMat> load_optional_mask(const std::string& path, const std::string& role,
                                               int downscale) {
    if (path.empty()) {
        return std::nullopt;
    }
    return io::NamedMat{io::downscale_mask(io::load_mask(path), downscale),
                        role + " mask " + quoted(path)};
}

void print_region(const char* label, const std::optional<io::RegionScore>& score,
                  const char* missing_option) {
    if (!score.has_value()) {
        std::printf("%-11s n/a (no %s mask)\n", label, missing_option);
    } else if (const auto percent = score->percent(); percent.has_value()) {
        std::printf("%-11s %.2f %%  (%lld of %lld pixels)\n", label, *percent,
                    static_cast<long long>(score->bad), static_cast<long long>(score->evaluated));
    } else {
        std::printf("%-11s n/a (no pixel with known ground truth in the mask)\n", label);
    }
}

void print_text(const io::EvalResult& result) {
    std::printf("threshold   %g\n", result.threshold);
    print_region("bad_nonocc", result.nonocc, "--nonocc");
    print_region("bad_all", result.all, "--all");
    print_region("bad_disc", result.disc, "--disc");
    print_region("bad_valid", result.valid, "--all");
    if (result.nmse.has_value()) {
        std::printf("nmse        %.6g  (%lld pixels)\n", *result.nmse,
                    static_cast<long long>(result.nmse_pixels));
    } else {
        std::printf("nmse        n/a (no valid pixel with known ground truth)\n");
    }
    if (result.coverage.has_value()) {
        std::printf("coverage    %.2f %%  (%lld of %lld known pixels)\n", 100.0 * *result.coverage,
                    static_cast<long long>(result.known_and_valid),
                    static_cast<long long>(result.known));
    } else {
        std::printf("coverage    n/a (ground truth has no known pixel)\n");
    }
}

void run_eval(const EvalOptions& options) {
    io::check_outputs_distinct(
        {options.error_map}, {options.disparity, options.ground_truth, options.nonocc, options.all,
                              options.disc, options.same_pixels});
    if (!options.error_map.empty()) {
        io::check_writable_location(options.error_map);
    }
    const io::DisparityEncoding png_encoding = options.encoding == "offset16"
                                                   ? io::DisparityEncoding::offset16
                                                   : io::DisparityEncoding::scaled;
    const auto load_ours = [&](const std::string& path) {
        const FileReading reading =
            file_reading(path, "--scale", options.scale, options.scale_given, png_encoding,
                         options.encoding_given);
        return io::load_disparity_file(path, reading.encoding, reading.scale);
    };
    const FileReading gt_reading =
        file_reading(options.ground_truth, "--gt-scale", options.gt_scale, options.gt_scale_given,
                     io::DisparityEncoding::scaled, false);
    // Every map is float with NaN where invalid or unknown: valid zero and negative
    // disparities count like any other.
    io::EvalInput input{
        .disparity = {load_ours(options.disparity), "disparity " + quoted(options.disparity)},
        .ground_truth = {io::downscale_ground_truth(
                             io::load_disparity_file(options.ground_truth, gt_reading.encoding,
                                                     gt_reading.scale),
                             options.gt_downscale),
                         "ground truth " + quoted(options.ground_truth)},
        .nonocc = load_optional_mask(options.nonocc, "nonocc", options.gt_downscale),
        .all = load_optional_mask(options.all, "all", options.gt_downscale),
        .disc = load_optional_mask(options.disc, "disc", options.gt_downscale),
        .threshold = options.threshold,
        .zero_is_invalid = false,
        .gt_zero_is_unknown = false,
    };
    if (!options.same_pixels.empty()) {
        const cv::Mat other = load_ours(options.same_pixels);
        if (other.size() != input.disparity.mat.size()) {
            throw std::invalid_argument("--same-pixels " + quoted(options.same_pixels) +
                                        " is not the size of " + quoted(options.disparity));
        }
        cv::Mat both(other.size(), CV_8UC1, cv::Scalar(0));
        for (int y = 0; y < other.rows; ++y) {
            for (int x = 0; x < other.cols; ++x) {
                const bool valid = std::isfinite(other.at<float>(y, x)) &&
                                   std::isfinite(input.disparity.mat.at<float>(y, x));
                both.at<std::uint8_t>(y, x) = valid ? 255 : 0;
            }
        }
        input.scored = io::NamedMat{both, "pixels valid in both maps"};
    }
    if (!options.any_gt_range) {
        io::check_ground_truth_range(
            input,
            "if GT holds d * K, give --gt-scale K (Middlebury 2003: 4, KITTI: 256); a PNG map from "
            "another tool may need --scale or --encoding offset16; --any-gt-range scores anyway");
    }
    const io::EvalResult result = io::evaluate(input);  // checks every size first
    if (!options.error_map.empty()) {
        const cv::Mat map = io::error_map(input);
        io::write_png(options.error_map, options.legend ? io::with_error_legend(map) : map);
    }
    if (options.json) {
        const nlohmann::json json = result;
        std::cout << io::versioned(json).dump() << '\n';
    } else {
        print_text(result);
    }
}

}  // namespace

void add_eval_command(CLI::App& app) {
    const auto [command, options] = add_command<EvalOptions>(app, run_eval);
    command->add_option("DISP", options->disparity, "Our disparity PNG or PFM")->required();
    command->add_option("GT", options->ground_truth, "Ground-truth PNG (0 = unknown) or PFM")
        ->required();
    add_number_options(
        *command, {{"--scale", &options->scale, "DISP holds disparity * K", disparity_scale()},
                   {"--gt-scale", &options->gt_scale, "GT holds disparity * G", disparity_scale()},
                   {"--gt-downscale", &options->gt_downscale,
                    "GT and masks are F times larger than DISP (match --downscale F)",
                    checks::integer_at_least(1)}});
    command->get_option("--scale")->each(
        [options = options.get()](const std::string&) { options->scale_given = true; });
    command->get_option("--gt-scale")->each([options = options.get()](const std::string&) {
        options->gt_scale_given = true;
    });
    command->add_option("--nonocc", options->nonocc, "Mask of non-occluded pixels (255 = scored)");
    command->add_option("--all", options->all,
                        "Mask of scored pixels (255); default: every known GT pixel");
    command->add_option("--disc", options->disc, "Mask of pixels near discontinuities (255)");
    command->add_option("--threshold", options->threshold, "Bad when |d - gt| > T")
        ->capture_default_str()
        ->check(checks::real_in(0, 1e6));
    command
        ->add_option("--error-map", options->error_map,
                     "Write an RGB PNG: grey correct, red bad, blue invalid, black unscored, "
                     "with a legend strip below")
        ->check(checks::png_output());
    add_switch(*command, "--legend", "--no-legend", options->legend,
               "--no-legend: the --error-map alone, the size of the map");
    command->add_flag("--json", options->json, "Print the scores as one JSON object");
    command
        ->add_option("--encoding", options->encoding,
                     "How a PNG DISP stores disparities: scaled (d * K, 0 = invalid) or offset16 "
                     "(32768 + 16 d, 0 = invalid; stereo match --png16). A .pfm file (DISP or GT) "
                     "is read as float with inf = invalid. A PNG written by stereo records its "
                     "encoding and scale (a text chunk): they apply unless given here")
        ->check(CLI::IsMember({"scaled", "offset16"}))
        ->capture_default_str()
        ->each([options = options.get()](const std::string&) { options->encoding_given = true; });
    char factor[16];
    std::snprintf(factor, sizeof factor, "%g", io::kGroundTruthRangeFactor);
    command->add_flag("--any-gt-range", options->any_gt_range,
                      std::string("Score even when GT's largest value is more than ") + factor +
                          "x the map's (by default an error: a GT read at the wrong --gt-scale "
                          "scores every pixel bad)");
    command->add_option("--same-pixels", options->same_pixels,
                        "Score only pixels valid in DISP and in this other disparity file (same "
                        "encoding), to compare two maps on one pixel set");
}

}  // namespace stereo::cli
