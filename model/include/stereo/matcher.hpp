// One interface for every matcher, in the spirit of OpenCV's StereoMatcher: a Matcher is built
// from a configuration by a registry entry (method x engine) and turns a stereo pair into a
// result. The CLI, the robot layers, the benchmarks and the tests all go through it;
// docs/architecture.md lists what is registered and how to add an engine.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "stereo/asw.hpp"
#include "stereo/edge_frontend.hpp"
#include "stereo/hierarchical.hpp"
#include "stereo/image.hpp"
#include "stereo/pipeline.hpp"
#include "stereo/search.hpp"
#include "stereo/sparse.hpp"
#include "stereo/speckle.hpp"

namespace stereo {

// Everything a matcher may be asked. A method reads the fields it documents and ignores the rest.
struct MatchConfig {
    MatchParams pipeline;  // ndisp, window, sigma, CA on/off, cost (every method)
    // hierarchical: vertical labels (0 = ndisp), CA rule 1's axes, and the output: the vertical
    // field and the 1-D pass with stage 6 (config.pipeline.validation), or the thesis' full level.
    int vrange = hierarchical::kDefaultVerticalRange;
    CaNeighbours neighbours = CaNeighbours::horizontal;
    hierarchical::Output hierarchical_output = hierarchical::kDefaultOutput;
    hierarchical::FieldModel field_model = hierarchical::kDefaultFieldModel;
    int field_radius = hierarchical::kDefaultFieldRadius;
    std::array<int, 3> level_windows = hierarchical::kDefaultLevelWindows;  // sigma 3 N / 11
    edge_frontend::EdgeParams edges;  // edges: LoG and truncation
    sparse::Params sparse;            // sparse: stage 6 uniqueness ratio and left-right tolerance
    asw::Params asw;                  // asw: support region, responses, ablation switches
    // Every method with a validated output (pipeline, asw, quad pairs), every engine: the
    // host-side speckle filter after stage 6 (MatcherRegistry::create applies it). Off here.
    speckle::Params speckle;
    // Engine fast (stereo/fast_engine.hpp): worker threads, 0 = every core (the result does not
    // depend on it).
    int threads = 0;
};

struct MatchResult {
    DisparityMap disparity;  // labels with the valid flag, every method
    // Sub-pixel disparities, sparse::kNoDisparity where invalid (sparse method); else empty.
    std::vector<float> subpixel;
    // 2-D methods: the vertical offset v of every valid pixel (right row y + v), 0 elsewhere.
    std::vector<std::int8_t> vertical;
    // Hierarchical: the winners of each level, quarter to full (full search: one level).
    std::vector<Winners> levels;
    // Named counts for reports: DSI cells per level, validation outcomes, ...
    std::vector<std::pair<std::string, std::int64_t>> counts;
    // Pipeline: stage 6's full output (signed sub-pixel disparity x 16, invalid reason,
    // certainty), of which `disparity` is the 8-bit view; empty for the other methods.
    ValidatedDisparity validated;

    // The count named `name`, 0 when the matcher did not report it.
    std::int64_t count(std::string_view name) const {
        for (const auto& [key, value] : counts) {
            if (key == name) {
                return value;
            }
        }
        return 0;
    }
};

class Matcher {
  public:
    virtual ~Matcher() = default;
    // Throws std::invalid_argument (one line) when the configuration cannot run on a pair of
    // this size; cheap, so callers check before loading or computing anything big.
    virtual void validate(int width, int height) const = 0;
    // Throws std::invalid_argument for a pair that does not fit (sizes, channels, parameters).
    virtual MatchResult compute(const Image& left, const Image& right) const = 0;
};

using MatcherFactory = std::function<std::unique_ptr<Matcher>(const MatchConfig&)>;

struct MatcherEntry {
    std::string method;  // the algorithm: pipeline, edges, hierarchical, sparse, ...
    std::string engine;  // how it runs: model (bit-exact), naive, float, hls, rtl, ...
    std::string description;
    MatcherFactory create;
};

class MatcherRegistry {
  public:
    // Throws std::logic_error when (method, engine) is registered already.
    void add(MatcherEntry entry);
    // Throws std::invalid_argument naming what exists when (method, engine) does not, and for
    // impossible speckle parameters. With config.speckle on, the matcher's validated output
    // passes through speckle::filter (its label map and counts follow).
    std::unique_ptr<Matcher> create(std::string_view method, std::string_view engine,
                                    const MatchConfig& config) const;
    const std::vector<MatcherEntry>& entries() const { return entries_; }
    std::vector<std::string> methods() const;
    std::vector<std::string> engines() const;  // of every method

  private:
    std::vector<MatcherEntry> entries_;
};

// A Matcher from a function; validate() runs `check`.
class FunctionMatcher final : public Matcher {
  public:
    using Check = std::function<void(int, int)>;
    using Compute = std::function<MatchResult(const Image&, const Image&)>;
    FunctionMatcher(Check check, Compute compute)
        : check_(std::move(check)), compute_(std::move(compute)) {}
    void validate(int width, int height) const override { check_(width, height); }
    MatchResult compute(const Image& left, const Image& right) const override {
        return compute_(left, right);
    }

  private:
    Check check_;
    Compute compute_;
};

// A factory for a pipeline engine: validates with stereo::validate, then runs `run`. An engine
// that returns only the 8-bit map refuses min_disp and the validation stages.
using PipelineFunction = DisparityMap (*)(const Image&, const Image&, const MatchParams&);
MatcherFactory pipeline_factory(PipelineFunction run);
using ValidatedPipelineFunction = ValidatedDisparity (*)(const Image&, const Image&,
                                                         const MatchParams&);
MatcherFactory pipeline_factory(ValidatedPipelineFunction run);
// A factory for an engine of method asw: the pipeline's cost, min_disp and stage 6 (its window,
// sigma and CA are not read) with the aggregator's parameters (MatchConfig::asw), both validated
// before `run`.
using AswFunction = ValidatedDisparity (*)(const Image&, const Image&, const MatchParams&,
                                           const asw::Params&);
MatcherFactory asw_factory(AswFunction run);

// The hierarchical search's parameters of a configuration (every engine of the method): the
// pipeline's cost, ndisp, CA and stage 6, the 2-D options, and the 1-D pass's window and sigma
// from the pipeline's (11x11, sigma 3 by default).
hierarchical::Params hierarchical_params(const MatchConfig& config);

// A factory for a hierarchical engine: validates with hierarchical::validate and `check` (an
// engine's own limits, may be null), then runs `run`; the result carries every level's winners
// and the cost evaluations.
using HierarchicalFunction = hierarchical::Result (*)(const Image&, const Image&,
                                                      const hierarchical::Params&);
using HierarchicalCheck = void (*)(const hierarchical::Params&, int width, int height);
MatcherFactory hierarchical_factory(HierarchicalFunction run, HierarchicalCheck check = nullptr);

// The model's matchers: pipeline (model, naive, float), edges (model, naive), hierarchical
// (model, naive, full-search), sparse (model), asw (model, naive, float).
void register_model_matchers(MatcherRegistry& registry);

}  // namespace stereo
