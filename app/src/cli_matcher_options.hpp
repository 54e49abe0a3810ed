// The matcher options every subcommand that matches shares (--ndisp, --window, --sigma, --no-ca,
// --cost, and where the subcommand chooses the matcher, --method / --engine / --frontend), with
// one help text each, registered by one helper and resolved into a stereo::MatchConfig once.
#pragma once

#include <optional>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "stereo/defaults.hpp"
#include "stereo/matcher.hpp"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace stereo::cli {

// The registry of every engine the tool has: the model's, the HLS kernels', the Verilated RTL's.
const MatcherRegistry& matchers();

struct MatcherOptions {
    MatchConfig config;
    bool no_ca = false;
    std::string method = "pipeline";
    // Empty: catalogue::kDefaultEngine where the method has it, else kReferenceEngine
    // (resolved_engine()).
    std::string engine;
    std::string frontend = "model";        // "edges": the same as --method edges (kept for scripts)
    std::string aggregation = "gaussian";  // "asw": the same as --method asw
    std::string asw_response = "log";
    std::string asw_shape = "circle";
    bool asw_no_continuity = false;
    bool asw_left_weights_only = false;
    // The options whose defaults depend on other options (the cost brings its own stage-6 ratio
    // and tolerance): empty unless given on the command line, applied by resolved() through
    // defaults::apply, the rule every interface shares.
    defaults::Overrides given;
    // --window, --sigma given on the command line (recorded while parsing).
    bool window_set = false;
    bool sigma_set = false;
    // `stereo match`: the cost defaults to defaults::kCost where the method and engine have it
    // (else defaults::kFallbackCost), and stage 6's ratio and tolerance to that cost's defaults
    // (stereo/defaults.hpp), each unless given on the command line.
    bool defaults_per_cost = false;
    bool no_validation = false;
    // --subpixel / --no-subpixel (or --subpixel=false): the value, and the option, to tell a
    // given value from the default.
    bool subpixel = false;
    const CLI::Option* subpixel_option = nullptr;

    // The sub-pixel switch given on the command line, if any.
    std::optional<bool> subpixel_given() const;

    // The method after --frontend and --aggregation; throws std::invalid_argument when they
    // contradict.
    std::string resolved_method() const;
    // --engine when given, else the default engine of resolved_method().
    std::string resolved_engine() const;
    // --window or --sigma was given on the command line.
    bool window_given() const { return window_set || sigma_set; }
    // --uniqueness, --lr-check, --subpixel / --no-subpixel or --speckle-size was given on the
    // command line.
    bool explicit_validation() const {
        return given.uniqueness || given.lr_tolerance || subpixel_given() || given.speckle_size;
    }
    // The configuration with --no-ca, the stage 6 switches, the per-cost defaults and the ASW
    // options applied (with --aggregation asw, --window is the support region's diameter, 55
    // when not given).
    MatchConfig resolved() const;
};

// The frame size and the pipeline parameters a run used, as the --json summaries of board and
// cosim name them (each adds uniqueness and lr_check in its own form).
nlohmann::json pipeline_json(int width, int height, const MatchParams& params);

enum class MatcherChoice {
    fixed,      // the subcommand runs one matcher: only the pipeline parameters
    selectable  // also --method, --engine, --frontend, --cost
};

// The pipeline parameters a subcommand exposes besides --window and --sigma: middlebury takes
// ndisp from each scene, avoid (edges) and slam (sparse) run matchers without the CA rules.
struct ExposedParams {
    bool ndisp = true;
    bool no_ca = true;
    bool validation = false;  // --min-disp, --uniqueness, --lr-check, --subpixel (stage 6)
    // --speckle-size / --speckle-range: the host-side filter after stage 6 (not in the core, so
    // not for cosim; quad fuses maps the filter has not seen)
    bool speckle = false;
    // Stage 6 on unless --no-validation (stereo match); otherwise each option turns its step on.
    bool validation_on_by_default = false;
    // A fixed-matcher subcommand (cosim) whose --cost defaults to the catalogue's and whose
    // --uniqueness and --lr-check defaults follow the cost, as stereo match's do (the subcommand
    // registers its own --cost, bound to MatcherOptions::given.cost).
    bool default_cost = false;
};

// Registers the options on `command`. The defaults shown by --help are the values
// options.config holds when this is called, so a subcommand sets its own defaults first.
void add_matcher_options(CLI::App& command, MatcherOptions& options, MatcherChoice choice,
                         ExposedParams exposed = {});

}  // namespace stereo::cli
