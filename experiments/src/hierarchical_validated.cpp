// `stereo_experiments hierarchical-validated`: the tables of docs/results-hierarchical.md,
// "Validated output". The validated hierarchical search (stage 6 and the speckle filter as
// `stereo match`), the validated 1-D pipeline (`stereo match`'s defaults) and OpenCV StereoSGBM
// on every scene with ground truth, aligned and misaligned (the right image shifted by rows,
// rotated, both images lens-distorted: stereo distort), scored against the exact ground truth
// (every pixel followed through the warp): coverage and bad > 1 px among the output.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cli_command.hpp"
#include "experiments.hpp"
#include "stereo/defaults.hpp"
#include "stereo/hierarchical.hpp"
#include "stereo/speckle.hpp"
#include "stereo_io/disparity_files.hpp"
#include "stereo_io/distortion.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/middlebury.hpp"

namespace stereo::experiments {
namespace {
using json = nlohmann::json;

struct Options : cli::ReportOptions {
    static constexpr std::string_view kName = "hierarchical-validated";
    static constexpr std::string_view kDescription =
        "Validated hierarchical search beside the validated 1-D pipeline and SGBM on every scene "
        "with ground truth, aligned and misaligned (docs/results-hierarchical.md).";
    std::string cost{defaults::kCost};
    int vrange = hierarchical::kDefaultVerticalRange;
    std::vector<int> windows{hierarchical::kDefaultLevelWindows.begin(),
                             hierarchical::kDefaultLevelWindows.end()};
    int field_radius = hierarchical::kDefaultFieldRadius;
    std::string field_model{hierarchical::field_model_name(hierarchical::kDefaultFieldModel)};
    double radial_min_gain = hierarchical::kDefaultRadialMinGain;
    int prior_factor = hierarchical::Params{}.prior_factor;
    bool thesis_output = false;       // Output::full_level instead of the vertical field
    std::vector<std::string> scenes;  // empty: all
    std::vector<std::string> cases;   // empty: all
};

struct Case {
    std::string name;
    io::PairWarp warp;
};

const std::vector<Case> kCases = {
    {"aligned", {}},           {"shift 1", {0, 1, 0}},          {"shift 2", {0, 2, 0}},
    {"shift 4", {0, 4, 0}},    {"rotation 0.25", {0, 0, 0.25}}, {"rotation 0.5", {0, 0, 0.5}},
    {"rotation 1", {0, 0, 1}}, {"distortion 5", {5, 0, 0}},     {"distortion 10", {10, 0, 0}}};

struct Score {
    double coverage = 0;
    double bad = 0;  // bad > 1 among the output
};

Score score(const io::SceneData& data, const cv::Mat& disparity) {
    const io::EvalResult result = io::evaluate({.disparity = {disparity, "disparity"},
                                                .ground_truth = data.ground_truth,
                                                .threshold = 1.0,
                                                .zero_is_invalid = false});
    return {100.0 * result.coverage.value_or(0.0), result.valid.percent().value_or(0.0)};
}

cv::Mat nan_invalid(cv::Mat map) {
    map.setTo(std::numeric_limits<float>::quiet_NaN(), map <= 0.0F);
    return map;
}

// Field models of the experiment only (upper bounds from the known warp, not the model's):
//  oracle: the exact vertical offset of every pixel's match, rounded, as the field (in the
//          right image's columns), the 1-D pass along it as for every field model;
//  oracle-subpixel: the right image resampled (linear in y) at the exact, unrounded offset,
//          then the same 1-D pass: what is left is the resampling of the warp and the changed
//          disparities, not the whole-row field;
//  oracle-half: as oracle-subpixel with the offset rounded to half rows (halves up): a field
//          of twice the resolution.
constexpr std::string_view kOracle = "oracle";
constexpr std::string_view kOracleSubpixel = "oracle-subpixel";
constexpr std::string_view kOracleHalf = "oracle-half";

std::vector<std::string> field_model_names() {
    std::vector<std::string> names;
    for (const hierarchical::FieldModelRow& row : hierarchical::kFieldModels) {
        names.emplace_back(row.name);
    }
    names.emplace_back(kOracle);
    names.emplace_back(kOracleSubpixel);
    names.emplace_back(kOracleHalf);
    return names;
}

bool is_oracle(const std::string& name) {
    return name == kOracle || name == kOracleSubpixel || name == kOracleHalf;
}

hierarchical::Params params_of(const Options& options, int ndisp) {
    hierarchical::Params params;
    params.ndisp = (ndisp + 3) / 4 * 4;
    params.vrange = options.vrange;
    params.cost = options.cost;
    for (std::size_t l = 0; l < hierarchical::kLevels; ++l) {
        params.levels[l] = hierarchical::default_level(options.windows.at(l));
    }
    params.output = options.thesis_output ? hierarchical::Output::full_level
                                          : hierarchical::Output::vertical_field;
    params.field_radius = options.field_radius;
    params.radial_min_gain = options.radial_min_gain;
    params.prior_factor = options.prior_factor;
    params.field_model = hierarchical::field_model_named(options.field_model)
                             .value_or(hierarchical::kDefaultFieldModel);
    const defaults::Validation chosen = defaults::validation_for(options.cost);
    params.validation = {true, chosen.uniqueness, true, chosen.lr_tolerance, true};
    return params;
}

// Percent of the pixels with a known vertical and horizontal disparity whose field value at their
// match's column (the field lives in the right image's columns) is the nearest integer to the
// vertical disparity.
double field_agreement(const std::vector<std::int8_t>& field, const cv::Mat& exact_vertical,
                       const cv::Mat& exact_horizontal) {
    std::int64_t known = 0;
    std::int64_t equal = 0;
    for (int y = 0; y < exact_vertical.rows; ++y) {
        for (int x = 0; x < exact_vertical.cols; ++x) {
            const float v = exact_vertical.at<float>(y, x);
            const float d = exact_horizontal.at<float>(y, x);
            const int column = x - static_cast<int>(std::lround(d));
            if (std::isnan(v) || !(d > 0) || column < 0) {
                continue;
            }
            ++known;
            const std::size_t p = static_cast<std::size_t>(y) * exact_vertical.cols + column;
            equal += field[p] == static_cast<int>(std::lround(v)) ? 1 : 0;
        }
    }
    return known == 0 ? 0.0 : 100.0 * static_cast<double>(equal) / static_cast<double>(known);
}

// The exact vertical offset at every right pixel (xr, y): the offset of the left pixel whose
// exact match lies in column xr of row y (xr = x - round(d)); of several, the one with the
// largest disparity (the visible one). A right pixel without one takes the nearest one of its
// row (the smaller column on a tie), a row without any the nearest such row (the upper on a tie).
std::vector<float> oracle_offsets(const cv::Mat& exact_vertical, const cv::Mat& exact_horizontal) {
    const int width = exact_vertical.cols;
    const int height = exact_vertical.rows;
    const float unknown = std::numeric_limits<float>::quiet_NaN();
    std::vector<float> offsets(static_cast<std::size_t>(width) * height, unknown);
    std::vector<float> depth(offsets.size(), 0.0F);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const float v = exact_vertical.at<float>(y, x);
            const float d = exact_horizontal.at<float>(y, x);
            const int column = x - static_cast<int>(std::lround(d));
            if (std::isnan(v) || !(d > 0) || column < 0 || column >= width) {
                continue;
            }
            const std::size_t p = static_cast<std::size_t>(y) * width + column;
            if (d > depth[p]) {
                depth[p] = d;
                offsets[p] = v;
            }
        }
    }
    std::vector<int> filled_rows;
    for (int y = 0; y < height; ++y) {
        float* row = offsets.data() + static_cast<std::size_t>(y) * width;
        std::vector<float> known(row, row + width);
        int last = -1;
        std::vector<int> before(static_cast<std::size_t>(width), -1);
        for (int x = 0; x < width; ++x) {
            last = std::isnan(known[static_cast<std::size_t>(x)]) ? last : x;
            before[static_cast<std::size_t>(x)] = last;
        }
        if (last < 0) {
            continue;
        }
        filled_rows.push_back(y);
        int next = -1;
        for (int x = width - 1; x >= 0; --x) {
            next = std::isnan(known[static_cast<std::size_t>(x)]) ? next : x;
            const int b = before[static_cast<std::size_t>(x)];
            const int nearest = b < 0 ? next : next < 0 ? b : (x - b <= next - x ? b : next);
            row[x] = known[static_cast<std::size_t>(nearest)];
        }
    }
    for (int y = 0; y < height && !filled_rows.empty(); ++y) {
        int nearest = filled_rows.front();
        for (const int r : filled_rows) {
            if (std::abs(r - y) < std::abs(nearest - y)) {
                nearest = r;
            }
        }
        if (nearest != y) {
            std::copy_n(offsets.begin() + static_cast<std::ptrdiff_t>(nearest) * width, width,
                        offsets.begin() + static_cast<std::ptrdiff_t>(y) * width);
        }
    }
    for (float& v : offsets) {
        v = std::isnan(v) ? 0.0F : v;
    }
    return offsets;
}

