// `stereo match LEFT RIGHT -o DISP.png [options]`: run any registered matcher on a pair.
#include <algorithm>
#include <array>
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
#include "cli_command.hpp"
#include "cli_matcher_options.hpp"
#include "stereo/catalogue.hpp"
#include "stereo/hierarchical.hpp"
#include "stereo_io/colour_key.hpp"
#include "stereo_io/disparity_files.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/output.hpp"
#include "stereo_io/versioned_json.hpp"

namespace stereo::cli {

namespace {

struct MatchOptions {
    std::string left;
    std::string right;
    std::string output;
    std::string colour;      // empty: no colour view
    bool colour_bar = true;  // the colour view's key below it (io::colour_view)
    MatcherOptions matcher;
    int scale = 1;
    int downscale = 1;
    bool json = false;
    bool png16 = false;       // pipeline: offset16 PNG (signed sub-pixel) instead of 8-bit
    std::string vertical;     // 2-D methods: vertical offset PNG, empty: none
    std::string dump_levels;  // hierarchical: folder for the per-level maps, empty: none
    // hierarchical: given values (-1 / empty: the defaults of MatchConfig)
    int vrange = -1;
    std::string field;  // prior, mode, plane or none (the thesis' full level)
    int field_radius = -1;
    std::vector<int> level_windows;  // hierarchical: empty = the defaults
    std::string certainty;           // stage-6 methods: certainty PNG (0..255), empty: none
    std::string reasons;  // stage-6 methods: invalid-reason PNG (fx::kReason...), empty: none

