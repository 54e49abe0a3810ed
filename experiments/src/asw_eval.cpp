// `stereo_experiments asw-eval`: the tables and figures of docs/results-asw-tables.md, adaptive
// support weights (thesis Sec. 3.4, method "asw") against the thesis and OpenCV SGBM, every
// method in the same run on the same images:
//   * Table 3.6, the ablation on Tsukuba (continuity, log response, circular window; ours: left
//     weights only, separable), bad > 1 nonocc / all / disc and the variation to "presented";
//   * Table 3.7 on the four Middlebury 2003 pairs: full ASW, separable, SGBM, the thesis;
//   * Table 3.8: ASW with the LCDM cost;
//   * held-out scenes (Reindeer, Cloth3, Wood2, Aloe at half size; no masks: bad > 1 over every
//     known pixel with invalid counted bad, and coverage);
//   * the lightness sweep of the right image on Tsukuba (separable ASW with AD and LCDM, SGBM);
//   * speed on Teddy (wall time; every run's time is in the JSON);
//   * figures: one strip per 2003 pair and held-out scene (io::scene_strip).
// The output is the plain winner map (no stage 6 validation), as in the thesis.
#include <algorithm>
#include <array>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <ranges>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <thread>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include "cli_command.hpp"
#include "cli_matcher_options.hpp"
#include "experiments.hpp"
#include "stereo/asw.hpp"
#include "stereo/matcher.hpp"
#include "stereo_io/data_dir.hpp"
#include "stereo_io/disparity_files.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/lighting.hpp"
#include "stereo_io/metrics.hpp"
#include "stereo_io/middlebury.hpp"
#include "stereo_io/scene_strip.hpp"
#include "stereo_io/versioned_json.hpp"

