#include "stereo/pipeline.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "stereo/search.hpp"
#include "stereo/stages.hpp"
#include "stereo/stages/validate.hpp"

namespace stereo {
namespace {

std::string size_text(int width, int height) {
    return std::to_string(width) + "x" + std::to_string(height);
}

void check_kernel(const std::vector<std::int32_t>& kernel) {
    std::int64_t sum = 0;
    for (const auto tap : kernel) {
        if (tap < 0) {
            throw std::invalid_argument("kernel taps must be non-negative");
        }
        sum += tap;
    }
    if (kernel.empty() || kernel.size() % 2 == 0 || sum != fx::kKernelSum) {
        throw std::invalid_argument("kernel must have an odd number of taps summing to " +
                                    std::to_string(fx::kKernelSum));
    }
}

// Winners of a 1-D search become disparities where the border rule allows.
DisparityMap to_disparity_map(const Winners& winners, const InvalidBorder& border) {
    DisparityMap map(winners.width, winners.height);
    for (int y = 0; y < map.height; ++y) {
        for (int x = 0; x < map.width; ++x) {
            const std::size_t i = map.index(x, y);
            const int d = winners.disparity[i];
            if (border.valid(x, y, d, map.width, map.height)) {
                map.disparity[i] = static_cast<std::uint8_t>(d);
                map.valid[i] = 1;
            }
        }
    }
    return map;
}

}  // namespace

void check_pair(const Image& left, const Image& right) {
    if (left.empty() || right.empty()) {
        throw std::invalid_argument("left and right images must not be empty");
    }
    if (left.width != right.width || left.height != right.height) {
        throw std::invalid_argument("left image is " + size_text(left.width, left.height) +
                                    " but right image is " + size_text(right.width, right.height));
    }
    if (left.channels != right.channels) {
        throw std::invalid_argument("left image has " + std::to_string(left.channels) +
                                    " channel(s) but right image has " +
                                    std::to_string(right.channels));
    }
}

InvalidBorder invalid_border(const MatchParams& params) {
    // Aggregation reaches `radius` pixels out; the CA rules one pixel more (3x3).
    return {params.window / 2 + (params.use_ca ? 1 : 0)};
}

void validate(const MatchParams& params, int width, int height) {
    validate_params(params);
    validate_size(params, width, height);
}

void validate_params(const MatchParams& params) {
    if (params.ndisp < 1 || params.ndisp > fx::kMaxDisparities) {
        throw std::invalid_argument("ndisp must be in [1, " + std::to_string(fx::kMaxDisparities) +
                                    "], got " + std::to_string(params.ndisp));
    }
    if (params.min_disp < -fx::kMaxMinDisparity || params.min_disp > fx::kMaxMinDisparity) {
        throw std::invalid_argument(
            "min-disp must be in [" + std::to_string(-fx::kMaxMinDisparity) + ", " +
            std::to_string(fx::kMaxMinDisparity) + "], got " + std::to_string(params.min_disp));
    }
    const ValidationParams& v = params.validation;
    if (v.uniqueness_ratio < 0 || v.uniqueness_ratio > fx::kMaxUniqueness) {
        throw std::invalid_argument("uniqueness ratio must be in [0, " +
                                    std::to_string(fx::kMaxUniqueness) + "] percent, got " +
                                    std::to_string(v.uniqueness_ratio));
    }
    if (v.lr_tolerance < 0 || v.lr_tolerance > fx::kMaxLrTolerance) {
        throw std::invalid_argument("left-right tolerance must be in [0, " +
                                    std::to_string(fx::kMaxLrTolerance) + "] labels, got " +
                                    std::to_string(v.lr_tolerance));
    }
    (void)gaussian_kernel(params.window, params.sigma);  // throws on a bad window or sigma
    (void)make_cost(params.cost);                        // throws on an unknown cost
}

void validate_size(const MatchParams& params, int width, int height) {
    if (params.ndisp >= width) {
        throw std::invalid_argument("ndisp " + std::to_string(params.ndisp) +
                                    " must be smaller than the image width " +
                                    std::to_string(width));
    }
    // Some disparity of the range must leave a match inside the image.
    const int lowest = params.min_disp;
    const int highest = params.min_disp + params.ndisp - 1;
    if (lowest >= width || highest <= -width) {
        throw std::invalid_argument("disparities " + std::to_string(lowest) + " .. " +
                                    std::to_string(highest) + " leave the image (width " +
                                    std::to_string(width) + ")");
    }
    const InvalidBorder border = invalid_border(params);
    if (width <= 2 * border.reach || height <= 2 * border.reach) {
        throw std::invalid_argument("image " + size_text(width, height) +
                                    " is too small for ndisp " + std::to_string(params.ndisp) +
                                    " and window " + std::to_string(params.window) +
                                    ": no pixel would be valid");
    }
}

// ---- The stages over whole volumes (the RTL and HLS stage tests compare against these) -------

Dsi cost(const Image& left, const Image& right, int ndisp) {
    check_pair(left, right);
    if (ndisp < 1 || ndisp > fx::kMaxDisparities) {
        throw std::invalid_argument("ndisp out of range: " + std::to_string(ndisp));
    }
    return cost_volume(*make_ad_cost(), left, right, ndisp);
}

Dsi aggregate(const Dsi& cost, const std::vector<std::int32_t>& kernel) {
    check_kernel(kernel);
    Dsi out(cost.width(), cost.height(), cost.ndisp());
    const auto aggregator = make_gaussian_aggregator(kernel, cost.width(), cost.height());
    for (int d = 0; d < cost.ndisp(); ++d) {
        aggregator->plane(cost.plane(d).data(), out.plane(d).data());
    }
    return out;
}

Dsi ca_rule1(const Dsi& dsi) {
    Dsi out(dsi.width(), dsi.height(), dsi.ndisp());
    const auto rule = make_ca_rule1(dsi.width(), dsi.height());
    for (int d = 0; d < dsi.ndisp(); ++d) {
        const NeighbourPlanes axis{d > 0 ? dsi.plane(d - 1).data() : nullptr,
                                   d + 1 < dsi.ndisp() ? dsi.plane(d + 1).data() : nullptr};
        rule->plane(dsi.plane(d).data(), std::span(&axis, 1), out.plane(d).data());
    }
    return out;
}

Dsi ca_rule2(const Dsi& dsi) {
    Dsi out(dsi.width(), dsi.height(), dsi.ndisp());
    const auto rule = make_ca_rule2(dsi.width(), dsi.height());
    for (int d = 0; d < dsi.ndisp(); ++d) {
        rule->plane(dsi.plane(d).data(), {}, out.plane(d).data());
    }
    return out;
}

DisparityMap wta(const Dsi& dsi, const InvalidBorder& border) {
    const auto grid = CandidateGrid::horizontal(dsi.width(), dsi.height(), dsi.ndisp());
    WinnerTakesAll selector(grid);
    for (int d = 0; d < dsi.ndisp(); ++d) {
        selector.update(dsi.plane(d).data(), d, 0);
    }
    return to_disparity_map(selector.winners(), border);
}

// ---- The pipeline: the same stages streamed over d by the plane scheduler -------------------

DisparityMap match(const Image& left, const Image& right, const MatchParams& params) {
    check_pair(left, right);
    validate(params, left.width, left.height);
    return match_with(*make_cost(params.cost), gaussian_kernel(params.window, params.sigma), left,
                      right, params);
}

ValidatedDisparity match_validated(const Image& left, const Image& right,
                                   const MatchParams& params) {
    check_pair(left, right);
    validate(params, left.width, left.height);
    return match_validated_with(*make_cost(params.cost),
                                gaussian_kernel(params.window, params.sigma), left, right, params);
}

namespace {

// Runs the pipeline's stages over the 1-D search into `selector`.
void run_pipeline(const CostFunction& cost, const std::vector<std::int32_t>& kernel,
                  const Image& left, const Image& right, const MatchParams& params,
                  Selector& selector) {
    check_pair(left, right);
    validate_size(params, left.width, left.height);
    if (kernel.size() != static_cast<std::size_t>(params.window)) {
        throw std::invalid_argument("the kernel must have params.window taps");
    }
    const int width = left.width;
    const int height = left.height;
    const PlanarImage left_planes = cost.prepare(left);
    const PlanarImage right_planes = cost.prepare(right);
    const auto grid = CandidateGrid::horizontal(width, height, params.ndisp, params.min_disp);
    const auto aggregator = make_gaussian_aggregator(kernel, width, height);
    const auto rule1 = make_ca_rule1(width, height);
    const auto rule2 = make_ca_rule2(width, height);
    const std::array<Refiner*, 2> ca = {rule1.get(), rule2.get()};
    search(left_planes, right_planes, grid,
           {cost, *aggregator, std::span(ca.data(), params.use_ca ? ca.size() : 0), selector});
}

// Keeps the values of some pixels from each plane it sees, in candidate order.
class PixelRecorder {
  public:
    PixelRecorder(std::vector<std::size_t> indices, std::size_t pixels_per_plane)
        : indices_(std::move(indices)), plane_size_(pixels_per_plane) {}
    void record(const CostValue* plane) {
        for (const std::size_t index : indices_) {
            values_.push_back(plane[index]);
        }
    }
    // Pixel n's value in plane k.
    std::uint16_t at(std::size_t n, std::size_t k) const {
        return values_[k * indices_.size() + n];
    }
    std::size_t plane_size() const { return plane_size_; }