// The right image resampled at the exact offsets, linearly in y (rows clamped into the image).
Image resample_rows(const Image& right, const std::vector<float>& offsets) {
    Image out(right.width, right.height, right.channels);
    for (int y = 0; y < right.height; ++y) {
        for (int x = 0; x < right.width; ++x) {
            const double row = std::clamp(
                y + static_cast<double>(offsets[static_cast<std::size_t>(y) * right.width + x]),
                0.0, right.height - 1.0);
            const int r0 = static_cast<int>(std::floor(row));
            const int r1 = std::min(r0 + 1, right.height - 1);
            const double t = row - r0;
            for (int c = 0; c < right.channels; ++c) {
                out.at(x, y, c) = static_cast<std::uint8_t>(
                    std::lround((1 - t) * right.at(x, r0, c) + t * right.at(x, r1, c)));
            }
        }
    }
    return out;
}

hierarchical::Result run_oracle(const Options& options, const io::SceneData& data,
                                const io::WarpedScene& warped) {
    const hierarchical::Params params = params_of(options, data.scene.ndisp);
    std::vector<float> offsets =
        oracle_offsets(warped.exact_vertical, warped.exact_ground_truth.mat);
    std::vector<std::int8_t> field(offsets.size());
    for (std::size_t p = 0; p < offsets.size(); ++p) {
        field[p] = static_cast<std::int8_t>(
            std::clamp<long>(std::lround(offsets[p]), -hierarchical::kMaxVerticalRange / 2,
                             hierarchical::kMaxVerticalRange / 2 - 1));
    }
    hierarchical::CostCount count;
    ValidatedDisparity validated;
    if (options.field_model == kOracleHalf) {
        for (float& v : offsets) {
            v = std::floor(2 * v + 0.5F) / 2;
        }
    }
    if (options.field_model == kOracleSubpixel || options.field_model == kOracleHalf) {
        // The pass on the resampled image with field 0 (its border rule: the image border).
        const Image resampled = resample_rows(data.pair.right, offsets);
        validated = hierarchical::match_along_field(data.pair.left, resampled,
                                                    std::vector<std::int8_t>(field.size(), 0),
                                                    params, count.field_pass);
    } else {
        validated = hierarchical::match_along_field(data.pair.left, data.pair.right, field, params,
                                                    count.field_pass);
    }
    return hierarchical::finish_field({}, count, std::move(field), std::move(validated));
}

