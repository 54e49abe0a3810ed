// The matcher registry and the model's registrations (stereo/matcher.hpp).
#include <algorithm>
#include <mutex>
#include <stdexcept>
#include <utility>

#include "stereo/catalogue.hpp"
#include "stereo/defaults.hpp"
#include "stereo/fast_engine.hpp"
#include "stereo/hierarchical.hpp"
#include "stereo/hierarchical_reference.hpp"
#include "stereo/matcher.hpp"
#include "stereo/quad.hpp"
#include "stereo/reference.hpp"

namespace stereo {
namespace {

std::string joined(const std::vector<std::string>& names) {
    std::string text;
    for (const auto& name : names) {
        text += (text.empty() ? "" : ", ") + name;
    }
    return text;
}

void add_unique(std::vector<std::string>& names, const std::string& name) {
    if (std::find(names.begin(), names.end(), name) == names.end()) {
        names.push_back(name);
    }
}

// A matcher whose validated output goes through the speckle filter; methods without one (their
// `validated` is empty) pass unchanged.
class SpeckleFiltered final : public Matcher {
  public:
    SpeckleFiltered(std::unique_ptr<Matcher> inner, speckle::Params params)
        : inner_(std::move(inner)), params_(params) {}
    void validate(int width, int height) const override { inner_->validate(width, height); }
    MatchResult compute(const Image& left, const Image& right) const override {
        MatchResult result = inner_->compute(left, right);
        if (!result.validated.fixed.empty()) {
            const int removed = speckle::filter(result.validated, params_);
            result.disparity = to_label_map(result.validated);
            result.counts.emplace_back("speckle", removed);
        }
        return result;
    }

  private:
    std::unique_ptr<Matcher> inner_;
    speckle::Params params_;
};

// ---- pipeline: the 1-D Sec. 3.1 matcher ------------------------------------------------------

// The model's pipeline: kernel and cost built once, when the matcher is made (a bad window,
// sigma or cost fails there, before any image is read).
class ModelPipeline final : public Matcher {
  public:
    explicit ModelPipeline(const MatchParams& params)
        : params_(params),
          kernel_(gaussian_kernel(params.window, params.sigma)),
          cost_(make_cost(params.cost)) {
        validate_params(params);
    }
    void validate(int width, int height) const override { validate_size(params_, width, height); }
    MatchResult compute(const Image& left, const Image& right) const override {
        MatchResult result;
        result.validated = match_validated_with(*cost_, kernel_, left, right, params_);
        result.disparity = to_label_map(result.validated);
        return result;
    }

  private:
    MatchParams params_;
    std::vector<std::int32_t> kernel_;
    std::unique_ptr<CostFunction> cost_;
};

// The fast CPU engine of the same pipeline (stereo/fast_engine.hpp): one engine, its buffers
// reused from frame to frame; calls on one matcher take turns.
class FastPipeline final : public Matcher {
  public:
    FastPipeline(const MatchParams& params, int threads)
        : engine_(params, fast::thread_count(threads)) {}
    void validate(int width, int height) const override { engine_.validate(width, height); }
    MatchResult compute(const Image& left, const Image& right) const override {
        MatchResult result;
        {
            const std::lock_guard lock(mutex_);
            engine_.match(left, right, result.validated);
        }
        result.disparity = to_label_map(result.validated);
        return result;
    }

