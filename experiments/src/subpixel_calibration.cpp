// `stereo_experiments subpixel-calibration`: where stage 6's sub-pixel correction table
// (fx::kSubpixelCorrection, docs/fixed-point.md stage 6) comes from, and what it does.
//
// Calibration, on no evaluation scene: fronto-parallel pairs with known sub-pixel shifts, sampled
// the way a camera samples them. A KITTI frame is the scene; the left view is its area average
// over FACTOR x FACTOR blocks, the right view the same after shifting the frame by FACTOR * D + m
// pixels, so the true disparity is D + m / FACTOR and every pixel integrates its footprint. For
// each vertex p of the parabola (1/16 px) the mean true offset of the pixels that got p gives
// the table entry. Evaluation: `stereo match`'s defaults for the cost on the eight scenes with
// ground truth, the integer winner, the plain parabola and the corrected offset (the model's
// output), scored among the valid output pixels with ground truth.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "cli_command.hpp"
#include "experiments.hpp"
#include "stereo/constants.hpp"
#include "stereo/defaults.hpp"
#include "stereo/pipeline.hpp"
#include "stereo/search.hpp"
#include "stereo/stages.hpp"
#include "stereo/stages/validate.hpp"
#include "stereo_io/io.hpp"

namespace stereo::experiments {
namespace {
namespace fs = std::filesystem;
using json = nlohmann::json;

constexpr int kHalf = fx::kSubpixelScale / 2;  // the largest |offset|, 8
constexpr int kCalibrationLabels = 16;
constexpr int kLeftMargin = 40;  // calibration columns left of this have no partner at D = 6

struct Options : cli::ReportOptions {
    std::string cost = std::string(defaults::kCost);  // its `stereo match` defaults
    int factor = 8;                                   // area factor: shifts of 1 / factor px
    static constexpr std::string_view kName = "subpixel-calibration";
    static constexpr std::string_view kDescription =
        "Stage 6's sub-pixel parabola on camera-sampled shifts of KITTI frames: its bias, the "
        "correction table it gives (constants.hpp), and the table's effect on the eight scenes "
        "(docs/fixed-point.md, stage 6).";
};

MatchParams defaults_for(const std::string& cost, int ndisp) {
    MatchParams params;
    params.ndisp = ndisp;
    params.cost = cost;
    return params;
}

// One pixel's three readings in 1/16 px: the integer winner, the parabola, the model's output.
struct Readings {
    int integer = 0;
    int parabola = 0;  // the offset p, -8 .. 8
    int fixed = 0;
};

// The pair as `stereo match` runs it with the cost's defaults, and for every valid pixel its
// readings from the final volume (cost, aggregation, CA rules: the winner is the first minimum of
// the column, as stage 6's). A valid pixel whose model output differs from the volume's winner
// plus subpixel_offset throws: the two paths must agree.
std::vector<std::pair<std::size_t, Readings>> readings(const Image& left, const Image& right,
                                                       const MatchParams& params) {
    const ValidatedDisparity map = match_as_stereo_match(left, right, params);
    Dsi volume = aggregate(cost_volume(*make_cost(params.cost), left, right, params.ndisp),
                           gaussian_kernel(params.window, params.sigma));
    if (params.use_ca) {
        volume = ca_rule2(ca_rule1(volume));
    }
    std::vector<std::pair<std::size_t, Readings>> out;
    for (std::size_t i = 0; i < map.fixed.size(); ++i) {
        if (!map.valid(i)) {
            continue;
        }
        int k1 = 0;
        for (int k = 1; k < params.ndisp; ++k) {
            k1 = volume.plane(k)[i] < volume.plane(k1)[i] ? k : k1;
        }
        Readings r;
        r.integer = fx::kSubpixelScale * (params.min_disp + k1);
        if (k1 > 0 && k1 + 1 < params.ndisp) {
            const int a = volume.plane(k1 - 1)[i];
            const int c = volume.plane(k1)[i];
            const int b = volume.plane(k1 + 1)[i];
            r.parabola = validation::parabola_offset(a, c, b);
            if (r.integer + validation::subpixel_offset(a, c, b) != map.fixed[i]) {
                throw std::logic_error("subpixel-calibration: stage 6 and the volume disagree");
            }
        }
        r.fixed = map.fixed[i];
        out.emplace_back(i, r);
    }
    return out;
}

struct Calibration {
    std::array<long long, 2 * kHalf + 1> count{};
    std::array<double, 2 * kHalf + 1> true_sum{};
    // Per true fraction m / factor: pixels, summed |error| of integer, parabola, corrected.
    std::vector<std::array<double, 4>> by_fraction;
};

Calibration calibrate(const Options& options) {
    const int factor = options.factor;
    Calibration cal;
    cal.by_fraction.assign(static_cast<std::size_t>(factor), {});
    int frames = 0;
    for (const int sequence : {1, 2}) {
        for (int frame = 0; frame <= 50; frame += 5) {
            char name[16];
            std::snprintf(name, sizeof name, "%06d.png", frame);
            const fs::path path = fs::path(options.data_dir) / "sequence" /
                                  ("kitti_sequence_" + std::to_string(sequence)) / "image_l" / name;
            const cv::Mat scene = io::load_bgr(path);
            const int width = (scene.cols - 64 * factor) / factor;
            if (width <= kLeftMargin + kCalibrationLabels) {
                throw std::runtime_error(path.string() + " is too narrow for --factor " +
                                         std::to_string(factor));
            }
            ++frames;
            const Image left = io::to_image(
                io::shrink_area(scene(cv::Rect(0, 0, width * factor, scene.rows)), factor), name);
            for (const int whole : {3, 6}) {
                for (int m = 0; m < factor; ++m) {
                    const int shift = whole * factor + m;
                    const Image right = io::to_image(
                        io::shrink_area(scene(cv::Rect(shift, 0, width * factor, scene.rows)),
                                        factor),
                        name);
                    const double true16 = static_cast<double>(fx::kSubpixelScale) * shift / factor;
                    for (const auto& [i, r] :
                         readings(left, right, defaults_for(options.cost, kCalibrationLabels))) {
                        if (static_cast<int>(i) % left.width < kLeftMargin ||
                            std::abs(r.fixed - true16) >= fx::kSubpixelScale) {
                            continue;  // no partner, or a gross error: not what the table is for
                        }
                        const double truth = true16 - r.integer;  // the true offset, 1/16
                        cal.count[static_cast<std::size_t>(r.parabola + kHalf)] += 1;
                        cal.true_sum[static_cast<std::size_t>(r.parabola + kHalf)] += truth;
                        auto& f = cal.by_fraction[static_cast<std::size_t>(m)];
                        f[0] += 1;
                        f[1] += std::abs(truth);
                        f[2] += std::abs(truth - r.parabola);
                        f[3] += std::abs(truth - (r.fixed - r.integer));
                    }
                }
            }
        }
    }
    if (frames == 0) {
        throw std::runtime_error("no KITTI frame under " + options.data_dir);
    }
    return cal;
}

// The table the calibration gives: for |p| = 1 .. 7 the mean true offset of the pixels at p
// and -p (sign folded), rounded half up, kept monotone and at most 8; 0 -> 0 and 8 -> 8 (a half
// pixel reads the same from either neighbouring winner).
std::array<int, kHalf + 1> derived_table(const Calibration& cal) {
    std::array<int, kHalf + 1> table{};
    for (int p = 1; p < kHalf; ++p) {
        const auto up = static_cast<std::size_t>(kHalf + p);
        const auto down = static_cast<std::size_t>(kHalf - p);
        const long long n = cal.count[up] + cal.count[down];
        const double mean = n == 0 ? p : (cal.true_sum[up] - cal.true_sum[down]) / n;
        table[static_cast<std::size_t>(p)] =
            std::clamp(static_cast<int>(std::floor(mean + 0.5)),
                       table[static_cast<std::size_t>(p - 1)], kHalf);
    }
    table[kHalf] = kHalf;
    return table;
}

void run(const Options& options) {
    if (options.factor < 2 || options.factor > 16) {
        throw std::invalid_argument("--factor must be 2 .. 16, got " +
                                    std::to_string(options.factor));
    }
    MatchParams check = defaults_for(options.cost, kCalibrationLabels);
    check.validation = ValidationParams::all_on();
    validate_params(check);
    check_report_outputs({options.markdown, options.json_path}, {}, options.data_dir);
    const Calibration cal = calibrate(options);
    const auto table = derived_table(cal);
    const bool same = std::equal(table.begin(), table.end(), fx::kSubpixelCorrection.begin());

    std::ostringstream md;
    json report = {{"cost", options.cost}, {"factor", options.factor}};
    md << "Calibration (" << options.cost << ", area factor " << options.factor
       << ", KITTI frames 0, 5, .., 50 of both clips, D = 3 and 6 px plus m / " << options.factor
       << "):\n\n| parabola offset p (1/16 px) | pixels | mean true offset (1/16 px) |\n"
          "|---|---|---|\n";
    for (int p = -kHalf; p <= kHalf; ++p) {
        const auto s = static_cast<std::size_t>(p + kHalf);
        if (cal.count[s] == 0) {
            continue;
        }
        const double mean = cal.true_sum[s] / static_cast<double>(cal.count[s]);
        md << "| " << p << " | " << cal.count[s] << " | " << fmt(mean) << " |\n";
        report["offsets"].push_back({{"p", p}, {"pixels", cal.count[s]}, {"mean_true", mean}});
    }
    md << "\nDerived table |p| = 0 .. 8: {";
    for (std::size_t k = 0; k < table.size(); ++k) {
        md << table[k] << (k + 1 < table.size() ? ", " : "}");
    }
    md << " — " << (same ? "equals" : "DIFFERS FROM") << " fx::kSubpixelCorrection.\n\n";
    report["table"] = table;
    report["table_equals_constants"] = same;
    md << "| true fraction | pixels | mean abs error px: integer | parabola | corrected |\n"
          "|---|---|---|---|---|\n";
    for (std::size_t m = 0; m < cal.by_fraction.size(); ++m) {
        const auto& f = cal.by_fraction[m];
        const double n = std::max(1.0, f[0]) * fx::kSubpixelScale;
        md << "| " << m << "/" << options.factor << " | " << static_cast<long long>(f[0]) << " | "
           << fmt(f[1] / n, 3) << " | " << fmt(f[2] / n, 3) << " | " << fmt(f[3] / n, 3) << " |\n";
        report["fractions"].push_back({{"m", m},
                                       {"pixels", f[0]},
                                       {"integer", f[1] / n},
                                       {"parabola", f[2] / n},
                                       {"corrected", f[3] / n}});
    }

    md << "\nThe eight scenes, `stereo match`'s defaults for " << options.cost
       << " (valid output pixels with ground truth):\n\n"
          "| scene | bad > 0.5 %: integer | parabola | corrected | RMS px: integer | parabola | "
          "corrected |\n|---|---|---|---|---|---|---|\n";
    for (const io::SceneData& scene : load_ground_truth_scenes(options.data_dir)) {
        const cv::Mat& gt = scene.ground_truth.mat;
        std::array<long long, 3> bad{};
        std::array<double, 3> squared{};
        long long n = 0;
        for (const auto& [i, r] : readings(scene.pair.left, scene.pair.right,
                                           defaults_for(options.cost, scene.scene.ndisp))) {
            const float g =
                gt.at<float>(static_cast<int>(i) / gt.cols, static_cast<int>(i) % gt.cols);
            if (g <= 0.0F) {
                continue;
            }
            ++n;
            const std::array<int, 3> estimate = {r.integer, r.integer + r.parabola, r.fixed};
            for (std::size_t e = 0; e < estimate.size(); ++e) {
                const double error = estimate[e] / static_cast<double>(fx::kSubpixelScale) - g;
                bad[e] += std::abs(error) > 0.5 ? 1 : 0;
                squared[e] += error * error;
            }
        }
        const double count = std::max<long long>(n, 1);
        md << "| " << scene.scene.name;
        json row = {{"scene", scene.scene.name}, {"pixels", n}};
        const char* names[3] = {"integer", "parabola", "corrected"};
        for (std::size_t e = 0; e < 3; ++e) {
            md << " | " << fmt(100.0 * bad[e] / count);
            row[names[e]]["bad_05"] = 100.0 * bad[e] / count;
        }
        for (std::size_t e = 0; e < 3; ++e) {
            md << " | " << fmt(std::sqrt(squared[e] / count), 3);
            row[names[e]]["rms"] = std::sqrt(squared[e] / count);
        }
        md << " |\n";
        report["scenes"].push_back(row);
    }
    print_and_write_report({}, options.markdown, md.str(), options.json_path, report);
}

}  // namespace

void add_subpixel_calibration_command(CLI::App& app) {
    const auto [command, options] = cli::add_report_command<Options>(app, run);
    command->add_option("--cost", options->cost, "Matching cost (its stereo match defaults)")
        ->check(CLI::IsMember({"census", "ad"}))
        ->capture_default_str();
    command->add_option("--factor", options->factor, "Area-downsampling factor: shifts of 1/F px")
        ->capture_default_str();
}

}  // namespace stereo::experiments