  private:
    std::vector<std::size_t> indices_;
    std::size_t plane_size_;
    std::vector<std::uint16_t> values_;
};

class RecordingAggregator final : public Aggregator {
  public:
    RecordingAggregator(Aggregator& inner, PixelRecorder& recorder)
        : inner_(inner), recorder_(recorder) {}
    int radius() const override { return inner_.radius(); }
    void plane(const CostValue* in, CostValue* out) override {
        inner_.plane(in, out);
        recorder_.record(out);
    }

  private:
    Aggregator& inner_;
    PixelRecorder& recorder_;
};

// A refiner that changes nothing and records what the previous one wrote.
class RecordingRefiner final : public Refiner {
  public:
    explicit RecordingRefiner(PixelRecorder& recorder) : recorder_(recorder) {}
    bool reads_neighbour_planes() const override { return false; }
    void plane(const CostValue* centre, std::span<const NeighbourPlanes> /*neighbours*/,
               CostValue* out) override {
        std::copy_n(centre, recorder_.plane_size(), out);
        recorder_.record(centre);
    }

  private:
    PixelRecorder& recorder_;
};

class RecordingSelector final : public Selector {
  public:
    explicit RecordingSelector(PixelRecorder& recorder) : recorder_(recorder) {}
    void update(const CostValue* plane, int /*i*/, int /*j*/) override { recorder_.record(plane); }

