// ZNCC cost plug-in over a 15x15 window (stereo/stages/zncc.hpp); naive reference in
// reference/zncc_naive.cpp. row() builds column sums of the window rows shared by the whole row,
// then slides the 15-column window with prefix sums.
#include <algorithm>
#include <cmath>
#include <vector>

#include "stereo/luma.hpp"
#include "stereo/stages.hpp"
#include "stereo/stages/zncc.hpp"

namespace stereo {
namespace zncc {

std::uint64_t isqrt64(std::uint64_t value) {
    auto root = static_cast<std::uint64_t>(std::sqrt(static_cast<double>(value)));
    while (root > 0 && root * root > value) {
        --root;
    }
    while ((root + 1) * (root + 1) <= value) {
        ++root;
    }
    return root;
}

int cost_from_sums(std::int64_t n, std::int64_t sl, std::int64_t sr, std::int64_t sll,
                   std::int64_t srr, std::int64_t slr) {
    const std::int64_t num = n * slr - sl * sr;
    const std::int64_t vl = n * sll - sl * sl;
    const std::int64_t vr = n * srr - sr * sr;
    const auto den = static_cast<std::int64_t>(
        isqrt64(static_cast<std::uint64_t>(vl) * static_cast<std::uint64_t>(vr)));
    if (den == 0) {
        return kFlatCost;
    }
    const std::int64_t cost = ((den - num) * fx::kCostMax + den) / (2 * den);
    return static_cast<int>(std::clamp<std::int64_t>(cost, 0, fx::kCostMax));
}

}  // namespace zncc

namespace {

class ZnccCost final : public CostFunction {
  public:
    PlanarImage prepare(const Image& image) const override { return PlanarImage(luma(image)); }

    void row(const PlanarImage& left, const PlanarImage& right, int y, int yr, int x0, int count,
             int shift, CostValue* out) const override {
        const int w = left.width;
        const int h = left.height;
        // Window rows j with both y + j and yr + j inside.
        const int j0 = std::max(-zncc::kRadius, std::max(-y, -yr));
        const int j1 = std::min(zncc::kRadius, std::min(h - 1 - y, h - 1 - yr));
        // Columns u (left coordinate) in [lo, hi) with u and u - shift inside.
        const int lo = std::max({0, shift, x0 - zncc::kRadius});
        const int hi = std::min({w, w + shift, x0 + count + zncc::kRadius});
        const int span = std::max(0, hi - lo);
        // Prefix sums over the columns: index k holds the sums of columns lo .. lo + k - 1.
        std::vector<std::int64_t> sl(span + 1, 0), sr(span + 1, 0), sll(span + 1, 0),
            srr(span + 1, 0), slr(span + 1, 0);
        for (int k = 0; k < span; ++k) {
            const int u = lo + k;
            std::int64_t cl = 0, cr = 0, cll = 0, crr = 0, clr = 0;
            for (int j = j0; j <= j1; ++j) {
                const std::int64_t l = left.row(0, y + j)[u];
                const std::int64_t r = right.row(0, yr + j)[u - shift];
                cl += l;
                cr += r;
                cll += l * l;
                crr += r * r;
                clr += l * r;
            }
            sl[k + 1] = sl[k] + cl;
            sr[k + 1] = sr[k] + cr;
            sll[k + 1] = sll[k] + cll;
            srr[k + 1] = srr[k] + crr;
            slr[k + 1] = slr[k] + clr;
        }
        const std::int64_t rows = j1 - j0 + 1;
        for (int n = 0; n < count; ++n) {
            const int x = x0 + n;
            const int a = std::clamp(x - zncc::kRadius - lo, 0, span);
            const int b = std::clamp(x + zncc::kRadius + 1 - lo, 0, span);
            const auto sum = [a, b](const std::vector<std::int64_t>& prefix) {
                return prefix[static_cast<std::size_t>(b)] - prefix[static_cast<std::size_t>(a)];
            };
            out[n] = static_cast<CostValue>(zncc::cost_from_sums(rows * (b - a), sum(sl), sum(sr),
                                                                 sum(sll), sum(srr), sum(slr)));
        }
    }
};

}  // namespace

std::unique_ptr<CostFunction> make_zncc_cost() {
    return std::make_unique<ZnccCost>();
}

}  // namespace stereo