namespace stereo::experiments {
namespace {
namespace fs = std::filesystem;
using json = nlohmann::json;
using Clock = std::chrono::steady_clock;

struct AswEvalOptions : cli::ReportOptions {
    static constexpr std::string_view kName = "asw-eval";
    static constexpr std::string_view kDescription =
        "Adaptive support weights (method asw) against the thesis' Tables 3.6-3.8 and OpenCV "
        "SGBM: ablation, the 2003 pairs, LCDM, held-out scenes, lightness sweep, speed "
        "(docs/results-asw-tables.md).";
    std::string figures;  // folder of the per-pair strips; empty: none
    bool quick = false;   // Tsukuba and Venus only
};

// A strip larger than this is downscaled until it fits (the figures live in the repository).
constexpr std::size_t kMaxFigureBytes = 300 * 1024;

// bad > 1 %: nonocc / all / disc.
using Triple = std::array<double, 3>;

// Thesis Table 3.6 (Tsukuba) and Table 3.7 ("presented"), Table 3.8 (LCDM).
const std::map<std::string, Triple>& thesis_presented() {
    static const std::map<std::string, Triple> table = {{"tsukuba", {3.62, 5.52, 14.6}},
                                                        {"venus", {3.15, 4.20, 20.4}},
                                                        {"teddy", {11.5, 18.2, 23.2}},
                                                        {"cones", {4.93, 13.0, 11.7}}};
    return table;
}
const std::map<std::string, Triple>& thesis_ablation() {
    // Table 3.6's "presented" row is Table 3.7's Tsukuba.
    static const std::map<std::string, Triple> table = {
        {"presented", thesis_presented().at("tsukuba")},
        {"no continuity", {5.19, 7.17, 21.7}},
        {"exp response", {8.89, 10.5, 36.1}},
        {"square window", {3.79, 5.62, 15.8}}};
    return table;
}
const std::map<std::string, Triple>& thesis_lcdm() {
    static const std::map<std::string, Triple> table = {{"tsukuba", {5.98, 7.84, 22.2}},
                                                        {"venus", {14.5, 15.4, 35.9}},
                                                        {"teddy", {20.8, 27.3, 38.3}},
                                                        {"cones", {8.90, 17.2, 20.0}}};
    return table;
}

// One configuration of the matcher (or the OpenCV baseline).
struct Config {
    std::string name;
    std::string cost = "ad";  // "sgbm": OpenCV StereoSGBM instead of ASW
    asw::Params params;
    int opencv_threads = -1;  // SGBM: cv::setNumThreads for the call, -1 = OpenCV's default
};

Config asw_config(const std::string& name, const std::function<void(asw::Params&)>& edit = {},
                  const std::string& cost = "ad") {
    Config config{name, cost, {}, -1};
    if (edit) {
        edit(config.params);
    }
    return config;
}

Config sgbm_config(const std::string& name, int threads) {
    return {name, "sgbm", {}, threads};
}

struct Run {
    cv::Mat disparity;  // CV_32FC1, NaN = invalid (stage 6's convention; 0 is a disparity)
    double seconds = 0.0;
};

Run run(const io::SceneData& data, const Config& config) {
    const auto start = Clock::now();
    Run result;
    if (config.cost == "sgbm") {
        const int before = cv::getNumThreads();
        if (config.opencv_threads >= 0) {
            cv::setNumThreads(config.opencv_threads);
        }
        try {
            result.disparity = io::run_stereo_sgbm(data);  // 0 = invalid
            result.disparity.setTo(std::numeric_limits<float>::quiet_NaN(),
                                   result.disparity <= 0.0F);
        } catch (...) {
            cv::setNumThreads(before);
            throw;
        }
        cv::setNumThreads(before);
    } else {
        MatchConfig match;
        match.pipeline.ndisp = data.scene.ndisp;
        match.pipeline.cost = config.cost;
        match.asw = config.params;
        const auto matcher = cli::matchers().create("asw", "model", match);
        result.disparity =
            io::to_float_disparity(matcher->compute(data.pair.left, data.pair.right).validated);
    }
    result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return result;
}

bool has_masks(const io::SceneData& data) {
    return !data.nonocc.mat.empty();
}

// The 2003 pairs of a scene list (scored on their masks), in order.
auto masked_pairs(const std::vector<io::SceneData>& scenes) {
    return scenes | std::views::filter(has_masks);
}

// The held-out scenes of a scene list (no masks), in order.
auto held_out_scenes(const std::vector<io::SceneData>& scenes) {
    return scenes | std::views::filter(std::not_fn(has_masks));
}

// The 2003 pairs: the Middlebury masks. The others: every known pixel, invalid counted bad.
json score(const io::SceneData& data, const cv::Mat& disparity) {
    io::EvalInput input{.disparity = {disparity, "disparity of " + data.scene.name},
                        .ground_truth = data.ground_truth,
                        .threshold = 1.0,
                        .zero_is_invalid = false};
    if (has_masks(data)) {
        input.nonocc = data.nonocc;
        input.all = data.all;
        input.disc = data.disc;
    }
    const io::EvalResult r = io::evaluate(input);
    json out = {{"bad_all", r.all.percent().value_or(0.0)},
                {"coverage", 100.0 * r.coverage.value_or(0.0)}};
    if (r.nonocc) {
        out["bad_nonocc"] = r.nonocc->percent().value_or(0.0);
    }
    if (r.disc) {
        out["bad_disc"] = r.disc->percent().value_or(0.0);
    }
    return out;
}

json params_json(const Config& config) {
    if (config.cost == "sgbm") {
        return {{"method", "opencv_sgbm"}, {"opencv_threads", config.opencv_threads}};
    }
    const asw::Params& p = config.params;
    return {{"method", "asw"},
            {"cost", config.cost},
            {"diameter", p.diameter},
            {"response", p.response == asw::Response::log ? "log" : "exp"},
            {"shape", p.shape == asw::Shape::circle ? "circle" : "square"},
            {"continuity", p.continuity},
            {"right_weights", p.right_weights},
            {"separable", p.separable},
            {"truncation", asw::truncation_for(p.truncation, config.cost)},
            {"threads", p.threads}};
}

// Every run of the evaluation, in order, and by (scene, config) for the tables.
class Results {
  public:
    json& add(const std::string& part, const io::SceneData& data, const Config& config,
              const Run& result, const json& extra = json::object()) {
        json entry = {{"part", part},
                      {"scene", data.scene.name},
                      {"config", config.name},
                      {"params", params_json(config)},
                      {"seconds", result.seconds}};
        entry.update(score(data, result.disparity));
        entry.update(extra);
        runs_.push_back(entry);
        char seconds[32];
        std::snprintf(seconds, sizeof seconds, "%.2f", result.seconds);
        std::cerr << "asw-eval: " << part << ", " << data.scene.name << ", " << config.name << ": "
                  << seconds << " s\n";
        return runs_.back();
    }
    const json* find(const std::string& part, const std::string& scene,
                     const std::string& config) const {
        for (const json& entry : runs_) {
            if (entry["part"] == part && entry["scene"] == scene && entry["config"] == config) {
                return &entry;
            }
        }
        return nullptr;
    }
    const json& at(const std::string& part, const std::string& scene,
                   const std::string& config) const {
        const json* entry = find(part, scene, config);
        if (entry == nullptr) {
            throw std::logic_error("asw-eval: no run " + part + " / " + scene + " / " + config);
        }
        return *entry;
    }
    const json& runs() const { return runs_; }