    static constexpr std::string_view kName = "match";
    static constexpr std::string_view kDescription =
        "Compute a disparity map from a stereo pair with any matcher.";
};

// One byte per pixel of stage 6's output (certainty or reason code) as an 8-bit PNG.
cv::Mat bytes_to_mat(const std::vector<std::uint8_t>& bytes, int width, int height) {
    cv::Mat out(height, width, CV_8UC1);
    std::copy(bytes.begin(), bytes.end(), out.data);
    return out;
}

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

double valid_fraction(const DisparityMap& map) {
    std::size_t valid = 0;
    for (const auto flag : map.valid) {
        valid += flag != 0 ? 1 : 0;
    }
    return map.valid.empty() ? 0.0 : static_cast<double>(valid) / map.valid.size();
}

// Per-level disparity, colour and vertical maps of a hierarchical result.
std::vector<std::pair<std::string, cv::Mat>> level_files(const MatchResult& result, int ndisp,
                                                         int scale) {
    std::vector<std::pair<std::string, cv::Mat>> files;
    for (std::size_t l = 0; l < result.levels.size() && l < hierarchical::kLevelNames.size(); ++l) {
        const Winners& level = result.levels[l];
        const int level_ndisp = ndisp / hierarchical::kLevelFactor[l];
        DisparityMap level_map(level.width, level.height);
        for (std::size_t p = 0; p < level.valid.size(); ++p) {
            level_map.valid[p] = level.valid[p];
            level_map.disparity[p] =
                level.valid[p] != 0 ? static_cast<std::uint8_t>(level.disparity[p]) : 0;
        }
        const std::string name = hierarchical::kLevelNames[l];
        files.emplace_back(name + "_disparity.png",
                           io::disparity_to_mat(level_map, level_ndisp, scale));
        files.emplace_back(name + "_color.png", io::disparity_to_colour(level_map, level_ndisp));
        files.emplace_back(name + "_vertical.png",
                           vertical_to_mat(level.vertical, level.valid, level.width, level.height));
    }
    return files;
}

// "pipeline, vertical, diagonal, asw": the methods with stage 6, for error messages.
std::string stage6_methods() {
    return catalogue::join(
        catalogue::method_names([](const catalogue::MethodRow& row) { return row.stage6; }));
}

// --field: the model's field models, then "none" (the thesis' output).
std::vector<std::string> field_choices() {
    std::vector<std::string> choices;
    for (const hierarchical::FieldModelRow& row : hierarchical::kFieldModels) {
        choices.emplace_back(row.name);
    }
    choices.emplace_back("none");
    return choices;
}

std::string field_help() {
    std::string help = "The vertical field:";
    for (const hierarchical::FieldModelRow& row : hierarchical::kFieldModels) {
        help += " " + std::string(row.name) + " (" + std::string(row.summary) + "),";
    }
    return help + " or none (the thesis: the full level's 3x3 winners, no 1-D pass, no stage 6) [" +
           std::string(hierarchical::field_model_name(hierarchical::kDefaultFieldModel)) + "]";
}

// The configuration of the run after every check that needs no image: options that belong to
// another method, impossible scales, outputs the method cannot write.
MatchConfig checked_config(const MatchOptions& options, const catalogue::MethodRow& row,
                           io::DisparityEncoding output_encoding) {
    if (!row.two_d &&
        (options.vrange >= 0 || !options.vertical.empty() || !options.dump_levels.empty() ||
         !options.field.empty() || options.field_radius >= 0 || !options.level_windows.empty())) {
        throw std::invalid_argument(
            "--vrange, --field, --field-radius, --level-windows, --vertical and --dump-levels "
            "need --method hierarchical");
    }
    // --field none: the thesis' output, the full level's 3x3 winners without stage 6.
    const bool full_level_only = options.field == "none";
    if (row.two_d && full_level_only && options.matcher.window_given()) {
        throw std::invalid_argument(
            "--window and --sigma set the hierarchical search's 1-D pass (11x11, sigma 3 by "
            "default), which --field none does not run; the levels use --level-windows");
    }
    if (full_level_only && options.field_radius >= 0) {
        throw std::invalid_argument(
            "--field-radius needs a vertical field (--field none has none)");
    }
    const bool stage6 = row.stage6 && !full_level_only;
    if (output_encoding != io::DisparityEncoding::scaled && !stage6) {
        throw std::invalid_argument(
            "PFM and --png16 outputs hold the pipeline's validated disparities: use a method "
            "with stage 6 (" +
            stage6_methods() + (full_level_only ? "; --field none has none" : "") + ")");
    }
    if ((!options.certainty.empty() || !options.reasons.empty()) && !stage6) {
        throw std::invalid_argument(
            "--certainty and --reasons write stage 6's outputs: use a method with stage 6 (" +
            stage6_methods() + (full_level_only ? "; --field none has none" : "") + ")");
    }
    MatchConfig config = options.matcher.resolved();
    if (row.two_d) {
        config.vrange = options.vrange >= 0 ? options.vrange : config.vrange;
        config.field_radius =
            options.field_radius >= 0 ? options.field_radius : config.field_radius;
        if (!options.level_windows.empty()) {
            std::copy(options.level_windows.begin(), options.level_windows.end(),
                      config.level_windows.begin());
        }
        if (full_level_only) {
            config.hierarchical_output = hierarchical::Output::full_level;
        } else if (!options.field.empty()) {
            config.field_model = hierarchical::field_model_named(options.field).value();
        }
    }
    if (!stage6) {
        // Stage 6 belongs to the 1-D pipeline, ASW and the quad pairs; the other methods
        // validate in their own way.
        if (options.matcher.explicit_validation() || config.pipeline.min_disp != 0) {
            throw std::invalid_argument(
                "--min-disp, --uniqueness, --lr-check, --subpixel and --speckle-size need a "
                "method with stage 6 (" +
                stage6_methods() + (full_level_only ? "; --field none has none" : "") + ")");
        }
        config.pipeline.validation = {};
        config.speckle = {};
    }
    return config;
}

// Every output file can be written, and none is an input or another output.
void check_outputs(const MatchOptions& options, int ndisp) {
    io::check_disparity_scale(ndisp, options.scale);
    std::vector<std::filesystem::path> outputs = {options.output, options.colour, options.vertical,
                                                  options.certainty, options.reasons};
    if (!options.dump_levels.empty()) {  // the nine level maps (level_files)
        for (const char* level : hierarchical::kLevelNames) {
            for (const char* map : {"_disparity.png", "_color.png", "_vertical.png"}) {
                outputs.push_back(std::filesystem::path(options.dump_levels) /
                                  (std::string(level) + map));
            }
        }
    }
    io::check_outputs(outputs, {.files = {options.left, options.right}});
    io::check_writable_location(options.output);
    for (const std::string& extra :
         {options.colour, options.vertical, options.certainty, options.reasons}) {
        if (!extra.empty()) {
            io::check_writable_location(extra);
        }
    }
    if (!options.dump_levels.empty()) {
        io::check_output_folder(options.dump_levels);
    }
}

// Every output encoded, in memory, before the first file is written.
std::vector<std::pair<std::filesystem::path, std::string>> encoded_outputs(
    const MatchOptions& options, const MatchResult& result, int ndisp, int min_disp,
    io::DisparityEncoding output_encoding) {
    const DisparityMap& map = result.disparity;
    std::vector<std::pair<std::filesystem::path, std::string>> files;
    if (output_encoding == io::DisparityEncoding::pfm) {
        files.emplace_back(options.output,
                           io::encode_pfm(io::to_float_disparity(result.validated)));
    } else if (output_encoding == io::DisparityEncoding::offset16) {
        files.emplace_back(options.output,
                           io::encode_disparity_png(io::to_offset16(result.validated),
                                                    {.encoding = io::DisparityEncoding::offset16},
                                                    options.output));
    } else {
        files.emplace_back(options.output,
                           io::encode_disparity_png(io::disparity_to_mat(map, ndisp, options.scale),
                                                    {.encoding = io::DisparityEncoding::scaled,
                                                     .scale = static_cast<double>(options.scale)},
                                                    options.output));
    }
    if (!options.colour.empty()) {
        files.emplace_back(options.colour,
                           io::encode_png(io::colour_view(map, ndisp, min_disp, options.colour_bar),
                                          options.colour));
    }
    if (!options.vertical.empty() && !result.vertical.empty()) {
        // The offsets of the output's valid pixels: the full level's winners, or the field.
        const std::vector<std::int16_t> vertical(result.vertical.begin(), result.vertical.end());
        files.emplace_back(options.vertical, io::encode_png(vertical_to_mat(vertical, map.valid,
                                                                            map.width, map.height),
                                                            options.vertical));
    }
    const ValidatedDisparity& validated = result.validated;
    for (const auto& [path, bytes] : {std::pair{&options.certainty, &validated.certainty},
                                      std::pair{&options.reasons, &validated.reason}}) {
        if (!path->empty()) {
            files.emplace_back(
                *path,
                io::encode_png(bytes_to_mat(*bytes, validated.width, validated.height), *path));
        }
    }
    if (!options.dump_levels.empty()) {
        for (const auto& [name, mat] : level_files(result, ndisp, options.scale)) {
            const std::filesystem::path path = std::filesystem::path(options.dump_levels) / name;
            // The *_disparity.png maps are disparity PNGs (labels x scale), the others views.
            files.emplace_back(
                path, name.ends_with("_disparity.png")
                          ? io::encode_disparity_png(mat,
                                                     {.encoding = io::DisparityEncoding::scaled,
                                                      .scale = static_cast<double>(options.scale)},
                                                     path)
                          : io::encode_png(mat, path));
        }
    }
    return files;
}

// The --json summary and the settings of the text line.
struct Summary {
    nlohmann::json json;
    std::string settings;  // "window 11 sigma 3 cost census ca on method pipeline engine model"
    std::string extra;     // the 2-D methods: ", 1.23 cost evaluations per pixel"
};

// Stage 6's settings and what it invalidated, for the methods with a validated output.
void summarise_stage6(nlohmann::json& json, const MatchResult& result, const MatchConfig& config) {
    const ValidationParams& v = config.pipeline.validation;
    json["uniqueness"] =
        v.uniqueness ? nlohmann::json(v.uniqueness_ratio) : nlohmann::json(nullptr);
    json["lr_check"] = v.left_right ? nlohmann::json(v.lr_tolerance) : nlohmann::json(nullptr);
    json["subpixel"] = v.subpixel;
    json["speckle"] = config.speckle.enabled() ? nlohmann::json{{"size", config.speckle.max_size},
                                                                {"range", config.speckle.range}}
                                               : nlohmann::json(nullptr);
    std::array<std::int64_t, fx::kReasonSpeckle + 1> reasons{};
    for (const auto reason : result.validated.reason) {
        reasons[std::min<std::size_t>(reason, reasons.size() - 1)] += 1;
    }
    json["invalid"] = {{"border", reasons[fx::kReasonBorder]},
                       {"uniqueness", reasons[fx::kReasonUniqueness]},
                       {"left_right", reasons[fx::kReasonLeftRight]},
                       {"speckle", reasons[fx::kReasonSpeckle]}};
}

// The hierarchical search's part: its levels and cost evaluations.
void summarise_levels(Summary& summary, const MatchResult& result, const MatchConfig& config,
                      const std::string& engine, const std::string& method, bool ca) {
    const DisparityMap& map = result.disparity;
    std::int64_t total = 0;
    for (const char* name : hierarchical::kLevelNames) {
        const std::int64_t count = result.count(std::string("cost_evaluations.") + name);
        summary.json["cost_evaluations"][name] = count;
        total += count;
    }
    const std::int64_t pass = result.count("cost_evaluations.field_pass");
    summary.json["cost_evaluations"]["field_pass"] = pass;
    total += pass;
    const double per_pixel = static_cast<double>(total) / (map.width * map.height);
    const int vrange = config.vrange == 0 ? config.pipeline.ndisp : config.vrange;
    const auto& windows = config.level_windows;
    summary.json["vrange"] = vrange;
    summary.json["windows"] = windows;
    summary.json["cost_evaluations_per_pixel"] = per_pixel;
    const bool field = config.hierarchical_output == hierarchical::Output::vertical_field;
    const std::string field_name{field ? hierarchical::field_model_name(config.field_model)
                                       : std::string_view("none")};
    summary.json["field"] = field_name;
    summary.json["field_radius"] =
        field ? nlohmann::json(config.field_radius) : nlohmann::json(nullptr);
    summary.json["cost"] = config.pipeline.cost;
    if (field) {
        summarise_stage6(summary.json, result, config);
    }
    char settings[200];
    std::snprintf(settings, sizeof settings,
                  "vrange %d windows %d/%d/%d field %s cost %s ca %s method %s engine %s", vrange,
                  windows[0], windows[1], windows[2], field_name.c_str(),
                  config.pipeline.cost.c_str(), ca ? "on" : "off", method.c_str(), engine.c_str());
    summary.settings = settings;
    char extra[120];
    std::snprintf(extra, sizeof extra, ", %.2f cost evaluations per pixel", per_pixel);
    // The core (engine rtl) counts no cost evaluations; it reports its frames and clocks.
    if (const std::int64_t frames = result.count("rtl_frames"); frames > 0) {
        const std::int64_t clocks = result.count("rtl_clocks");
        summary.json["rtl_frames"] = frames;
        summary.json["rtl_clocks"] = clocks;
        std::snprintf(extra, sizeof extra,
                      ", %lld frames of the core until its plane settled, %lld clocks",
                      static_cast<long long>(frames), static_cast<long long>(clocks));
    }
    summary.extra = extra;
}

// The 1-D methods' part: window, cost, stage 6 and what it invalidated, ASW's options.
void summarise_plane_search(Summary& summary, const MatchOptions& options,
                            const MatchResult& result, const MatchConfig& config,
                            const catalogue::MethodRow& row, const std::string& engine, bool ca) {
    const MatchParams& params = config.pipeline;
    nlohmann::json& json = summary.json;
    json["window"] = params.window;
    json["sigma"] = params.sigma;
    json["cost"] = params.cost;
    json["min_disp"] = params.min_disp;
    summarise_stage6(json, result, config);
    const std::string method(row.name);
    char settings[200];
    if (row.id == catalogue::Method::asw) {
        const asw::Params& weights = config.asw;
        json["window"] = weights.diameter;
        json.erase("sigma");
        json["asw"] = {{"diameter", weights.diameter},
                       {"response", options.matcher.asw_response},
                       {"shape", options.matcher.asw_shape},
                       {"continuity", weights.continuity},
                       {"right_weights", weights.right_weights},
                       {"separable", weights.separable},
                       {"truncation", asw::truncation_for(weights.truncation, params.cost)}};
        std::snprintf(settings, sizeof settings,
                      "asw diameter %d %s %s%s%s%s cost %s method %s engine %s", weights.diameter,
                      options.matcher.asw_response.c_str(), options.matcher.asw_shape.c_str(),
                      weights.continuity ? " continuity" : "",
                      weights.right_weights ? " both-weights" : " left-weights",
                      weights.separable ? " separable" : "", params.cost.c_str(), method.c_str(),
                      engine.c_str());
    } else {
        std::snprintf(settings, sizeof settings,
                      "window %d sigma %g cost %s ca %s method %s engine %s", params.window,
                      params.sigma, params.cost.c_str(), ca ? "on" : "off", method.c_str(),
                      engine.c_str());
    }
    summary.settings = settings;
}

void run_match(const MatchOptions& options) {
    const std::string method = options.matcher.resolved_method();
    const std::string engine = options.matcher.resolved_engine();
    const catalogue::MethodRow& row = catalogue::method(method);
    // No extension is a PNG, as before; a folder or device fails the file checks (exit 1).
    const auto output_encoding =
        io::output_encoding(options.output, options.png16 ? io::DisparityEncoding::offset16
                                                          : io::DisparityEncoding::scaled);
    const MatchConfig config = checked_config(options, row, output_encoding);
    const auto matcher = matchers().create(method, engine, config);
    const int ndisp = config.pipeline.ndisp;

    // Everything that can be checked cheaply is checked before loading and matching, and all
    // outputs are encoded before the first file is written.
    check_outputs(options, ndisp);
    const io::ImagePair pair = io::load_pair(options.left, options.right, options.downscale);
    matcher->validate(pair.left.width, pair.left.height);

    const auto start = std::chrono::steady_clock::now();
    const MatchResult result = matcher->compute(pair.left, pair.right);
    const std::chrono::duration<double, std::milli> elapsed =
        std::chrono::steady_clock::now() - start;

    // The Verilated core (engine rtl) outputs no level maps: nothing to dump, and no file written.
    if (!options.dump_levels.empty() && result.levels.empty()) {
        throw std::invalid_argument("--dump-levels: engine " + engine + " outputs no level maps");
    }
    // Every output together, all or nothing (io::write_files_atomic).
    const auto files =
        encoded_outputs(options, result, ndisp, config.pipeline.min_disp, output_encoding);
    if (!options.dump_levels.empty()) {
        std::filesystem::create_directories(options.dump_levels);
    }
    io::write_files_atomic(files);

    const DisparityMap& map = result.disparity;
    const double valid = valid_fraction(map);
    const bool ca = config.pipeline.use_ca && row.ca;
    Summary summary;
    summary.json = {
        {"width", map.width}, {"height", map.height}, {"method", method},       {"ndisp", ndisp},
        {"ca", ca},           {"engine", engine},     {"valid_fraction", valid}};
    if (row.two_d) {
        summarise_levels(summary, result, config, engine, method, ca);
    } else {
        summarise_plane_search(summary, options, result, config, row, engine, ca);
    }
    summary.json["ms"] = elapsed.count();
    if (options.json) {
        std::cout << io::versioned(summary.json).dump() << '\n';
        return;
    }
    // "<W>x<H> ndisp <N> <settings>: <valid>% valid, <ms> ms<extra>".
    std::printf("%dx%d ndisp %d %s: %.1f%% valid, %.1f ms%s\n", map.width, map.height, ndisp,
                summary.settings.c_str(), 100.0 * valid, elapsed.count(), summary.extra.c_str());
}

}  // namespace

void add_match_command(CLI::App& app) {
    const auto [command, options] = add_command<MatchOptions>(app, run_match);
    command->add_option("LEFT", options->left, "Left image (8-bit grey, RGB or RGBA)")->required();
    command->add_option("RIGHT", options->right, "Right image, same size as LEFT")->required();
    command
        ->add_option("-o,--output", options->output,
                     "Disparity PNG: disparity * scale, 0 = invalid")
        ->required();
    add_matcher_options(*command, options->matcher, MatcherChoice::selectable,
                        {.validation = true, .speckle = true, .validation_on_by_default = true});
    command->add_flag(
        "--png16,!--no-png16", options->png16,
        "pipeline: write a 16-bit PNG of 32768 + 16 d (signed, 1/16 pixel), 0 = "
        "invalid; a .pfm output holds float disparities with +inf invalid [default: " +
            std::string(options->png16 ? "--png16" : "--no-png16") + "]");
    // The 2-D search's own options, under its heading (the catalogue's summary).
    const std::string two_d =
        "--method hierarchical: " +
        std::string(catalogue::method(catalogue::Method::hierarchical).summary);
    command
        ->add_option("--vrange", options->vrange,
                     "Vertical labels V (offsets -V/2..V/2-1), 0 = ndisp [" +
                         std::to_string(hierarchical::kDefaultVerticalRange) + "]")
        ->group(two_d);
    command->add_option("--field", options->field, field_help())
        ->check(CLI::IsMember(field_choices()))
        ->group(two_d);
    command
        ->add_option("--field-radius", options->field_radius,
                     "Window radius of the field's mode [" +
                         std::to_string(hierarchical::kDefaultFieldRadius) + "]")
        ->check(checks::integer_in(0, hierarchical::kMaxFieldRadius))
        ->group(two_d);
    command
        ->add_option("--level-windows", options->level_windows,
                     "Windows of the quarter, half and full level, odd (sigma 3 N / 11) [9 15 "
                     "15; the thesis: 9 15 23]")
        ->expected(3)
        ->check(checks::odd_in(1, hierarchical::kMaxLevelWindow))
        ->group(two_d);
    command
        ->add_option("--vertical", options->vertical,
                     "Write the vertical offsets (128 + v, 0 = invalid)")
        ->check(checks::png_output())
        ->group(two_d);
    command
        ->add_option("--dump-levels", options->dump_levels,
                     "Write each level's maps into this folder")
        ->group(two_d);
    command
        ->add_option("--scale", options->scale,
                     "Multiply disparities by K in the PNG (16-bit when (N-1)*K > 255)")
        ->capture_default_str()
        ->check(checks::integer_in(1, 65535));
    command
        ->add_option("--color", options->colour,
                     "Also write a colour-mapped view (TURBO, invalid white) with a colour bar "
                     "of the disparities in pixels below it")
        ->check(checks::png_output());
    add_switch(*command, "--color-bar", "--no-color-bar", options->colour_bar,
               "--no-color-bar: the --color view alone, the size of the map");
    command
        ->add_option("--certainty", options->certainty,
                     "pipeline, asw, vertical, diagonal: also write stage 6's certainty of "
                     "every pixel (8-bit PNG, 0..255)")
        ->check(checks::png_output());
    command
        ->add_option("--reasons", options->reasons,
                     "pipeline, asw, vertical, diagonal: also write stage 6's reason code of "
                     "every pixel (8-bit PNG: 0 valid, 1 border, 2 uniqueness, 3 left-right, "
                     "4 speckle)")
        ->check(checks::png_output());
    add_downscale_option(*command, options->downscale);
    add_switch(*command, "--json", "--no-json", options->json,
               "Print the summary as one JSON object; --no-json: one line of text");
}

}  // namespace stereo::cli
