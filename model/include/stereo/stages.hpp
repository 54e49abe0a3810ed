// The plug-in stages of the golden model: a matching cost, an aggregator, refiners (the CA
// rules) and a selector (WTA). Every matcher is a composition of these, run by one plane
// scheduler (stereo/search.hpp); docs/architecture.md shows how to add one.
//
// A stage works on one plane of the disparity-space image at a time (all pixels of one candidate
// displacement), so the scheduler can stream over the candidates and keep only a few planes.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "stereo/dsi.hpp"
#include "stereo/image.hpp"

namespace stereo {

using CostValue = Dsi::Value;

// An image as a cost function reads it: one contiguous plane per component (the colour channels
// for AD, the census code bytes for census), so that rows vectorise.
struct PlanarImage {
    int width = 0;
    int height = 0;
    std::vector<std::vector<std::uint8_t>> planes;

    PlanarImage() = default;
    PlanarImage(int w, int h, int count);
    // The channels of `image`, one plane each.
    explicit PlanarImage(const Image& image);
    const std::uint8_t* row(int plane, int y) const {
        return planes[static_cast<std::size_t>(plane)].data() + static_cast<std::size_t>(y) * width;
    }
    std::uint8_t* row(int plane, int y) {
        return planes[static_cast<std::size_t>(plane)].data() + static_cast<std::size_t>(y) * width;
    }
    int count() const { return static_cast<int>(planes.size()); }
};

// Stage 1: the dissimilarity of a left and a right pixel, at most fx::kCostMax. The scheduler
// writes fx::kCostOutside where the right pixel lies outside the right image.
class CostFunction {
  public:
    virtual ~CostFunction() = default;
    // What the cost compares, computed once per image.
    virtual PlanarImage prepare(const Image& image) const = 0;
    // out[n] = cost of left pixel (x0 + n, y) against right pixel (x0 + n - shift, yr) for
    // n < count; every one of those right pixels lies inside the image.
    virtual void row(const PlanarImage& left, const PlanarImage& right, int y, int yr, int x0,
                     int count, int shift, CostValue* out) const = 0;
};

// Stage 2: window aggregation of one plane (width x height, row-major) into another.
class Aggregator {
  public:
    virtual ~Aggregator() = default;
    virtual int radius() const = 0;  // how far the window reaches from its centre
    virtual void plane(const CostValue* in, CostValue* out) = 0;
};

// The planes of the two neighbouring candidates along one search axis (d - 1 and d + 1 in the
// 1-D search); nullptr where the neighbour does not exist.
struct NeighbourPlanes {
    const CostValue* before = nullptr;
    const CostValue* after = nullptr;
};

// Stage 3..: a rule that rewrites one plane. Only the first refiner of a chain reads neighbouring
// planes (the aggregated ones); the others see only the plane the previous refiner wrote.
class Refiner {
  public:
    virtual ~Refiner() = default;
    virtual bool reads_neighbour_planes() const = 0;
    virtual void plane(const CostValue* centre, std::span<const NeighbourPlanes> neighbours,
                       CostValue* out) = 0;
};

// Stage 5: sees every final plane once, in candidate order (i fastest, then j).
class Selector {
  public:
    virtual ~Selector() = default;
    virtual void update(const CostValue* plane, int i, int j) = 0;
};

// ---- The model's stages (one file each under model/src/stages/) --------------------------

// Absolute difference summed over RGB; a grey pixel counts as (g, g, g). docs/fixed-point.md.
std::unique_ptr<CostFunction> make_ad_cost();
// min(AD, truncation): the edge front end's cost (docs/avoidance.md).
std::unique_ptr<CostFunction> make_truncated_ad_cost(int truncation);
// 5x5 census transform of the luma, Hamming distance times fx::kCensusWeight (stages/census.hpp).
std::unique_ptr<CostFunction> make_census_cost();
// LCDM (thesis Sec. 3.5): distance on the HSL hue-saturation disc, colour only
// (stages/lcdm.hpp); `dark_floor` is the saturation denominator's floor (lcdm::kDarkFloor).
std::unique_ptr<CostFunction> make_lcdm_cost(int dark_floor);
// 1 - ZNCC of the 15x15 luma windows, scaled to [0, fx::kCostMax] (stages/zncc.hpp); meant for
// aggregation window 1 without CA.
std::unique_ptr<CostFunction> make_zncc_cost();

// The costs a matcher can be asked for by name (stereo/catalogue.hpp, catalogue order).
const std::vector<std::string>& cost_names();
// Throws std::invalid_argument naming the known costs when `name` is not one of them.
std::unique_ptr<CostFunction> make_cost(std::string_view name);

// Separable Gaussian window with integer taps summing to fx::kKernelSum, zero padding.
std::unique_ptr<Aggregator> make_gaussian_aggregator(const std::vector<std::int32_t>& kernel,
                                                     int width, int height);

// CA rule 1: a cell that agrees with a neighbour along any given axis becomes the rounded mean
// of its 3x3 in-plane neighbourhood. With two axes, the first axis that fires decides.
std::unique_ptr<Refiner> make_ca_rule1(int width, int height);
// CA rule 2: a cell that agrees with at least fx::kRule2MinCount of its 8 in-plane neighbours is
// divided by 1.3.
std::unique_ptr<Refiner> make_ca_rule2(int width, int height);

}  // namespace stereo