  private:
    json runs_ = json::array();
};

// "3.62 / 5.52 / 14.6" in the thesis' style (three significant digits).
std::string fmt3(double value) {
    return fmt(value, value >= 10.0 ? 1 : 2);
}

Triple triple(const json& entry) {
    return {entry["bad_nonocc"].get<double>(), entry["bad_all"].get<double>(),
            entry["bad_disc"].get<double>()};
}

std::string cells(const Triple& t) {
    return fmt3(t[0]) + " / " + fmt3(t[1]) + " / " + fmt3(t[2]);
}

std::string variation(const Triple& t, const Triple& base) {
    std::string out;
    for (std::size_t i = 0; i < 3; ++i) {
        out += (i > 0 ? " / " : "") + std::string(t[i] >= base[i] ? "+" : "") +
               fmt(100.0 * (t[i] - base[i]) / base[i], 0);
    }
    return out;
}

// ---- the tables --------------------------------------------------------------------------

// `ndisp`: the scene's, for the continuity normaliser row.
std::vector<Config> ablation_configs(int ndisp) {
    return {asw_config("presented"),
            asw_config("no continuity", [](asw::Params& p) { p.continuity = false; }),
            asw_config("exp response", [](asw::Params& p) { p.response = asw::Response::exp; }),
            asw_config("square window", [](asw::Params& p) { p.shape = asw::Shape::square; }),
            asw_config("left weights only", [](asw::Params& p) { p.right_weights = false; }),
            asw_config("separable", [](asw::Params& p) { p.separable = true; }),
            asw_config("continuity range ndisp",
                       [ndisp](asw::Params& p) { p.disparity_range = std::min(ndisp, 255); }),
            asw_config("untruncated cost", [](asw::Params& p) { p.truncation = 0; })};
}

const Config kFull = asw_config("full");
const Config kSeparable = asw_config("separable", [](asw::Params& p) { p.separable = true; });
const Config kLcdm = asw_config("lcdm", {}, "lcdm");
const Config kSeparableLcdm = asw_config(
    "separable lcdm", [](asw::Params& p) { p.separable = true; }, "lcdm");
// The census cost (the default of `stereo match`'s pipeline), not truncated (its default).
const Config kCensus = asw_config("census", {}, "census");
const Config kSeparableCensus = asw_config(
    "separable census", [](asw::Params& p) { p.separable = true; }, "census");
const Config kSgbm = sgbm_config("sgbm", -1);
const Config kSgbmSingle = sgbm_config("sgbm 1 thread", 1);
const Config kFullSingle = asw_config("full 1 thread", [](asw::Params& p) { p.threads = 1; });
const Config kSeparableSingle = asw_config("separable 1 thread", [](asw::Params& p) {
    p.separable = true;
    p.threads = 1;
});

std::vector<double> sweep_steps() {
    std::vector<double> steps;
    for (int p = -25; p <= 25; p += 5) {
        steps.push_back(p);
    }
    return steps;
}

std::string ablation_table(const Results& results, int ndisp) {
    std::ostringstream md;
    const Triple base = triple(results.at("ablation", "tsukuba", "presented"));
    const Triple thesis_base = thesis_ablation().at("presented");
    md << "### Table 3.6: ablation on Tsukuba (bad > 1 %, nonocc / all / disc)\n\n"
       << "| configuration | ours | variation to our presented (%) | thesis | thesis variation "
          "(%) | seconds |\n|---|---|---|---|---|---|\n";
    for (const Config& config : ablation_configs(ndisp)) {
        const json& entry = results.at("ablation", "tsukuba", config.name);
        const Triple ours = triple(entry);
        md << "| " << config.name << " | " << cells(ours) << " | " << variation(ours, base)
           << " | ";
        const auto thesis = thesis_ablation().find(config.name);
        if (thesis != thesis_ablation().end()) {
            md << cells(thesis->second) << " | " << variation(thesis->second, thesis_base);
        } else {
            md << "- | -";
        }
        md << " | " << fmt(entry["seconds"].get<double>()) << " |\n";
    }
    md << "\nexp response: Yoon and Kweon's exp(-difference / gamma) with the colour gamma "
          "asw::kExpColourGamma = "
       << fmt(asw::kExpColourGamma, 0)
       << " and continuity gamma asw::kExpContinuityGamma = " << fmt(asw::kExpContinuityGamma, 0)
       << " (the project's constants, stereo/asw.hpp; proximity gamma = the radius). square "
          "window: the odd square of nearly the circle's pixel count. continuity range ndisp: the "
          "continuity stimulus normalised by ndisp = "
       << ndisp
       << " instead of asw::Params::disparity_range = 255 (ours). untruncated cost: the AD "
          "without Yoon and Kweon's truncation at asw::kDefaultTruncation = "
       << asw::kDefaultTruncation << " (docs/asw.md, \"The truncated cost\").\n";
    return md.str();
}

// The goal column of a table against the thesis: "yes" or "no" for each figure of ours at or
// below the thesis' (nonocc / all / disc), counted into met of figures.
struct ThesisGoal {
    int met = 0;
    int figures = 0;
    std::string row(const Triple& ours, const Triple& thesis) {
        std::string goal;
        for (std::size_t i = 0; i < 3; ++i) {
            const bool ok = ours[i] <= thesis[i];
            met += ok ? 1 : 0;
            ++figures;
            goal += (i > 0 ? " / " : "") + std::string(ok ? "yes" : "no");
        }
        return goal;
    }
};

std::string presented_table(const Results& results, const std::vector<io::SceneData>& scenes) {
    std::ostringstream md;
    md << "### Table 3.7: the four 2003 pairs (bad > 1 %, nonocc / all / disc)\n\n"
       << "| pair | ours (full ASW, AD) | ours separable | separable / full | OpenCV SGBM | thesis "
          "presented | goal: ours <= thesis (nonocc / all / disc); ours < SGBM nonocc |\n"
       << "|---|---|---|---|---|---|---|\n";
    ThesisGoal thesis_goal;
    int below_sgbm = 0;
    int pairs = 0;
    for (const io::SceneData& data : masked_pairs(scenes)) {
        const std::string& name = data.scene.name;
        const Triple full = triple(results.at("pairs", name, kFull.name));
        const Triple separable = triple(results.at("pairs", name, kSeparable.name));
        const Triple sgbm = triple(results.at("pairs", name, kSgbm.name));
        const Triple thesis = thesis_presented().at(name);
        std::string ratio;
        for (std::size_t i = 0; i < 3; ++i) {
            ratio += (i > 0 ? " / " : "") + fmt(separable[i] / full[i]);
        }
        std::string goal = thesis_goal.row(full, thesis);
        const bool beats_sgbm = full[0] < sgbm[0];
        below_sgbm += beats_sgbm ? 1 : 0;
        ++pairs;
        goal += std::string("; ") + (beats_sgbm ? "yes" : "no");
        md << "| " << name << " | " << cells(full) << " | " << cells(separable) << " | " << ratio
           << " | " << cells(sgbm) << " | " << cells(thesis) << " | " << goal << " |\n";
    }
    md << "\nGoal: " << thesis_goal.met << " of " << thesis_goal.figures
       << " figures at or below the thesis; ours below "
       << "SGBM (nonocc) on " << below_sgbm << " of " << pairs << " pairs.\n";
    return md.str();
}

std::string lcdm_table(const Results& results, const std::vector<io::SceneData>& scenes) {
    std::ostringstream md;
    md << "### Table 3.8: ASW with the LCDM cost (bad > 1 %, nonocc / all / disc)\n\n"
       << "| pair | ours ASW + LCDM | thesis (Table 3.8) | ours ASW + AD | LCDM - AD (nonocc) "
          "|\n|---|---|---|---|---|\n";
    for (const io::SceneData& data : masked_pairs(scenes)) {
        const std::string& name = data.scene.name;
        const Triple lcdm = triple(results.at("pairs", name, kLcdm.name));
        const Triple ad = triple(results.at("pairs", name, kFull.name));
        md << "| " << name << " | " << cells(lcdm) << " | " << cells(thesis_lcdm().at(name))
           << " | " << cells(ad) << " | " << fmt(lcdm[0] - ad[0]) << " |\n";
    }
    return md.str();
}

std::string census_table(const Results& results, const std::vector<io::SceneData>& scenes) {
    std::ostringstream md;
    md << "### ASW with the census cost (not in the thesis; bad > 1 %, nonocc / all / disc)\n\n"
       << "| pair | ours ASW + census | ours separable + census | ours ASW + AD | thesis "
          "presented (AD) | census <= thesis |\n|---|---|---|---|---|---|\n";
    ThesisGoal thesis_goal;
    for (const io::SceneData& data : masked_pairs(scenes)) {
        const std::string& name = data.scene.name;
        const Triple census = triple(results.at("pairs", name, kCensus.name));
        const Triple thesis = thesis_presented().at(name);
        const std::string goal = thesis_goal.row(census, thesis);
        md << "| " << name << " | " << cells(census) << " | "
           << cells(triple(results.at("pairs", name, kSeparableCensus.name))) << " | "
           << cells(triple(results.at("pairs", name, kFull.name))) << " | " << cells(thesis)
           << " | " << goal << " |\n";
    }
    md << "\nASW + census: " << thesis_goal.met << " of " << thesis_goal.figures
       << " figures at or below the thesis' presented (AD) row.\n";
    return md.str();
}

std::string held_out_table(const Results& results, const std::vector<io::SceneData>& scenes) {
    std::ostringstream md;
    md << "### Held-out scenes (no masks: bad > 1 % over every known pixel, invalid counted "
          "bad / coverage %)\n\n"
       << "| scene | ndisp | full ASW | separable | ASW + LCDM | ASW + census | separable + "
          "census | OpenCV SGBM | full ASW seconds |\n|---|---|---|---|---|---|---|---|---|\n";
    for (const io::SceneData& data : held_out_scenes(scenes)) {
        const std::string& name = data.scene.name;
        md << "| " << name << " | " << data.scene.ndisp << " |";
        for (const Config* config :
             {&kFull, &kSeparable, &kLcdm, &kCensus, &kSeparableCensus, &kSgbm}) {
            const json& entry = results.at("held-out", name, config->name);
            md << ' ' << fmt(entry["bad_all"].get<double>()) << " / "
               << fmt(entry["coverage"].get<double>(), 1) << " |";
        }
        md << ' ' << fmt(results.at("held-out", name, kFull.name)["seconds"].get<double>(), 1)
           << " |\n";
    }
    return md.str();
}

std::string sweep_table(const Results& results) {
    std::ostringstream md;
    md << "### Lightness sweep on Tsukuba (right image), bad > 1 % nonocc; ASW rows use the "
          "separable variant (speed)\n\n| method |";
    for (const double p : sweep_steps()) {
        md << ' ' << (p > 0 ? "+" : "") << fmt(p, 0) << " % |";
    }
    md << " worst |\n|---|";
    for (std::size_t i = 0; i <= sweep_steps().size(); ++i) {
        md << "---|";
    }
    md << '\n';
    for (const Config* config : {&kSeparable, &kSeparableLcdm, &kSeparableCensus, &kSgbm}) {
        md << "| " << (config == &kSgbm ? "OpenCV SGBM" : "ASW " + config->name) << " |";
        double worst = 0.0;
        for (const double p : sweep_steps()) {
            const json& entry = results.at("sweep " + fmt(p, 0), "tsukuba", config->name);
            worst = std::max(worst, entry["bad_nonocc"].get<double>());
            md << ' ' << fmt(entry["bad_nonocc"].get<double>()) << " |";
        }
        md << ' ' << fmt(worst) << " |\n";
    }
    return md.str();
}

std::string speed_table(const Results& results, const std::string& scene) {
    std::ostringstream md;
    md << "### Speed on " << scene << " (wall time, one run each)\n\n"
       << "| method | threads | seconds | ratio to SGBM (1 thread) |\n|---|---|---|---|\n";
    const double sgbm = results.at("speed", scene, kSgbmSingle.name)["seconds"].get<double>();
    const auto row = [&](const std::string& label, const std::string& threads, const json& e) {
        const double seconds = e["seconds"].get<double>();
        md << "| " << label << " | " << threads << " | " << fmt(seconds, 3) << " | "
           << fmt(seconds / sgbm, 1) << "x |\n";
    };
    const std::string all = std::to_string(std::thread::hardware_concurrency());
    row("full ASW", all, results.at("pairs", scene, kFull.name));
    row("full ASW", "1", results.at("speed", scene, kFullSingle.name));
    row("separable ASW", all, results.at("pairs", scene, kSeparable.name));
    row("separable ASW", "1", results.at("speed", scene, kSeparableSingle.name));
    row("OpenCV SGBM", "1", results.at("speed", scene, kSgbmSingle.name));
    return md.str();
}

// ---- the run -----------------------------------------------------------------------------

io::SceneData relit(const io::SceneData& data, double percent) {
    io::SceneData out = data;
    io::Lighting lighting;
    lighting.lightness_percent = percent;
    out.right_bgr = io::relight(data.right_bgr, lighting);
    out.pair.right = io::to_image(out.right_bgr, "right (relit)");
    return out;
}

// "tsukuba", "reindeer", "aloe-half": the scene's name as a file name.
std::string figure_stem(const io::SceneData& data) {
    std::string stem;
    for (const char c : data.scene.name) {
        if (std::isalnum(static_cast<unsigned char>(c)) != 0) {
            stem += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        } else if (!stem.empty() && stem.back() != '-') {
            stem += '-';
        }
    }
    while (!stem.empty() && stem.back() == '-') {
        stem.pop_back();
    }
    return stem;
}

std::string figure_png(const io::SceneData& data, const cv::Mat& ours, const fs::path& path) {
    // The figures' convention is 0 = invalid: a valid 0 (the winner at the left border, where
    // no match exists) becomes a tiny disparity so that it shows as wrong, not as invalid.
    cv::Mat zero_invalid = ours.clone();
    zero_invalid.setTo(1e-3F, zero_invalid == 0.0F);
    zero_invalid.setTo(0.0F, zero_invalid != zero_invalid);
    cv::Mat strip = io::scene_strip(data, zero_invalid, "ours (ASW, AD)");
    std::string png = io::encode_png(strip, path);
    while (png.size() > kMaxFigureBytes && strip.cols > 100) {
        cv::resize(strip, strip, cv::Size(), 0.8, 0.8, cv::INTER_AREA);
        png = io::encode_png(strip, path);
    }
    return png;
}

void run_asw_eval(const AswEvalOptions& options) {
    check_report_outputs({options.markdown, options.json_path}, {options.figures},
                         options.data_dir);
    std::vector<io::SceneData> scenes = load_ground_truth_scenes(options.data_dir);
    if (options.quick) {
        std::erase_if(scenes, [](const io::SceneData& data) {
            return data.scene.name != "tsukuba" && data.scene.name != "venus";
        });
    }
    const auto tsukuba = std::find_if(scenes.begin(), scenes.end(), [](const io::SceneData& d) {
        return d.scene.name == "tsukuba";
    });
    if (tsukuba == scenes.end()) {
        throw std::runtime_error("no Middlebury 2003 Tsukuba under '" + options.data_dir + "'");
    }
    Results results;
    OutputFiles files;

    for (const Config& config : ablation_configs(tsukuba->scene.ndisp)) {
        results.add("ablation", *tsukuba, config, run(*tsukuba, config));
    }
    std::string speed_scene;
    for (const io::SceneData& data : masked_pairs(scenes)) {
        const Run full = run(data, kFull);
        results.add("pairs", data, kFull, full);
        for (const Config* config : {&kSeparable, &kLcdm, &kCensus, &kSeparableCensus, &kSgbm}) {
            results.add("pairs", data, *config, run(data, *config));
        }
        if (!options.figures.empty()) {
            const fs::path path = fs::path(options.figures) / (figure_stem(data) + ".png");
            files.emplace_back(path, figure_png(data, full.disparity, path));
        }
        // Speed: Teddy, or the last 2003 pair with --quick.
        if (speed_scene != "teddy") {
            speed_scene = data.scene.name;
        }
    }
    for (const io::SceneData& data : scenes) {
        if (speed_scene == data.scene.name) {
            for (const Config* config : {&kFullSingle, &kSeparableSingle, &kSgbmSingle}) {
                results.add("speed", data, *config, run(data, *config));
            }
        }
    }
    for (const io::SceneData& data : held_out_scenes(scenes)) {
        std::cerr << "asw-eval: held-out, " << data.scene.name << " (" << data.pair.left.width
                  << "x" << data.pair.left.height << ", ndisp " << data.scene.ndisp
                  << "): the full ASW may take minutes\n";
        for (const Config* config :
             {&kFull, &kSeparable, &kLcdm, &kCensus, &kSeparableCensus, &kSgbm}) {
            const Run out = run(data, *config);
            results.add("held-out", data, *config, out);
            if (config == &kFull && !options.figures.empty()) {
                // No masks: the error map's "all" is every known pixel, as the score's.
                io::SceneData masked = data;
                masked.all = {data.ground_truth.mat > 0.0F, "known"};
                const fs::path path = fs::path(options.figures) / (figure_stem(data) + ".png");
                files.emplace_back(path, figure_png(masked, out.disparity, path));
            }
        }
    }
    for (const double p : sweep_steps()) {
        const io::SceneData data = relit(*tsukuba, p);
        for (const Config* config : {&kSeparable, &kSeparableLcdm, &kSeparableCensus, &kSgbm}) {
            results.add("sweep " + fmt(p, 0), data, *config, run(data, *config),
                        {{"lightness_percent", p}});
        }
    }

    std::ostringstream md;
    md << "<!-- Generated by `stereo_experiments asw-eval" << (options.quick ? " --quick" : "")
       << "` (docs/results-asw-tables.md: `--markdown docs/results-asw-tables.md --json "
          "docs/figures/asw/results.json --figures docs/figures/asw`); do not edit. -->\n\n"
       << ablation_table(results, tsukuba->scene.ndisp) << '\n'
       << presented_table(results, scenes) << '\n'
       << lcdm_table(results, scenes) << '\n'
       << census_table(results, scenes) << '\n';
    if (!held_out_scenes(scenes).empty()) {
        md << held_out_table(results, scenes) << '\n';
    }
    md << sweep_table(results) << '\n' << speed_table(results, speed_scene);
    const json report = {{"quick", options.quick},
                         {"hardware_threads", std::thread::hardware_concurrency()},
                         {"runs", results.runs()}};
    print_and_write_report(std::move(files), options.markdown, md.str(), options.json_path, report);
}

}  // namespace

void add_asw_eval_command(CLI::App& app) {
    const auto [command, options] = cli::add_report_command<AswEvalOptions>(app, run_asw_eval);
    command->add_option("--figures", options->figures,
                        "Write one strip per 2003 pair into this existing folder");
    command->add_flag("--quick", options->quick, "Tsukuba and Venus only (a smoke test)");
}

}  // namespace stereo::experiments
