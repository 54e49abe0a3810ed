// Census cost plug-in (stereo/stages/census.hpp); naive reference in reference/census_naive.cpp.
#include <bit>

#include "stereo/luma.hpp"
#include "stereo/stages.hpp"
#include "stereo/stages/census.hpp"

namespace stereo {
namespace census {

std::vector<std::uint32_t> transform(const Image& image) {
    const Image grey = luma(image);
    const int w = grey.width;
    const int h = grey.height;
    std::vector<std::uint32_t> codes(static_cast<std::size_t>(w) * h, 0);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const int centre = grey.at(x, y, 0);
            std::uint32_t code = 0;
            for (int dy = -kRadius; dy <= kRadius; ++dy) {
                for (int dx = -kRadius; dx <= kRadius; ++dx) {
                    if (dx == 0 && dy == 0) {
                        continue;
                    }
                    const int nx = x + dx;
                    const int ny = y + dy;
                    const bool inside = nx >= 0 && nx < w && ny >= 0 && ny < h;
                    code = (code << 1) | (inside && grey.at(nx, ny, 0) < centre ? 1U : 0U);
                }
            }
            codes[static_cast<std::size_t>(y) * w + x] = code;
        }
    }
    return codes;
}

}  // namespace census

namespace {

// The bits set in one byte, by halves, nibbles then the byte: unlike std::popcount (a library
// call without the POPCNT instruction) it vectorises over the row.
constexpr unsigned byte_popcount(unsigned v) {
    v = v - ((v >> 1) & 0x55U);
    v = (v & 0x33U) + ((v >> 2) & 0x33U);
    return (v + (v >> 4)) & 0x0FU;
}

constexpr bool byte_popcount_exact() {
    for (unsigned v = 0; v < 256; ++v) {
        if (byte_popcount(v) != static_cast<unsigned>(std::popcount(v))) {
            return false;
        }
    }
    return true;
}
static_assert(byte_popcount_exact(), "every byte, checked at compile time");

class CensusCost final : public CostFunction {
  public:
    // The code's three bytes as three planes.
    PlanarImage prepare(const Image& image) const override {
        const auto codes = census::transform(image);
        PlanarImage planes(image.width, image.height, 3);
        for (std::size_t p = 0; p < codes.size(); ++p) {
            for (std::size_t b = 0; b < 3; ++b) {
                planes.planes[b][p] = static_cast<std::uint8_t>(codes[p] >> (8 * b));
            }
        }
        return planes;
    }

    void row(const PlanarImage& left, const PlanarImage& right, int y, int yr, int x0, int count,
             int shift, CostValue* out) const override {
        const std::uint8_t* l0 = left.row(0, y) + x0;
        const std::uint8_t* l1 = left.row(1, y) + x0;
        const std::uint8_t* l2 = left.row(2, y) + x0;
        const std::uint8_t* r0 = right.row(0, yr) + x0 - shift;
        const std::uint8_t* r1 = right.row(1, yr) + x0 - shift;
        const std::uint8_t* r2 = right.row(2, yr) + x0 - shift;
        for (int n = 0; n < count; ++n) {
            const unsigned distance = byte_popcount(static_cast<unsigned>(l0[n] ^ r0[n])) +
                                      byte_popcount(static_cast<unsigned>(l1[n] ^ r1[n])) +
                                      byte_popcount(static_cast<unsigned>(l2[n] ^ r2[n]));
            out[n] = static_cast<CostValue>(distance * census::kWeight);
        }
    }
};

}  // namespace

std::unique_ptr<CostFunction> make_census_cost() {
    return std::make_unique<CensusCost>();
}

}  // namespace stereo