  private:
    PixelRecorder& recorder_;
};

}  // namespace

std::vector<PixelStageValues> stage_values_at(const Image& left, const Image& right,
                                              const MatchParams& params,
                                              const std::vector<std::pair<int, int>>& pixels) {
    check_pair(left, right);
    validate(params, left.width, left.height);
    const int width = left.width;
    const int height = left.height;
    std::vector<std::size_t> indices;
    for (const auto& [x, y] : pixels) {
        if (x < 0 || y < 0 || x >= width || y >= height) {
            throw std::invalid_argument("stage_values_at: pixel outside the image");
        }
        indices.push_back(static_cast<std::size_t>(y) * width + x);
    }
    const std::size_t plane_size = static_cast<std::size_t>(width) * height;
    PixelRecorder aggregated(indices, plane_size);
    PixelRecorder after_rule1(indices, plane_size);
    PixelRecorder after_rule2(indices, plane_size);

    const auto cost = make_cost(params.cost);
    const PlanarImage left_planes = cost->prepare(left);
    const PlanarImage right_planes = cost->prepare(right);
    const auto grid = CandidateGrid::horizontal(width, height, params.ndisp, params.min_disp);
    const auto gaussian =
        make_gaussian_aggregator(gaussian_kernel(params.window, params.sigma), width, height);
    RecordingAggregator aggregator(*gaussian, aggregated);
    const auto rule1 = make_ca_rule1(width, height);
    RecordingRefiner record_rule1(after_rule1);
    const auto rule2 = make_ca_rule2(width, height);
    const std::array<Refiner*, 3> ca = {rule1.get(), &record_rule1, rule2.get()};
    RecordingSelector selector(after_rule2);
    search(left_planes, right_planes, grid,
           {*cost, aggregator, std::span(ca.data(), params.use_ca ? ca.size() : 0), selector});

    std::vector<PixelStageValues> out;
    for (std::size_t n = 0; n < pixels.size(); ++n) {
        PixelStageValues values{pixels[n].first, pixels[n].second, {}, {}, {}};
        for (int k = 0; k < params.ndisp; ++k) {
            const auto plane = static_cast<std::size_t>(k);
            values.aggregate.push_back(aggregated.at(n, plane));
            values.rule2.push_back(after_rule2.at(n, plane));
            values.rule1.push_back(params.use_ca ? after_rule1.at(n, plane)
                                                 : aggregated.at(n, plane));
        }
        out.push_back(std::move(values));
    }
    return out;
}

DisparityMap match_with(const CostFunction& cost, const std::vector<std::int32_t>& kernel,
                        const Image& left, const Image& right, const MatchParams& params) {
    if (params.min_disp != 0 || params.validation != ValidationParams{}) {
        return to_label_map(match_validated_with(cost, kernel, left, right, params));
    }
    // The plain winners: the validating selector's result without its extra work.
    const auto grid = CandidateGrid::horizontal(left.width, left.height, params.ndisp);
    WinnerTakesAll selector(grid);
    run_pipeline(cost, kernel, left, right, params, selector);
    return to_disparity_map(selector.winners(), invalid_border(params));
}

ValidatedDisparity match_validated_with(const CostFunction& cost,
                                        const std::vector<std::int32_t>& kernel, const Image& left,
                                        const Image& right, const MatchParams& params) {
    ValidatingSelector selector(left.width, left.height, params.ndisp, params.min_disp,
                                params.validation, invalid_border(params));
    run_pipeline(cost, kernel, left, right, params, selector);
    return selector.result();
}

CostedDisparity match_validated_with_costs(const Image& left, const Image& right,
                                           const MatchParams& params) {
    check_pair(left, right);
    validate(params, left.width, left.height);
    ValidatingSelector selector(left.width, left.height, params.ndisp, params.min_disp,
                                params.validation, invalid_border(params));
    run_pipeline(*make_cost(params.cost), gaussian_kernel(params.window, params.sigma), left, right,
                 params, selector);
    return {selector.result(), selector.winner_costs()};
}

}  // namespace stereo