  private:
    mutable std::mutex mutex_;
    mutable fast::Engine engine_;
};

// ---- edges: the obstacle-avoidance front end (Sec. 4.1.1) --------------------------------

using EdgeFunction = DisparityMap (*)(const Image&, const Image&, const MatchParams&,
                                      const edge_frontend::EdgeParams&);

MatcherFactory edges_factory(EdgeFunction run) {
    return [run](const MatchConfig& config) -> std::unique_ptr<Matcher> {
        MatchParams params = config.pipeline;
        params.use_ca = false;  // the front end has no CA stage
        const edge_frontend::EdgeParams edges = config.edges;
        if (catalogue::cost(params.cost).id != catalogue::Cost::ad) {
            throw std::invalid_argument("the edge front end has its own cost (truncated AD)");
        }
        return std::make_unique<FunctionMatcher>(
            [params, edges](int width, int height) {
                validate(params, width, height);
                edge_frontend::validate(edges);
            },
            [params, edges, run](const Image& left, const Image& right) {
                return MatchResult{run(left, right, params, edges), {}, {}, {}, {}, {}};
            });
    };
}

// ---- hierarchical: the 2-D search for uncalibrated pairs (Sec. 3.3) ---------------------

MatchResult to_match_result(hierarchical::Result result) {
    MatchResult out{std::move(result.disparity), {}, std::move(result.vertical), {}, {},
                    std::move(result.validated)};
    for (std::size_t l = 0; l < result.levels.size(); ++l) {
        if (!result.levels[l].valid.empty()) {
            out.levels.push_back(std::move(result.levels[l]));
        }
        out.counts.emplace_back(std::string("cost_evaluations.") + hierarchical::kLevelNames[l],
                                result.cost_evaluations.level[l]);
    }
    out.counts.emplace_back("cost_evaluations.field_pass", result.cost_evaluations.field_pass);
    return out;
}

// ---- sparse: validated sub-pixel disparities (the SLAM front end, Sec. 4.2.1) ---------------
// The pipeline without CA and with every stage-6 check (sparse::stage6_params); the result keeps
// stage 6's full output and adds the sub-pixel disparities and the reason counts.

std::unique_ptr<Matcher> make_sparse(const MatchConfig& config) {
    const MatchParams params = config.pipeline;
    const sparse::Params checks = config.sparse;
    return std::make_unique<FunctionMatcher>(
        [params, checks](int width, int height) {
            sparse::validate(params, checks, width, height);
        },
        [params, checks](const Image& left, const Image& right) {
            check_pair(left, right);
            sparse::validate(params, checks, left.width, left.height);
            ValidatedDisparity validated =
                match_validated(left, right, sparse::stage6_params(params, checks));
            sparse::ValidationCounts counts;
            const sparse::SparseDisparity map = sparse::from_validated(validated, &counts);
            MatchResult result{to_label_map(validated), map.disparity, {}, {}, {}, {}};
            result.validated = std::move(validated);
            result.counts = {{"candidates", static_cast<std::int64_t>(counts.candidates)},
                             {"uncertain", static_cast<std::int64_t>(counts.uncertain)},
                             {"inconsistent", static_cast<std::int64_t>(counts.inconsistent)},
                             {"valid", static_cast<std::int64_t>(counts.valid)}};
            return result;
        });
}

// validate_params, and an engine without the minimum-disparity and validation stages (`engine`
// names it in the message) refuses parameters that need them.
void validate_plain_params(const MatchParams& params, const std::string& engine) {
    validate_params(params);
    // Only the switches count: the ratio or tolerance of a step that is off is never read.
    const ValidationParams& v = params.validation;
    if (params.min_disp != 0 || v.uniqueness || v.left_right || v.subpixel) {
        throw std::invalid_argument(engine +
                                    " has no minimum disparity or validation stages (use "
                                    "--no-validation, or --engine model or naive)");
    }
}

// ASW's matching parameters: the pipeline's cost, min_disp and stage 6 with the ASW aggregator
// instead of the Gaussian window and the CA rules (pipeline.window, sigma and use_ca not read).
MatchParams asw_checked(MatchParams params) {
    params.window = 1;
    params.use_ca = false;
    return params;
}

}  // namespace

hierarchical::Params hierarchical_params(const MatchConfig& config) {
    hierarchical::Params params;
    params.cost = config.pipeline.cost;
    params.ndisp = config.pipeline.ndisp;
    params.vrange = config.vrange;
    params.use_ca = config.pipeline.use_ca;
    params.neighbours = config.neighbours;
    params.output = config.hierarchical_output;
    params.field_model = config.field_model;
    params.field_radius = config.field_radius;
    for (std::size_t l = 0; l < hierarchical::kLevels; ++l) {
        params.levels[l] = hierarchical::default_level(config.level_windows[l]);
    }
    params.field_level = {config.pipeline.window, config.pipeline.sigma};
    params.validation = config.pipeline.validation;
    return params;
}

MatcherFactory pipeline_factory(PipelineFunction run) {
    return [run](const MatchConfig& config) -> std::unique_ptr<Matcher> {
        const MatchParams params = config.pipeline;
        validate_plain_params(params, "this engine");
        return std::make_unique<FunctionMatcher>(
            [params](int width, int height) { validate(params, width, height); },
            [params, run](const Image& left, const Image& right) {
                return MatchResult{run(left, right, params), {}, {}, {}, {}, {}};
            });
    };
}

MatcherFactory pipeline_factory(ValidatedPipelineFunction run) {
    return [run](const MatchConfig& config) -> std::unique_ptr<Matcher> {
        const MatchParams params = config.pipeline;
        validate_params(params);
        return std::make_unique<FunctionMatcher>(
            [params](int width, int height) { validate(params, width, height); },
            [params, run](const Image& left, const Image& right) {
                MatchResult result;
                result.validated = run(left, right, params);
                result.disparity = to_label_map(result.validated);
                return result;
            });
    };
}

MatcherFactory asw_factory(AswFunction run) {
    return [run](const MatchConfig& config) -> std::unique_ptr<Matcher> {
        const MatchParams params = asw_checked(config.pipeline);
        const asw::Params weights = config.asw;
        validate_params(params);
        return std::make_unique<FunctionMatcher>(
            [params, weights](int width, int height) {
                validate(params, width, height);
                asw::validate(weights, width, height);
            },
            [params, weights, run](const Image& left, const Image& right) {
                MatchResult result;
                result.validated = run(left, right, params, weights);
                result.disparity = to_label_map(result.validated);
                return result;
            });
    };
}

MatcherFactory hierarchical_factory(HierarchicalFunction run, HierarchicalCheck check) {
    return [run, check](const MatchConfig& config) -> std::unique_ptr<Matcher> {
        const hierarchical::Params params = hierarchical_params(config);
        const auto validate_size = [params, check](int width, int height) {
            hierarchical::validate(params, width, height);
            if (check != nullptr) {
                check(params, width, height);
            }
        };
        return std::make_unique<FunctionMatcher>(
            validate_size, [params, run, check](const Image& left, const Image& right) {
                if (check != nullptr) {  // `run` validates the rest itself
                    check(params, left.width, left.height);
                }
                return to_match_result(run(left, right, params));
            });
    };
}

namespace {

// A factory for one quad-camera pair geometry (stereo/quad.hpp): `left` is the reference,
// `right` the partner below (vertical) or below-right (diagonal).
using PairFunction = ValidatedDisparity (*)(quad::Pair, const Image&, const Image&,
                                            const MatchParams&);
MatcherFactory quad_pair_factory(quad::Pair pair, PairFunction run) {
    return [pair, run](const MatchConfig& config) -> std::unique_ptr<Matcher> {
        const MatchParams params = config.pipeline;
        validate_params(params);
        return std::make_unique<FunctionMatcher>(
            [pair, params](int width, int height) {
                quad::validate_pair(pair, params, width, height);
            },
            [pair, params, run](const Image& left, const Image& right) {
                MatchResult result;
                result.validated = run(pair, left, right, params);
                result.disparity = to_label_map(result.validated);
                return result;
            });
    };
}

// ---- asw: adaptive support weights (Sec. 3.4) --------------------------------------------
// The pipeline's cost, min_disp and stage 6 with the ASW aggregator instead of the Gaussian
// window and the CA rules (asw_checked).
MatcherFactory asw_floating_factory() {
    return [](const MatchConfig& config) -> std::unique_ptr<Matcher> {
        const MatchParams params = asw_checked(config.pipeline);
        const asw::Params weights = config.asw;
        validate_plain_params(params, "engine float of asw");
        return std::make_unique<FunctionMatcher>(
            [params, weights](int width, int height) {
                validate(params, width, height);
                asw::validate(weights, width, height);
            },
            [params, weights](const Image& left, const Image& right) {
                return MatchResult{
                    asw::match_floating(left, right, params, weights), {}, {}, {}, {}, {}};
            });
    };
}

}  // namespace

void MatcherRegistry::add(MatcherEntry entry) {
    // Every method and engine has its catalogue row (throws std::invalid_argument otherwise).
    try {
        catalogue::method(entry.method);
        catalogue::engine(entry.engine);
    } catch (const std::invalid_argument& error) {
        throw std::logic_error("matcher " + entry.method + "/" + entry.engine +
                               " is not in the catalogue: " + error.what());
    }
    for (const auto& existing : entries_) {
        if (existing.method == entry.method && existing.engine == entry.engine) {
            throw std::logic_error("matcher " + entry.method + "/" + entry.engine +
                                   " registered twice");
        }
    }
    entries_.push_back(std::move(entry));
}

std::unique_ptr<Matcher> MatcherRegistry::create(std::string_view method, std::string_view engine,
                                                 const MatchConfig& config) const {
    std::vector<std::string> engines_of_method;
    for (const auto& entry : entries_) {
        if (entry.method == method) {
            if (entry.engine == engine) {
                speckle::validate(config.speckle);
                std::unique_ptr<Matcher> matcher = entry.create(config);
                if (config.speckle.enabled()) {
                    return std::make_unique<SpeckleFiltered>(std::move(matcher), config.speckle);
                }
                return matcher;
            }
            engines_of_method.push_back(entry.engine);
        }
    }
    if (engines_of_method.empty()) {
        throw std::invalid_argument("unknown method \"" + std::string(method) +
                                    "\" (methods: " + joined(methods()) + ")");
    }
    throw std::invalid_argument("method " + std::string(method) + " has no engine \"" +
                                std::string(engine) + "\" (engines: " + joined(engines_of_method) +
                                ")");
}

std::vector<std::string> MatcherRegistry::methods() const {
    std::vector<std::string> names;
    for (const auto& entry : entries_) {
        add_unique(names, entry.method);
    }
    return names;
}

std::vector<std::string> MatcherRegistry::engines() const {
    std::vector<std::string> names;
    for (const auto& entry : entries_) {
        add_unique(names, entry.engine);
    }
    return names;
}

void register_model_matchers(MatcherRegistry& registry) {
    registry.add({"pipeline", "model", "Sec. 3.1 pipeline, the bit-exact golden model",
                  [](const MatchConfig& config) -> std::unique_ptr<Matcher> {
                      return std::make_unique<ModelPipeline>(config.pipeline);
                  }});
    registry.add({"pipeline", "fast", "Sec. 3.1 pipeline, fast CPU engine (row tiles, threads)",
                  [](const MatchConfig& config) -> std::unique_ptr<Matcher> {
                      return std::make_unique<FastPipeline>(config.pipeline, config.threads);
                  }});
    registry.add({"pipeline", "naive", "Sec. 3.1 pipeline, naive reference (direct sums)",
                  pipeline_factory(&naive::match_validated)});
    registry.add({"pipeline", "float", "Sec. 3.1 pipeline in double precision",
                  pipeline_factory(&floating::match)});
    registry.add({"edges", "model", "LoG edge front end with truncated AD, no CA (Sec. 4.1.1)",
                  edges_factory(&edge_frontend::match)});
    registry.add({"edges", "naive", "edge front end, naive reference",
                  edges_factory(&edge_frontend::naive::match)});
    registry.add({"hierarchical", "model", "three-level 2-D search (Sec. 3.3)",
                  hierarchical_factory(&hierarchical::match)});
    registry.add({"hierarchical", "naive", "2-D search, naive reference",
                  hierarchical_factory(&hierarchical::naive::match)});
    registry.add({"hierarchical", "full-search", "every D x V displacement at full size",
                  hierarchical_factory(&hierarchical::full_search)});
    registry.add(
        {"sparse", "model", "validated sub-pixel disparities (SLAM front end)", &make_sparse});
    for (const quad::Pair pair : {quad::Pair::vertical, quad::Pair::diagonal}) {
        const std::string method(quad::name(pair));
        registry.add({method, "model",
                      "Sec. 3.2 " + method + " pair (partner below" +
                          (pair == quad::Pair::diagonal ? "-right" : "") + ")",
                      quad_pair_factory(pair, &quad::match_pair)});
        registry.add({method, "naive", method + " pair, naive reference",
                      quad_pair_factory(pair, &quad::naive::match_pair)});
    }
    registry.add({"asw", "model", "Sec. 3.4 adaptive support weights (gestalt, log response)",
                  asw_factory(&asw::match)});
    registry.add({"asw", "naive", "adaptive support weights, naive reference",
                  asw_factory(&asw::match_naive)});
    registry.add(
        {"asw", "float", "adaptive support weights in double precision", asw_floating_factory()});
}

void defaults::apply(const Overrides& overrides, MatchConfig& config) {
    MatchParams& params = config.pipeline;
    ValidationParams& v = params.validation;
    if (overrides.cost) {
        params.cost = *overrides.cost;
        const Validation chosen = validation_for(params.cost);
        v.uniqueness_ratio = chosen.uniqueness;
        v.lr_tolerance = chosen.lr_tolerance;
    }
    if (!overrides.validation) {
        v.uniqueness = v.left_right = v.subpixel = false;
        config.speckle.max_size = 0;
    }
    if (overrides.uniqueness) {
        v.uniqueness = true;
        v.uniqueness_ratio = *overrides.uniqueness;
    }
    if (overrides.lr_tolerance) {
        v.left_right = true;
        v.lr_tolerance = *overrides.lr_tolerance;
    }
    v.subpixel = overrides.subpixel.value_or(v.subpixel);
    config.speckle.max_size = overrides.speckle_size.value_or(config.speckle.max_size);
    config.speckle.range = overrides.speckle_range.value_or(config.speckle.range);
}

MatchConfig defaults::match_config(std::string_view method, std::string_view engine) {
    const catalogue::MethodRow& row = catalogue::method(method);
    const catalogue::EngineRow& runner = catalogue::engine(engine);
    MatchConfig config;
    MatchParams& params = config.pipeline;
    params.cost = std::string(catalogue::default_cost(method, engine));
    if (row.stage6 && runner.stage6) {
        const Validation chosen = validation_for(params.cost);
        params.validation = ValidationParams::all_on();
        params.validation.uniqueness_ratio = chosen.uniqueness;
        params.validation.lr_tolerance = chosen.lr_tolerance;
        config.speckle = speckle::Params::defaults();
    }
    return config;
}

}  // namespace stereo