cv::Mat run_hierarchical(const Options& options, const io::SceneData& data,
                         const io::WarpedScene& warped, double& agreement) {
    hierarchical::Result result = is_oracle(options.field_model)
                                      ? run_oracle(options, data, warped)
                                      : hierarchical::match(data.pair.left, data.pair.right,
                                                            params_of(options, data.scene.ndisp));
    agreement = result.field.empty() ? 0.0
                                     : field_agreement(result.field, warped.exact_vertical,
                                                       warped.exact_ground_truth.mat);
    if (options.thesis_output) {
        return nan_invalid(io::to_float_disparity(result.disparity));
    }
    speckle::filter(result.validated, speckle::Params::defaults());
    return io::to_float_disparity(result.validated);
}

cv::Mat run_pipeline(const io::SceneData& data) {
    MatchParams params;
    params.ndisp = data.scene.ndisp;
    params.cost = defaults::kCost;
    return io::to_float_disparity(match_as_stereo_match(data.pair.left, data.pair.right, params));
}

bool wanted(const std::vector<std::string>& list, const std::string& name) {
    return list.empty() || std::find(list.begin(), list.end(), name) != list.end();
}

void run(const Options& options) {
    check_report_outputs({options.markdown, options.json_path});
    const auto scenes = load_ground_truth_scenes(options.data_dir);
    json report = {{"cost", options.cost},
                   {"vrange", options.vrange},
                   {"windows", options.windows},
                   {"field_radius", options.field_radius},
                   {"field_model", options.field_model},
                   {"radial_min_gain", options.radial_min_gain},
                   {"prior_factor", options.prior_factor},
                   {"thesis_output", options.thesis_output},
                   {"rows", json::array()}};
    std::ostringstream md;
    md << "| scene | case | hierarchical coverage % / bad % | 1-D coverage % / bad % | SGBM "
          "coverage % / bad % | hierarchical / 1-D | hierarchical / SGBM | field = exact v % "
          "|\n|---|---|---|---|---|---|---|---|\n";
    for (const auto& scene : scenes) {
        if (!wanted(options.scenes, scene.scene.name)) {
            continue;
        }
        for (const auto& c : kCases) {
            if (!wanted(options.cases, c.name)) {
                continue;
            }
            const io::WarpedScene warped = io::warp_scene(scene, c.warp);
            io::SceneData exact = warped.data;
            exact.ground_truth = warped.exact_ground_truth;
            double agreement = 0;
            const Score h = score(exact, run_hierarchical(options, warped.data, warped, agreement));
            const Score p = score(exact, run_pipeline(warped.data));
            const Score s = score(exact, nan_invalid(io::run_stereo_sgbm(warped.data)));
            report["rows"].push_back(json{{"scene", scene.scene.name},
                                          {"case", c.name},
                                          {"field_agreement", agreement},
                                          {"hierarchical", json::array({h.coverage, h.bad})},
                                          {"pipeline", json::array({p.coverage, p.bad})},
                                          {"sgbm", json::array({s.coverage, s.bad})}});
            const auto pair = [](const Score& x) {
                return fmt(x.coverage, 1) + " / " + fmt(x.bad);
            };
            const std::string line =
                "| " + scene.scene.name + " | " + c.name + " | " + pair(h) + " | " + pair(p) +
                " | " + pair(s) + " | " + fmt(h.bad / std::max(p.bad, 1e-9)) + "x | " +
                fmt(h.bad / std::max(s.bad, 1e-9)) + "x | " + fmt(agreement, 1) + " |\n";
            md << line;
            std::cerr << line << std::flush;
        }
    }
    print_and_write_report({}, options.markdown, md.str(), options.json_path, report);
}

}  // namespace

