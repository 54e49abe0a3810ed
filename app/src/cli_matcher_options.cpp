#include "cli_matcher_options.hpp"

#include <stdexcept>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cli_command.hpp"
#include "stereo/catalogue.hpp"
#include "stereo/defaults.hpp"
#include "stereo/hls/match.hpp"
#ifdef STEREO_WITH_RTL
#include "stereo_top_sim.hpp"
#endif

namespace stereo::cli {

const MatcherRegistry& matchers() {
    static const MatcherRegistry registry = [] {
        MatcherRegistry r;
        register_model_matchers(r);
        hls::register_matchers(r);
#ifdef STEREO_WITH_RTL
        sim::register_matchers(r);
#else
        // Listed, so that --engine rtl explains itself instead of failing as an unknown name.
        for (const catalogue::Method method :
             {catalogue::Method::pipeline, catalogue::Method::hierarchical}) {
            r.add({std::string(catalogue::method(method).name), "rtl",
                   "the Verilated RTL (not built)",
                   [](const MatchConfig&) -> std::unique_ptr<Matcher> {
                       throw std::invalid_argument(
                           "engine rtl: this stereo was built without the RTL "
                           "(-DSTEREO_WITH_RTL=OFF); rebuild with Verilator to co-simulate");
                   }});
        }
#endif
        return r;
    }();
    return registry;
}

std::optional<bool> MatcherOptions::subpixel_given() const {
    if (subpixel_option == nullptr || subpixel_option->count() == 0) {
        return std::nullopt;
    }
    return subpixel;
}

std::string MatcherOptions::resolved_method() const {
    if (aggregation == "asw") {
        const catalogue::Method chosen = catalogue::method(method).id;
        if (chosen != catalogue::Method::pipeline && chosen != catalogue::Method::asw) {
            throw std::invalid_argument("--aggregation asw runs only with --method pipeline");
        }
        if (frontend != "model") {
            throw std::invalid_argument("--aggregation asw and --frontend " + frontend +
                                        " contradict");
        }
        return "asw";
    }
    if (frontend == "model") {
        return method;
    }
    if (catalogue::method(method).id != catalogue::Method::pipeline) {
        throw std::invalid_argument("--frontend " + frontend + " runs only with --method pipeline");
    }
    return frontend;  // "edges"
}

std::string MatcherOptions::resolved_engine() const {
    if (!engine.empty()) {
        return engine;
    }
    const std::string chosen = resolved_method();
    for (const auto& entry : matchers().entries()) {
        if (entry.method == chosen && entry.engine == catalogue::kDefaultEngine) {
            return entry.engine;
        }
    }
    return std::string(catalogue::kReferenceEngine);
}

namespace {

// "ad (absolute differences ...), census (...), ...": every cost with its summary, the default
// named, for --cost's help.
std::string cost_help(bool defaults_per_cost) {
    std::string text = "Matching cost: " + catalogue::cost_help();
    if (defaults_per_cost) {
        text += ". Default: " + std::string(defaults::kCost) + " for the methods " +
                "with stage 6 where the engine has it, else " +
                std::string(defaults::kFallbackCost) +
                "; the --uniqueness and --lr-check defaults follow the cost (docs/results.md)";
    }
    return text;
}

}  // namespace

MatchConfig MatcherOptions::resolved() const {
    MatchConfig resolved_config = config;
    resolved_config.pipeline.use_ca = !no_ca;
    // The options given, applied by the rule every interface shares (defaults::apply): where the
    // subcommand has per-cost defaults, the cost (--cost, else the method's default on this
    // engine) brings its ratio and tolerance first; the given ones win.
    defaults::Overrides overrides = given;
    if (defaults_per_cost && !overrides.cost) {
        overrides.cost = std::string(catalogue::default_cost(resolved_method(), resolved_engine()));
    } else if (!defaults_per_cost && overrides.cost) {
        resolved_config.pipeline.cost = *overrides.cost;  // no per-cost ratio and tolerance
        overrides.cost.reset();
    }
    overrides.validation = !no_validation;
    overrides.subpixel = subpixel_given();
    defaults::apply(overrides, resolved_config);
    asw::Params& weights = resolved_config.asw;
    if (window_set) {
        weights.diameter = config.pipeline.window;
    }
    weights.response = asw::response_from_name(asw_response);
    weights.shape = asw::shape_from_name(asw_shape);
    weights.continuity = weights.continuity && !asw_no_continuity;
    weights.right_weights = weights.right_weights && !asw_left_weights_only;
    weights.threads = config.threads;  // one --threads for ASW and the fast engine
    return resolved_config;
}

namespace {

// " [by cost: census 0, ad 6, ...]": a stage-6 value's default for each cost of the catalogue.
template <class Field>
std::string by_cost(Field field) {
    std::string text = " [by cost:";
    for (const catalogue::CostRow& row : catalogue::kCosts) {
        text += " " + std::string(row.name) + " " + std::to_string(field(row.validation)) + ",";
    }
    text.back() = ']';
    return text;
}

// Puts every option of `command` from the `first`-th on under the --help heading `group`.
void group_options_since(CLI::App& command, std::size_t first, const std::string& group) {
    const std::vector<CLI::Option*> all = command.get_options();
    for (std::size_t i = first; i < all.size(); ++i) {
        all[i]->group(group);
    }
}

// An option whose default follows another one (the cost brings its own ratio and tolerance,
// resolved()): it holds a value only when given; --help shows the subcommand's default.
void add_given(CLI::App& command, const char* name, std::optional<int>& value,
               const std::string& help, int shown_default) {
    command.add_option(name, value, help)->default_str(std::to_string(shown_default));
}

// Stage 6's options (--min-disp, --uniqueness, --lr-check, --subpixel, --no-validation) and the
// speckle filter's, where the subcommand exposes them, with their defaults.
void add_validation_options(CLI::App& command, MatcherOptions& options, MatcherChoice choice,
                            ExposedParams exposed) {
    MatchParams& params = options.config.pipeline;
    // Under their own --help heading, which names the methods that have them (the catalogue's).
    const std::size_t first = command.get_options().size();
    if (exposed.validation) {
        ValidationParams& v = params.validation;
        if (exposed.validation_on_by_default) {
            v = ValidationParams::all_on();
            if ((exposed.speckle && choice == MatcherChoice::selectable) || exposed.default_cost) {
                // The one default run (defaults::match_config): its cost and stage 6; resolved()
                // applies another cost's ratio and tolerance when --cost or the method changes it.
                options.defaults_per_cost = true;
                const MatchConfig standard = defaults::match_config();
                params.cost = standard.pipeline.cost;
                v = standard.pipeline.validation;
            } else if (exposed.speckle) {
                // The subcommand's cost (board: the AD core) with its ratio and tolerance.
                const defaults::Validation chosen = defaults::validation_for(params.cost);
                v.uniqueness_ratio = chosen.uniqueness;
                v.lr_tolerance = chosen.lr_tolerance;
            }
            add_switch(command, "--no-validation", "--validation", options.no_validation,
                       "Output the plain winners: no uniqueness, left-right, sub-pixel or "
                       "speckle step (an explicit --uniqueness, --lr-check, --subpixel or "
                       "--speckle-size turns that step back on); --validation: every step");
        }
        command
            .add_option("--min-disp", params.min_disp,
                        "Smallest disparity searched (may be negative): labels cover "
                        "min-disp .. min-disp + ndisp - 1")
            ->capture_default_str();
        // Where the cost brings its own values, --help lists them for every cost.
        const auto with_costs = [&](std::string help, auto field) {
            return options.defaults_per_cost ? help + by_cost(field) : help;
        };
        const std::string uniqueness_help = with_costs(
            "Invalidate a pixel whose best cost is not U percent below every cost "
            "outside its neighbours (0..255)",
            [](const catalogue::Validation& d) { return d.uniqueness; });
        const std::string lr_help = with_costs(
            "Invalidate a pixel whose right-image winner differs by more than T "
            "labels (0..255)",
            [](const catalogue::Validation& d) { return d.lr_tolerance; });
        add_given(command, "--uniqueness", options.given.uniqueness, uniqueness_help.c_str(),
                  v.uniqueness_ratio);
        add_given(command, "--lr-check", options.given.lr_tolerance, lr_help.c_str(),
                  v.lr_tolerance);
        options.subpixel = v.subpixel;  // the cost's default, shown in --help (given: see below)
        options.subpixel_option = add_switch(
            command, "--subpixel", "--no-subpixel", options.subpixel,
            "Refine each disparity by the parabola through its neighbours' costs (1/16 pixel); "
            "--no-subpixel (or --subpixel=false): whole labels");
    }
    if (exposed.speckle) {
        speckle::Params& speckles = options.config.speckle;
        if (exposed.validation_on_by_default) {
            speckles = speckle::Params::defaults();
        }
        add_given(command, "--speckle-size", options.given.speckle_size,
                  "Invalidate every region of at most N connected valid pixels (neighbours "
                  "within --speckle-range), after stage 6; 0: off",
                  speckles.max_size);
        command
            .add_option("--speckle-range", speckles.range,
                        "Largest disparity step, in pixels, inside one speckle region")
            ->capture_default_str();
    }
    const std::string methods = catalogue::join(
        catalogue::method_names([](const catalogue::MethodRow& row) { return row.stage6; }));
    group_options_since(
        command, first,
        std::string(exposed.speckle ? "Stage 6 and the speckle filter" : "Stage 6") + " (methods " +
            methods + ")");
}

// --cost, --method, --engine, --frontend, --aggregation and ASW's options: the subcommands that
// choose the matcher.
void add_selection_options(CLI::App& command, MatcherOptions& options) {
    MatchParams& params = options.config.pipeline;
    // An option whose value must be one of `choices`, its default shown in --help.
    const auto add_choice = [&command](const char* name, std::string& value, const char* help,
                                       const std::vector<std::string>& choices) {
        command.add_option(name, value, help)->check(CLI::IsMember(choices))->capture_default_str();
    };
    command.add_option("--cost", options.given.cost, cost_help(options.defaults_per_cost))
        ->check(CLI::IsMember(catalogue::cost_names()))
        ->default_str(params.cost);
    const std::string method_help = "Method: " + catalogue::method_help();
    add_choice("--method", options.method, method_help.c_str(), matchers().methods());
    const std::string engine_help =
        "Engine: " + catalogue::engine_help() +
        "; not every method has every engine. Default: " + std::string(catalogue::kDefaultEngine) +
        " where the method has it, else " + std::string(catalogue::kReferenceEngine);
    command.add_option("--engine", options.engine, engine_help)
        ->check(CLI::IsMember(matchers().engines()))
        ->default_str(std::string(catalogue::kDefaultEngine));
    add_choice("--frontend", options.frontend, "model, or edges (the same as --method edges)",
               {"model", "edges"});
    add_choice("--aggregation", options.aggregation,
               "gaussian (the Sec. 3.1 window and CA rules) or asw (adaptive support weights, "
               "Sec. 3.4: --window is the circle's diameter, 55 when not given; the same as "
               "--method asw)",
               {"gaussian", "asw"});
    command
        .add_option("--threads", options.config.threads,
                    "Worker threads of engine fast and of ASW, 0 = every core (the result does "
                    "not depend on it)")
        ->capture_default_str()
        ->check(thread_count());
    asw::Params& weights = options.config.asw;
    const std::size_t asw_first = command.get_options().size();
    add_switch(command, "--no-continuity", "--continuity", options.asw_no_continuity,
               "ASW: one pass, without the continuity (preliminary disparity) weight");
    add_choice("--response", options.asw_response,
               "ASW: log (Weber-Fechner, the thesis) or exp (Yoon-Kweon's exponentials)",
               {"log", "exp"});
    add_choice("--shape", options.asw_shape,
               "ASW: circle of diameter --window, or square of the same pixel count",
               {"circle", "square"});
    add_switch(command, "--separable", "--no-separable", weights.separable,
               "ASW: the hardware-friendly variant (a vertical then a horizontal 1-D pass)");
    add_switch(command, "--left-weights-only", "--both-weights", options.asw_left_weights_only,
               "ASW: colour similarity in the left image only; --both-weights: in the right too");
    command
        .add_option("--truncation", weights.truncation,
                    "ASW: the cost is min(C, T) before the aggregation; -1: by the cost "
                    "(Yoon and Kweon's 40, census not truncated), 0: not truncated")
        ->capture_default_str();
    group_options_since(
        command, asw_first,
        "--method asw: " + std::string(catalogue::method(catalogue::Method::asw).summary));
}

}  // namespace

void add_matcher_options(CLI::App& command, MatcherOptions& options, MatcherChoice choice,
                         ExposedParams exposed) {
    MatchParams& params = options.config.pipeline;
    if (exposed.ndisp) {
        command.add_option("--ndisp", params.ndisp, "Number of disparity labels 0..N-1")
            ->capture_default_str();
    }
    // Recorded when given: the board keeps its own window otherwise, and ASW's diameter has
    // its own default.
    command
        .add_option("--window", params.window,
                    "Odd aggregation window side (hierarchical: of its 1-D pass)")
        ->capture_default_str()
        ->each([&options](const std::string&) { options.window_set = true; });
    command.add_option("--sigma", params.sigma, "Gaussian sigma in pixels")
        ->capture_default_str()
        ->each([&options](const std::string&) { options.sigma_set = true; });
    if (exposed.no_ca) {
        add_switch(command, "--no-ca", "--ca", options.no_ca,
                   "Skip the cellular-automata rules; --ca: apply them");
    }
    add_validation_options(command, options, choice, exposed);
    if (choice == MatcherChoice::selectable) {
        add_selection_options(command, options);
    }
}

nlohmann::json pipeline_json(int width, int height, const MatchParams& params) {
    return {{"width", width},
            {"height", height},
            {"ndisp", params.ndisp},
            {"window", params.window},
            {"ca", params.use_ca},
            {"min_disp", params.min_disp},
            {"subpixel", params.validation.subpixel}};
}

}  // namespace stereo::cli