void add_hierarchical_validated_command(CLI::App& app) {
    const auto [command, options] = cli::add_report_command<Options>(app, run);
    command->add_option("--cost", options->cost, "Cost of the hierarchical search")
        ->check(CLI::IsMember(cost_names()))
        ->capture_default_str();
    command->add_option("--vrange", options->vrange, "Vertical labels V")->capture_default_str();
    command->add_option("--windows", options->windows, "Windows of the three levels")
        ->expected(3)
        ->capture_default_str();
    command->add_option("--field-radius", options->field_radius, "Vertical field radius")
        ->check(CLI::Range(0, hierarchical::kMaxFieldRadius))
        ->capture_default_str();
    command->add_option("--field-model", options->field_model, "How the field is made")
        ->check(CLI::IsMember(field_model_names()))
        ->capture_default_str();
    command
        ->add_option("--radial-min-gain", options->radial_min_gain,
                     "Radial field models: keep the lens term if it explains this many times "
                     "the plane's votes")
        ->capture_default_str();
    command
        ->add_option("--prior-factor", options->prior_factor,
                     "Prior field models: the prior's offset stays unless outvoted this many "
                     "times")
        ->capture_default_str();
    command->add_flag("--thesis-output", options->thesis_output,
                      "The full level's 3x3 winners instead of the vertical field");
    command->add_option("--scenes", options->scenes, "Only these scenes");
    command->add_option("--cases", options->cases, "Only these cases");
}

}  // namespace stereo::experiments
