// Adaptive support weights (stereo/asw.hpp, docs/asw.md): the fast fixed-point model. The full
// variant: rows are shared among threads; a row is cut into tiles, and for each tile the weights
// of a chunk of offsets are computed once (for every disparity), then summed disparity by
// disparity, offset by offset, with the innermost loop over the tile's contiguous pixels (it
// vectorises). The separable variant is streamed row by row (SeparableRow, docs/asw.md "On the
// CPU"): no aggregated volume, the sums of 32 pixels kept in registers over every tap.
#include "stereo/asw.hpp"
#include "stereo/catalogue.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <thread>

#include "stereo/search.hpp"
#include "stereo/stages.hpp"
#include "stereo/stages/validate.hpp"
#include "stereo/target_clones.hpp"

namespace stereo::asw {
namespace {

int round_response(double value) {
    return std::clamp(static_cast<int>(std::floor(value * kResponseMax + 0.5)), 0, kResponseMax);
}

// -ln S / ln w for S clamped to [1/w, 1]: 1 at (or below) the truncation, 0 at S = 1.
double log_response(double stimulus, int diameter) {
    const double floor = 1.0 / diameter;
    const double s = std::clamp(stimulus, floor, 1.0);
    return -std::log(s) / std::log(static_cast<double>(diameter));
}

int square_side(int diameter) {
    // The odd side whose square is nearest the circle's pixel count (smaller side on a tie).
    Params circle;
    circle.diameter = diameter;
    const auto count = static_cast<double>(support_region(circle).size());
    int best = 1;
    for (int side = 1; side <= diameter; side += 2) {
        if (std::abs(side * side - count) < std::abs(best * best - count)) {
            best = side;
        }
    }
    return best;
}

// One image as three 8-bit planes (a grey image three times), so colour differences vectorise.
struct Planes {
    int width = 0;
    std::vector<std::uint8_t> data[3];
    explicit Planes(const Image& image) : width(image.width) {
        const std::size_t size = static_cast<std::size_t>(image.width) * image.height;
        for (int c = 0; c < 3; ++c) {
            data[c].resize(size);
            const int source = image.channels == 3 ? c : 0;
            for (std::size_t i = 0; i < size; ++i) {
                data[c][i] = image.pixels[i * image.channels + source];
            }
        }
    }
    const std::uint8_t* row(int c, int y) const {
        return data[c].data() + static_cast<std::size_t>(y) * width;
    }
};

// |dR| + |dG| + |dB| between row y and row qy shifted by dx, for x in [x0, x1).
void colour_row(const Planes& image, int y, int qy, int dx, int x0, int x1, std::uint16_t* out) {
    for (int x = x0; x < x1; ++x) {
        out[x] = 0;
    }
    for (int c = 0; c < 3; ++c) {
        const std::uint8_t* a = image.row(c, y);
        const std::uint8_t* b = image.row(c, qy) + dx;
        for (int x = x0; x < x1; ++x) {
            out[x] = static_cast<std::uint16_t>(out[x] + std::abs(int{a[x]} - int{b[x]}));
        }
    }
}

struct Volume {
    const Dsi& cost;
    int min_disp;
};

// One pass over `offsets` (all of them, or one axis of the separable variant): out =
// round((sum W * in) << out_shift / sum W). Rows y in [first, height) step `step`. Each row is
// cut into tiles of kTile pixels whose sums (ndisp x kTile) stay in the L1 cache while every
// offset is added; the weights of a tile are computed once per offset for every disparity.
constexpr int kTile = 128;
// Offsets whose weights are computed before any of them is summed, so that the sums can run
// disparity by disparity over the whole chunk (the rows of one cost plane in order).
constexpr std::size_t kChunk = 32;

// One offset of a chunk, clipped to the tile and the image.
struct Prepared {
    int dx = 0;
    int qy = 0;
    int x0 = 0;
    int x1 = 0;
    int span0 = 0;  // the first right-image column whose response the sums read
};

// Den: the type of the weight sums, std::uint16_t when they cannot exceed it (at most 257
// offsets of weight <= 255: the separable passes), which halves their memory traffic.
template <typename Den>
void aggregate_rows(const Volume& in, const Planes& left, const Planes& right,
                    const std::vector<Offset>& offsets, const ResponseTables& tables,
                    const Params& params, const std::vector<std::int16_t>& labels, int out_shift,
                    int first, int step, Dsi& out) {
    const int width = in.cost.width();
    const int height = in.cost.height();
    const int ndisp = in.cost.ndisp();
    const bool continuity = params.continuity && !labels.empty();
    const int d_low = in.min_disp;
    const int d_high = in.min_disp + ndisp - 1;
    // Right responses of a tile [t0, t1) are read at x - d, i.e. in [t0 - d_high, t1 - d_low);
    // the buffer holds that span, kResponseMax (a pixel outside the right image) where the pair
    // of right pixels is not inside.
    const std::size_t span = static_cast<std::size_t>(kTile + ndisp);
    std::vector<std::uint16_t> right_response(kChunk * span);
    std::vector<std::uint16_t> left_weight(kChunk * kTile);
    std::array<Prepared, kChunk> prep_list{};
    std::vector<std::uint16_t> difference(static_cast<std::size_t>(kTile + ndisp));
    std::vector<std::uint32_t> num(static_cast<std::size_t>(ndisp) * kTile);
    std::vector<Den> den(static_cast<std::size_t>(ndisp) * kTile);

    for (int y = first; y < height; y += step) {
        for (int t0 = 0; t0 < width; t0 += kTile) {
            const int t1 = std::min(width, t0 + kTile);
            std::fill(num.begin(), num.end(), 0U);
            std::fill(den.begin(), den.end(), Den{0});
            for (std::size_t chunk = 0; chunk < offsets.size(); chunk += kChunk) {
                // Phase 1: the weights of up to kChunk offsets (table look-ups, scalar stores).
                int prepared = 0;
                for (std::size_t i = chunk; i < std::min(offsets.size(), chunk + kChunk); ++i) {
                    const Offset& o = offsets[i];
                    const int qy = y + o.dy;
                    // Pixels of the tile whose neighbour p + o lies inside the image.
                    const int x0 = std::max(t0, -o.dx);
                    const int x1 = std::min(t1, width - o.dx);
                    if (qy < 0 || qy >= height || x0 >= x1) {
                        continue;  // outside the image: no contribution
                    }
                    Prepared& prep = prep_list[static_cast<std::size_t>(prepared)];
                    prep = {o.dx, qy, x0, x1, x0 - d_high};
                    std::uint16_t* lw = left_weight.data() + std::size_t(prepared) * kTile - t0;
                    colour_row(left, y, qy, o.dx, x0, x1, difference.data() - t0);
                    const std::int16_t* label_p =
                        continuity ? labels.data() + std::size_t(y) * width : nullptr;
                    const std::int16_t* label_q =
                        continuity ? labels.data() + std::size_t(qy) * width + o.dx : nullptr;
                    for (int x = x0; x < x1; ++x) {
                        int w = combine(o.proximity, tables.colour[difference[x - t0]]);
                        if (continuity) {
                            w = combine(w, tables.continuity[static_cast<std::size_t>(
                                               std::abs(label_p[x] - label_q[x]))]);
                        }
                        lw[x] = static_cast<std::uint16_t>(w);
                    }
                    if (params.right_weights) {
                        // rr[i] is the right response at x' = span0 + i, x' in
                        // [x0 - d_high, x1 - d_low).
                        std::uint16_t* rr = right_response.data() + std::size_t(prepared) * span;
                        const int span1 = x1 - d_low;
                        std::fill(rr, rr + (span1 - prep.span0),
                                  static_cast<std::uint16_t>(kResponseMax));
                        const int r0 = std::max({prep.span0, 0, -o.dx});
                        const int r1 = std::min({span1, width, width - o.dx});
                        if (r0 < r1) {
                            colour_row(right, y, qy, o.dx, r0, r1, difference.data() - r0);
                            for (int x = r0; x < r1; ++x) {
                                rr[x - prep.span0] = tables.colour[difference[x - r0]];
                            }
                        }
                    }
                    ++prepared;
                }
                // Phase 2: the weighted sums, vectorised over x. Disparity outside, offset
                // inside: the sums of one disparity stay in registers / L1 while the chunk's
                // offsets walk the rows of one cost plane in order (the prefetcher follows).
                for (int k = 0; k < ndisp; ++k) {
                    const int d = d_low + k;
                    // Distinct buffers: __restrict spares the vectoriser its run-time overlap
                    // checks on these short (one tile) loops.
                    std::uint32_t* __restrict n =
                        num.data() + static_cast<std::size_t>(k) * kTile - t0;
                    Den* __restrict s = den.data() + static_cast<std::size_t>(k) * kTile - t0;
                    const CostValue* plane = in.cost.plane(k).data();
                    int i = 0;
                    if (params.right_weights) {
                        // Two offsets per sweep where they cover the same pixels (every offset of
                        // an inner tile): half the loads and stores of the sums.
                        for (; i + 1 < prepared; i += 2) {
                            const Prepared& pa = prep_list[static_cast<std::size_t>(i)];
                            const Prepared& pb = prep_list[static_cast<std::size_t>(i) + 1];
                            if (pa.x0 != pb.x0 || pa.x1 != pb.x1) {
                                break;
                            }
                            const std::uint16_t* __restrict lwa =
                                left_weight.data() + std::size_t(i) * kTile - t0;
                            const std::uint16_t* __restrict lwb = lwa + kTile;
                            const CostValue* __restrict ca =
                                plane + static_cast<std::size_t>(pa.qy) * width + pa.dx;
                            const CostValue* __restrict cb =
                                plane + static_cast<std::size_t>(pb.qy) * width + pb.dx;
                            const std::uint16_t* __restrict ra =
                                right_response.data() + std::size_t(i) * span - pa.span0 - d;
                            const std::uint16_t* __restrict rb =
                                right_response.data() + (std::size_t(i) + 1) * span - pb.span0 - d;
                            for (int x = pa.x0; x < pa.x1; ++x) {
                                const auto wa = static_cast<std::uint16_t>(
                                    static_cast<std::uint16_t>(lwa[x] * ra[x] + 128U) >>
                                    kResponseBits);
                                const auto wb = static_cast<std::uint16_t>(
                                    static_cast<std::uint16_t>(lwb[x] * rb[x] + 128U) >>
                                    kResponseBits);
                                n[x] += std::uint32_t{wa} * ca[x] + std::uint32_t{wb} * cb[x];
                                s[x] = static_cast<Den>(s[x] + wa + wb);
                            }
                        }
                    }
                    for (; i < prepared; ++i) {
                        const Prepared& prep = prep_list[static_cast<std::size_t>(i)];
                        const std::uint16_t* __restrict lw =
                            left_weight.data() + std::size_t(i) * kTile - t0;
                        const CostValue* __restrict c =
                            plane + static_cast<std::size_t>(prep.qy) * width + prep.dx;
                        if (params.right_weights) {
                            // r[x] = right response at x - d.
                            const std::uint16_t* __restrict r =
                                right_response.data() + std::size_t(i) * span - prep.span0 - d;
                            for (int x = prep.x0; x < prep.x1; ++x) {
                                // lw * r + 128 <= 65153: the product fits 16 bits, so it
                                // vectorises as 16-bit lanes.
                                const auto product =
                                    static_cast<std::uint16_t>(lw[x] * r[x] + 128U);
                                const auto w = static_cast<std::uint16_t>(product >> kResponseBits);
                                n[x] += std::uint32_t{w} * c[x];
                                s[x] = static_cast<Den>(s[x] + w);
                            }
                        } else {
                            for (int x = prep.x0; x < prep.x1; ++x) {
                                n[x] += std::uint32_t{lw[x]} * c[x];
                                s[x] = static_cast<Den>(s[x] + lw[x]);
                            }
                        }
                    }
                }
            }
            for (int k = 0; k < ndisp; ++k) {
                CostValue* row = out.plane(k).data() + static_cast<std::size_t>(y) * width;
                const std::uint32_t* n = num.data() + static_cast<std::size_t>(k) * kTile - t0;
                const Den* s = den.data() + static_cast<std::size_t>(k) * kTile - t0;
                for (int x = t0; x < t1; ++x) {
                    // floor((n << shift + s / 2) / s) in double precision, which vectorises
                    // where the 64-bit integer division does not: the numerator (< 2^37) and the
                    // denominator (< 2^22) are exact doubles, and a quotient that is not an
                    // integer lies at least 1/s > 2^-22 from one, far beyond the rounding error
                    // of the division (< 2^14 * 2^-53), so truncation gives the exact floor.
                    const auto numerator =
                        static_cast<double>((std::uint64_t{n[x]} << out_shift) + s[x] / 2);
                    row[x] = static_cast<CostValue>(numerator / static_cast<double>(s[x]));
                }
            }
        }
    }
}

int thread_count(const Params& params, int rows) {
    int threads =
        params.threads > 0 ? params.threads : static_cast<int>(std::thread::hardware_concurrency());
    return std::clamp(threads, 1, std::max(1, rows));
}

Dsi aggregate_pass(const Volume& in, const Planes& left, const Planes& right,
                   const std::vector<Offset>& offsets, const ResponseTables& tables,
                   const Params& params, const std::vector<std::int16_t>& labels, int out_shift) {
    Dsi out(in.cost.width(), in.cost.height(), in.cost.ndisp());
    const int threads = thread_count(params, in.cost.height());
    const bool narrow = offsets.size() * kResponseMax <= 0xFFFF;
    const auto rows = [&](int first, int step) {
        if (narrow) {
            aggregate_rows<std::uint16_t>(in, left, right, offsets, tables, params, labels,
                                          out_shift, first, step, out);
        } else {
            aggregate_rows<std::uint32_t>(in, left, right, offsets, tables, params, labels,
                                          out_shift, first, step, out);
        }
    };
    if (threads == 1) {
        rows(0, 1);
        return out;
    }
    std::vector<std::jthread> workers;
    workers.reserve(static_cast<std::size_t>(threads));
    for (int t = 0; t < threads; ++t) {
        workers.emplace_back([&, t] { rows(t, threads); });
    }
    workers.clear();  // joins
    return out;
}

void check_inputs(const Dsi& cost, const Image& left, const Image& right, const Params& params,
                  const std::vector<std::int16_t>& labels) {
    check_pair(left, right);
    if (cost.width() != left.width || cost.height() != left.height) {
        throw std::invalid_argument("the cost volume and the images differ in size");
    }
    if (params.continuity && !labels.empty() &&
        labels.size() != static_cast<std::size_t>(left.width) * left.height) {
        throw std::invalid_argument("the preliminary map and the images differ in size");
    }
}

std::vector<std::int16_t> winners_of(const Dsi& volume, int min_disp) {
    const auto grid =
        CandidateGrid::horizontal(volume.width(), volume.height(), volume.ndisp(), min_disp);
    WinnerTakesAll selector(grid);
    for (int k = 0; k < volume.ndisp(); ++k) {
        selector.update(volume.plane(k).data(), k, 0);
    }
    return selector.winners().disparity;
}

// stereo::cost_volume with the planes shared among the threads (same cells).
Dsi parallel_cost_volume(const CostFunction& cost, const Image& left, const Image& right,
                         const MatchParams& match, const Params& params) {
    const PlanarImage left_planes = cost.prepare(left);
    const PlanarImage right_planes = cost.prepare(right);
    const auto grid =
        CandidateGrid::horizontal(left.width, left.height, match.ndisp, match.min_disp);
    Dsi dsi(left.width, left.height, match.ndisp);
    const int threads = thread_count(params, match.ndisp);
    std::vector<std::jthread> workers;
    for (int t = 0; t < threads; ++t) {
        workers.emplace_back([&, t] {
            for (int k = t; k < match.ndisp; k += threads) {
                cost_plane(cost, left_planes, right_planes, grid, k, 0, dsi.plane(k).data());
            }
        });
    }
    workers.clear();  // joins
    return dsi;
}

// ---- The separable variant, streamed row by row -------------------------------------------
// Output row y of the separable variant depends on the cost rows y - reach .. y + reach (the
// vertical pass) and on row y of the images and of the preliminary map (both horizontal passes,
// the continuity factor included: its offsets stay in the row). So each row is one work item:
// the vertical pass, the first horizontal pass, its winners, the second horizontal pass and
// stage 6 run on row buffers, and no aggregated volume is ever materialised. Threads take rows
// from a shared counter; every row is computed the same way whichever thread takes it.

// Pixels whose sums stay in registers while every tap of a 1-D pass is added (two vectors).
constexpr int kBlock = 32;

int padded_width(int width) {
    return (width + kBlock - 1) / kBlock * kBlock;
}

// The sums run on GCC's vector extensions, one source for every clone (stereo/target_clones.hpp).
using U16x32 = std::uint16_t __attribute__((vector_size(64)));
using U32x16 = std::uint32_t __attribute__((vector_size(64)));
using I32x16 = std::int32_t __attribute__((vector_size(64)));
using F64x16 = double __attribute__((vector_size(128)));

// One tap of a 1-D pass at label 0, each pointer at pixel 0 of the row: the left weight
// (proximity, left colour and continuity factors; 0 where the neighbour is outside the image), the
// right response at x - d and the input at x + dx. Label j reads the right responses one pixel
// further left per label (x - d - j) and the input `input_step` further per label.
struct Tap {
    const std::uint16_t* left;
    const std::uint16_t* right;
    const std::uint16_t* input;
};

// The row of a 1-D pass at labels j0 .. j0 + kLabels - 1 (see weighted_means). Labels in pairs
// share the left weights' loads and the loop over the taps.
template <int kLabels>
[[gnu::always_inline]] inline void weighted_means_of(const Tap* taps, int ntaps, bool right,
                                                     int count, int shift, int j0,
                                                     std::ptrdiff_t input_step, std::uint16_t* out,
                                                     std::ptrdiff_t out_step) {
    constexpr std::uint32_t kLow = 0xFFFF;
    for (int x0 = 0; x0 < count; x0 += kBlock) {
        U32x16 num_even[kLabels] = {};
        U32x16 num_odd[kLabels] = {};
        U16x32 den[kLabels] = {};
        for (int t = 0; t < ntaps; ++t) {
            U16x32 left;
            std::memcpy(&left, taps[t].left + x0, sizeof left);
            for (int l = 0; l < kLabels; ++l) {
                const int j = j0 + l;
                U16x32 w = left;
                if (right) {
                    U16x32 r;
                    std::memcpy(&r, taps[t].right - j + x0, sizeof r);
                    w = (w * r + 128) >> kResponseBits;  // left * right + 128 <= 65153: 16 bits
                }
                U16x32 c;
                std::memcpy(&c, taps[t].input + j * input_step + x0, sizeof c);
                // At most kMaxDiameter taps of weight <= 255: the 16-bit sum cannot wrap.
                den[l] += w;
                const auto w32 = reinterpret_cast<U32x16>(w);
                const auto c32 = reinterpret_cast<U32x16>(c);
                num_even[l] += (w32 & kLow) * (c32 & kLow);
                num_odd[l] += (w32 >> 16) * (c32 >> 16);
            }
        }
        // The division in double precision, as aggregate_rows argues: the numerator (< 2^31) and
        // the denominator (< 2^15) are exact, and truncating the quotient is the exact floor.
        for (int l = 0; l < kLabels; ++l) {
            const auto den32 = reinterpret_cast<U32x16>(den[l]);
            const U32x16 dens[2] = {den32 & kLow, den32 >> 16};
            const U32x16 nums[2] = {num_even[l], num_odd[l]};
            U32x16 quotients[2];
            for (int h = 0; h < 2; ++h) {
                const auto n = reinterpret_cast<I32x16>((nums[h] << shift) + (dens[h] >> 1));
                const auto d =
                    reinterpret_cast<I32x16>(dens[h] + (dens[h] == 0 ? 1 : 0));  // padding
                const F64x16 q =
                    __builtin_convertvector(n, F64x16) / __builtin_convertvector(d, F64x16);
                quotients[h] = reinterpret_cast<U32x16>(__builtin_convertvector(q, I32x16));
            }
            const U32x16 packed = quotients[0] | (quotients[1] << 16);
            std::memcpy(out + (j0 + l) * out_step + x0, &packed, sizeof packed);
        }
    }
}

// One row of a 1-D pass at every label j in [0, nlabels): out_j[x] = floor(((sum_t w c) << shift
// + s / 2) / s), s = sum_t w, with the weight w = (left_t[x] * right_t[x - j] + 128) >> 8
// (left_t[x] alone without right weights) and c = input_t[x + j * input_step], for x in
// [0, count), count a multiple of kBlock; out_j = out + j * out_step. Pixels of no weight (only
// the padding) give 0. The 16-bit lanes are also read as 32-bit lanes, each an even pixel (low
// half) and an odd one (high half), so the products w * c (< 2^22) need no widening shuffles.
STEREO_TARGET_CLONES
void weighted_means(const Tap* taps, int ntaps, bool right, int count, int shift, int nlabels,
                    std::ptrdiff_t input_step, std::uint16_t* out, std::ptrdiff_t out_step) {
    int j = 0;
    for (; j + 1 < nlabels; j += 2) {
        weighted_means_of<2>(taps, ntaps, right, count, shift, j, input_step, out, out_step);
    }
    if (j < nlabels) {
        weighted_means_of<1>(taps, ntaps, right, count, shift, j, input_step, out, out_step);
    }
}

// A cost volume whose rows are padded to padded_width (zeros), plane-major like Dsi.
class PaddedVolume {
  public:
    PaddedVolume(int width, int height, int ndisp)
        : width_(width),
          height_(height),
          stride_(padded_width(width)),
          cells_(std::make_unique_for_overwrite<CostValue[]>(static_cast<std::size_t>(stride_) *
                                                             height * ndisp)) {}
    int width() const { return width_; }
    int stride() const { return stride_; }
    std::ptrdiff_t plane_step() const { return static_cast<std::ptrdiff_t>(height_) * stride_; }
    CostValue* row(int k, int y) {
        return cells_.get() + (static_cast<std::size_t>(k) * height_ + y) * stride_;
    }
    const CostValue* row(int k, int y) const {
        return cells_.get() + (static_cast<std::size_t>(k) * height_ + y) * stride_;
    }

  private:
    int width_;
    int height_;
    int stride_;
    std::unique_ptr<CostValue[]> cells_;
};

// Runs work(thread, row) for every row on `threads` threads (rows taken from a shared counter).
template <typename Work>
void for_each_row(int height, int threads, const Work& work) {
    std::atomic<int> next{0};
    const auto run = [&](int thread) {
        for (int y = next.fetch_add(1); y < height; y = next.fetch_add(1)) {
            work(thread, y);
        }
    };
    if (threads <= 1) {
        run(0);
        return;
    }
    std::vector<std::jthread> workers;
    workers.reserve(static_cast<std::size_t>(threads) - 1);
    for (int t = 1; t < threads; ++t) {
        workers.emplace_back(run, t);
    }
    run(0);
}  // the workers join here

// The truncated cost volume of `match` in padded rows: stereo::cost_plane's cells, then
// min(C, truncation) (truncate_cost), row by row.
PaddedVolume padded_cost_volume(const CostFunction& cost, const Image& left, const Image& right,
                                const MatchParams& match, int truncation, int threads) {
    const PlanarImage left_planes = cost.prepare(left);
    const PlanarImage right_planes = cost.prepare(right);
    const int width = left.width;
    PaddedVolume volume(width, left.height, match.ndisp);
    constexpr auto outside = static_cast<CostValue>(fx::kCostOutside);
    const auto cap = static_cast<CostValue>(truncation);
    for_each_row(left.height, threads, [&](int, int y) {
        for (int k = 0; k < match.ndisp; ++k) {
            CostValue* row = volume.row(k, y);
            const int d = match.min_disp + k;
            // As cost_plane: the pixels whose match x - d lies inside the right image.
            const int first = std::clamp(d, 0, width);
            const int last = std::clamp(width + d, 0, width);
            if (first >= last) {
                std::fill(row, row + width, outside);
            } else {
                std::fill(row, row + first, outside);
                cost.row(left_planes, right_planes, y, y, first, last - first, d, row + first);
                std::fill(row + last, row + width, outside);
            }
            if (truncation != 0) {
                for (int x = 0; x < width; ++x) {
                    row[x] = std::min(row[x], cap);
                }
            }
            std::fill(row + width, row + volume.stride(), CostValue{0});
        }
    });
    return volume;
}

// The same volume from a Dsi (asw::aggregate's input).
PaddedVolume padded_copy(const Dsi& cost) {
    PaddedVolume volume(cost.width(), cost.height(), cost.ndisp());
    for (int k = 0; k < cost.ndisp(); ++k) {
        for (int y = 0; y < cost.height(); ++y) {
            const auto source = cost.plane(k).subspan(static_cast<std::size_t>(y) * cost.width(),
                                                      static_cast<std::size_t>(cost.width()));
            CostValue* row = volume.row(k, y);
            std::copy(source.begin(), source.end(), row);
            std::fill(row + cost.width(), row + volume.stride(), CostValue{0});
        }
    }
    return volume;
}

// The inputs of the separable variant shared by every row: tables, axes and colour planes.
struct SeparableInputs {
    const PaddedVolume& cost;
    const Planes& left;
    const Planes& right;
    int height;
    int ndisp;
    int min_disp;
    const Params& params;
    const ResponseTables& tables;
    const std::vector<Offset>& column;  // the vertical axis (dx == 0)
    const std::vector<Offset>& row;     // the horizontal axis (dy == 0)
};

// One thread's row buffers and the steps of one row.
class SeparableRow {
  public:
    explicit SeparableRow(const SeparableInputs& in)
        : in_(in),
          width_(in.cost.width()),
          count_(in.cost.stride()),
          reach_(std::max(max_reach(in.column), max_reach(in.row))),
          right_span_(static_cast<std::size_t>(count_ + in.ndisp + reach_)),
          mirror_(mirrors(in.row)),
          left_(std::max(in.column.size(), in.row.size()) * static_cast<std::size_t>(count_)),
          continuity_left_(in.row.size() * static_cast<std::size_t>(count_)),
          right_(std::max(in.column.size(), in.row.size()) * right_span_),
          vertical_stride_(static_cast<std::size_t>(count_ + 2 * reach_)),
          vertical_(static_cast<std::size_t>(in.ndisp) * vertical_stride_, 0),
          horizontal_(static_cast<std::size_t>(in.ndisp) * count_),
          difference_(static_cast<std::size_t>(count_ + in.ndisp)),
          labels_(static_cast<std::size_t>(count_)) {
        taps_.reserve(std::max(in.column.size(), in.row.size()));
    }

    // The vertical pass of row y into vertical_ (4 fraction bits).
    void vertical(int y) {
        prepared_.clear();
        for (const Offset& o : in_.column) {
            if (y + o.dy >= 0 && y + o.dy < in_.height) {
                prepared_.push_back(o);
            }
        }
        for (std::size_t t = 0; t < prepared_.size(); ++t) {
            const int qy = y + prepared_[t].dy;
            std::uint16_t* lw = left_.data() + t * count_;
            colour_row(in_.left, y, qy, 0, 0, width_, difference_.data());
            for (int x = 0; x < width_; ++x) {
                lw[x] = static_cast<std::uint16_t>(
                    combine(prepared_[t].proximity, in_.tables.colour[difference_[x]]));
            }
            std::fill(lw + width_, lw + count_, std::uint16_t{0});
            if (in_.params.right_weights) {
                right_responses(t, y, qy, 0);
            }
        }
        taps_.clear();
        for (std::size_t t = 0; t < prepared_.size(); ++t) {
            taps_.push_back(
                {left_.data() + t * count_, right_at(t, 0), in_.cost.row(0, y + prepared_[t].dy)});
        }
        weighted_means(taps_.data(), static_cast<int>(taps_.size()), in_.params.right_weights,
                       count_, kOutputFracBits, in_.ndisp, in_.cost.plane_step(), vertical_row(0),
                       static_cast<std::ptrdiff_t>(vertical_stride_));
    }

    // The left weights and right responses of the horizontal passes of row y (no continuity).
    void prepare_horizontal(int y) {
        for (std::size_t t = 0; t < in_.row.size(); ++t) {
            if (mirror_[t] >= 0) {
                continue;  // below, from its mirror
            }
            const Offset& o = in_.row[t];
            std::uint16_t* lw = left_.data() + t * count_;
            std::fill(lw, lw + count_, std::uint16_t{0});
            const int x0 = std::max(0, -o.dx);
            const int x1 = std::min(width_, width_ - o.dx);
            if (x0 < x1) {
                colour_row(in_.left, y, y, o.dx, x0, x1, difference_.data());
                for (int x = x0; x < x1; ++x) {
                    lw[x] = static_cast<std::uint16_t>(
                        combine(o.proximity, in_.tables.colour[difference_[x]]));
                }
            }
            if (in_.params.right_weights) {
                right_responses(t, y, y, o.dx);
            }
        }
        for (std::size_t t = 0; t < in_.row.size(); ++t) {
            if (mirror_[t] >= 0) {
                mirror_copy(left_.data(), count_, t);
                if (in_.params.right_weights) {
                    mirror_copy(right_.data(), right_span_, t);
                }
            }
        }
    }

    // A horizontal pass of the row prepared last over vertical_ into horizontal_, with the
    // continuity factor of `labels` (a row of the preliminary map) unless it is null.
    void horizontal(const std::int16_t* labels) {
        const std::uint16_t* left = left_.data();
        if (labels != nullptr) {
            for (std::size_t t = 0; t < in_.row.size(); ++t) {
                if (mirror_[t] >= 0) {
                    continue;
                }
                const int dx = in_.row[t].dx;
                const std::uint16_t* lw = left_.data() + t * count_;
                std::uint16_t* cw = continuity_left_.data() + t * count_;
                std::fill(cw, cw + count_, std::uint16_t{0});
                for (int x = std::max(0, -dx); x < std::min(width_, width_ - dx); ++x) {
                    cw[x] = static_cast<std::uint16_t>(
                        combine(lw[x], in_.tables.continuity[static_cast<std::size_t>(
                                           std::abs(labels[x] - labels[x + dx]))]));
                }
            }
            for (std::size_t t = 0; t < in_.row.size(); ++t) {
                if (mirror_[t] >= 0) {
                    mirror_copy(continuity_left_.data(), count_, t);
                }
            }
            left = continuity_left_.data();
        }
        taps_.clear();
        for (std::size_t t = 0; t < in_.row.size(); ++t) {
            taps_.push_back({left + t * count_, right_at(t, 0), vertical_row(0) + in_.row[t].dx});
        }
        weighted_means(taps_.data(), static_cast<int>(taps_.size()), in_.params.right_weights,
                       count_, 0, in_.ndisp, static_cast<std::ptrdiff_t>(vertical_stride_),
                       horizontal_row(0), count_);
    }

    // Each pixel's first smallest label of horizontal_ among those whose match lies inside the
    // right image (winners_of after exclude_outside_matches); min_disp where there is none.
    const std::int16_t* winners() {
        std::vector<CostValue>& best = best_;
        best.assign(static_cast<std::size_t>(width_), kNoCandidate);
        std::fill(labels_.begin(), labels_.end(), static_cast<std::int16_t>(in_.min_disp));
        for (int k = 0; k < in_.ndisp; ++k) {
            const int d = in_.min_disp + k;
            const std::uint16_t* row = horizontal_row(k);
            const int begin = std::clamp(d, 0, width_);
            const int end = std::clamp(width_ + d, begin, width_);
            for (int x = begin; x < end; ++x) {
                const bool better = row[x] < best[static_cast<std::size_t>(x)];
                best[static_cast<std::size_t>(x)] =
                    better ? row[x] : best[static_cast<std::size_t>(x)];
                labels_[static_cast<std::size_t>(x)] =
                    better ? static_cast<std::int16_t>(d) : labels_[static_cast<std::size_t>(x)];
            }
        }
        return labels_.data();
    }

    // horizontal_ with every outside match set to kNoCandidate (exclude_outside_matches).
    void exclude_outside() {
        for (int k = 0; k < in_.ndisp; ++k) {
            const int d = in_.min_disp + k;
            std::uint16_t* row = horizontal_row(k);
            const int begin = std::clamp(d, 0, width_);
            const int end = std::clamp(width_ + d, begin, width_);
            std::fill(row, row + begin, kNoCandidate);
            std::fill(row + end, row + width_, kNoCandidate);
        }
    }

    std::uint16_t* horizontal_row(int k) {
        return horizontal_.data() + static_cast<std::size_t>(k) * count_;
    }

  private:
    static int max_reach(const std::vector<Offset>& axis) {
        int reach = 0;
        for (const Offset& o : axis) {
            reach = std::max({reach, std::abs(o.dx), std::abs(o.dy)});
        }
        return reach;
    }

    std::uint16_t* vertical_row(int k) {
        return vertical_.data() + static_cast<std::size_t>(k) * vertical_stride_ + reach_;
    }

    // Right responses of tap t for the right pixels x' = x - d, x' in [-d_high, count - d_low),
    // and reach_ more on the left (a mirrored tap reads them): colour similarity of R(x', y)
    // and R(x' + dx, qy), kResponseMax where either is outside. rr[i] is x' = i - first_right().
    void right_responses(std::size_t t, int y, int qy, int dx) {
        const int first = first_right();
        std::uint16_t* rr = right_.data() + t * right_span_;
        std::fill(rr, rr + right_span_, static_cast<std::uint16_t>(kResponseMax));
        // x' inside with x' + dx, intersected with the span [-first, -first + right_span_).
        const int s0 = std::max({0, -dx, -first});
        const int s1 = std::min({width_, width_ - dx, -first + static_cast<int>(right_span_)});
        if (s0 < s1) {
            colour_row(in_.right, y, qy, dx, s0, s1, difference_.data() - s0);
            for (int x = s0; x < s1; ++x) {
                rr[x + first] = in_.tables.colour[difference_[static_cast<std::size_t>(x - s0)]];
            }
        }
    }

    int first_right() const { return in_.min_disp + in_.ndisp - 1 + reach_; }

    // Tap t's right responses at label k as seen from pixel x: rr at x' = x - d.
    const std::uint16_t* right_at(std::size_t t, int k) const {
        return right_.data() + t * right_span_ + (first_right() - (in_.min_disp + k));
    }

    // The buffer of horizontal tap t (offset -a, a > 0) from its mirror's (+a): the colour, right
    // and continuity stimuli are symmetric (|L(x) - L(x - a)| is the mirror's at x - a, and so
    // is "both inside"), and so is the proximity, so each buffer is the mirror's shifted by a.
    void mirror_copy(std::uint16_t* buffers, std::size_t size, std::size_t t) const {
        const auto a = static_cast<std::size_t>(-in_.row[t].dx);
        const std::uint16_t* from = buffers + static_cast<std::size_t>(mirror_[t]) * size;
        std::uint16_t* to = buffers + t * size;
        std::fill(to, to + a,
                  std::uint16_t{0});  // the left buffers' outside; never read on the right
        std::copy(from, from + (size - a), to + a);
    }

    // For each horizontal tap of negative dx, the tap of -dx with the same proximity; else -1.
    static std::vector<int> mirrors(const std::vector<Offset>& axis) {
        std::vector<int> mirror(axis.size(), -1);
        for (std::size_t t = 0; t < axis.size(); ++t) {
            for (std::size_t m = 0; m < axis.size() && axis[t].dx < 0; ++m) {
                if (axis[m].dx == -axis[t].dx && axis[m].dy == axis[t].dy &&
                    axis[m].proximity == axis[t].proximity) {
                    mirror[t] = static_cast<int>(m);
                }
            }
        }
        return mirror;
    }

    const SeparableInputs& in_;
    int width_;
    int count_;
    int reach_;
    std::size_t right_span_;
    std::vector<int> mirror_;                     // mirrors(in_.row)
    std::vector<std::uint16_t> left_;             // per tap, count_ pixels
    std::vector<std::uint16_t> continuity_left_;  // left_ with the continuity factor
    std::vector<std::uint16_t> right_;            // per tap, right_span_ right pixels
    std::size_t vertical_stride_;
    std::vector<std::uint16_t> vertical_;  // per label: reach_ zeros, count_ pixels, reach_ zeros
    std::vector<std::uint16_t> horizontal_;
    std::vector<std::uint16_t> difference_;
    std::vector<std::int16_t> labels_;
    std::vector<CostValue> best_;
    std::vector<Offset> prepared_;
    std::vector<Tap> taps_;
};

// One SeparableRow per thread over the inputs of the separable variant.
class SeparableRun {
  public:
    SeparableRun(const PaddedVolume& cost, const Image& left, const Image& right, int ndisp,
                 int min_disp, const Params& params)
        : tables_(response_tables(params)),
          column_(axis_offsets(support_region(params), true)),
          row_(axis_offsets(support_region(params), false)),
          left_(left),
          right_(right),
          inputs_{cost,     left_,  right_,  left.height, ndisp,
                  min_disp, params, tables_, column_,     row_} {}

    // work(row buffers, y) for every row y on thread_count(params) threads.
    template <typename Work>
    void rows(const Work& work) const {
        const int threads = thread_count(inputs_.params, inputs_.height);
        std::vector<std::unique_ptr<SeparableRow>> buffers;
        for (int t = 0; t < threads; ++t) {
            buffers.push_back(std::make_unique<SeparableRow>(inputs_));
        }
        for_each_row(inputs_.height, threads, [&](int thread, int y) {
            work(*buffers[static_cast<std::size_t>(thread)], y);
        });
    }

  private:
    ResponseTables tables_;
    std::vector<Offset> column_;
    std::vector<Offset> row_;
    Planes left_;
    Planes right_;
    SeparableInputs inputs_;
};

Dsi aggregate_separable(const Dsi& cost, const Image& left, const Image& right, int min_disp,
                        const Params& params, const std::vector<std::int16_t>& labels) {
    const PaddedVolume padded = padded_copy(cost);
    const SeparableRun run(padded, left, right, cost.ndisp(), min_disp, params);
    const bool continuity = params.continuity && !labels.empty();
    const int width = cost.width();
    Dsi out(width, cost.height(), cost.ndisp());
    run.rows([&](SeparableRow& row, int y) {
        row.vertical(y);
        row.prepare_horizontal(y);
        row.horizontal(continuity ? labels.data() + static_cast<std::size_t>(y) * width : nullptr);
        for (int k = 0; k < cost.ndisp(); ++k) {
            const std::uint16_t* source = row.horizontal_row(k);
            std::copy(source, source + width,
                      out.plane(k).begin() + static_cast<std::ptrdiff_t>(y) * width);
        }
    });
    return out;
}

ValidatedDisparity match_separable(const Image& left, const Image& right, const MatchParams& match,
                                   const Params& params) {
    const PaddedVolume cost = padded_cost_volume(*make_cost(match.cost), left, right, match,
                                                 truncation_for(params.truncation, match.cost),
                                                 thread_count(params, left.height));
    const SeparableRun run(cost, left, right, match.ndisp, match.min_disp, params);
    const int width = left.width;
    ValidatedDisparity out(width, left.height);
    run.rows([&](SeparableRow& row, int y) {
        row.vertical(y);
        row.prepare_horizontal(y);
        row.horizontal(nullptr);
        if (params.continuity) {
            row.horizontal(row.winners());
        }
        row.exclude_outside();
        // Stage 6 of one row is stage 6 of the image restricted to it (the left-right check
        // stays in the row, and the border is 0).
        ValidatingSelector selector(width, 1, match.ndisp, match.min_disp, match.validation,
                                    InvalidBorder{0});
        for (int k = 0; k < match.ndisp; ++k) {
            selector.update(row.horizontal_row(k), k, 0);
        }
        const ValidatedDisparity one = selector.result();
        const auto at = static_cast<std::ptrdiff_t>(y) * width;
        std::copy(one.fixed.begin(), one.fixed.end(), out.fixed.begin() + at);
        std::copy(one.reason.begin(), one.reason.end(), out.reason.begin() + at);
        std::copy(one.certainty.begin(), one.certainty.end(), out.certainty.begin() + at);
    });
    return out;
}
}  // namespace

std::vector<Offset> axis_offsets(const std::vector<Offset>& region, bool vertical) {
    std::vector<Offset> line;
    for (const Offset& o : region) {
        if ((vertical && o.dx == 0) || (!vertical && o.dy == 0)) {
            line.push_back(o);
        }
    }
    return line;
}

Response response_from_name(std::string_view name) {
    if (name == "log" || name == "exp") {
        return name == "exp" ? Response::exp : Response::log;
    }
    throw std::invalid_argument("ASW response must be \"log\" or \"exp\", got \"" +
                                std::string(name) + "\"");
}

Shape shape_from_name(std::string_view name) {
    if (name == "circle" || name == "square") {
        return name == "square" ? Shape::square : Shape::circle;
    }
    throw std::invalid_argument("ASW shape must be \"circle\" or \"square\", got \"" +
                                std::string(name) + "\"");
}

std::vector<Offset> support_region(const Params& params) {
    const ResponseTables tables = response_tables(params);
    const int radius = params.shape == Shape::circle ? (params.diameter - 1) / 2
                                                     : square_side(params.diameter) / 2;
    std::vector<Offset> region;
    for (int dy = -radius; dy <= radius; ++dy) {
        for (int dx = -radius; dx <= radius; ++dx) {
            const int squared = dx * dx + dy * dy;
            if (params.shape == Shape::circle && squared > radius * radius) {
                continue;
            }
            region.push_back({dx, dy, tables.proximity[static_cast<std::size_t>(squared)]});
        }
    }
    return region;
}

ResponseTables response_tables(const Params& params) {
    const int w = params.diameter;
    ResponseTables tables;
    tables.colour.resize(kMaxColourDifference + 1);
    tables.continuity.resize(256);
    // Squared distances up to the square's corner (the square is never wider than w).
    const int radius = (w - 1) / 2;
    tables.proximity.resize(static_cast<std::size_t>(2 * radius * radius) + 1);
    const bool log = params.response == Response::log;
    for (std::size_t i = 0; i < tables.colour.size(); ++i) {
        const double v = static_cast<double>(i);
        tables.colour[i] = static_cast<std::uint8_t>(round_response(
            log ? log_response(v / params.colour_range, w) : std::exp(-v / kExpColourGamma)));
    }
    for (std::size_t i = 0; i < tables.continuity.size(); ++i) {
        const double v = static_cast<double>(i);
        tables.continuity[i] = static_cast<std::uint8_t>(
            round_response(log ? log_response(v / params.disparity_range, w)
                               : std::exp(-v / kExpContinuityGamma)));
    }
    for (std::size_t i = 0; i < tables.proximity.size(); ++i) {
        const double distance = std::sqrt(static_cast<double>(i));
        tables.proximity[i] = static_cast<std::uint8_t>(round_response(
            log ? log_response(distance / w, w) : std::exp(-distance / std::max(1, radius))));
    }
    return tables;
}

int colour_difference(const Image& a, int ax, int ay, const Image& b, int bx, int by) {
    int sum = 0;
    for (int c = 0; c < 3; ++c) {
        const int va = a.at(ax, ay, a.channels == 3 ? c : 0);
        const int vb = b.at(bx, by, b.channels == 3 ? c : 0);
        sum += std::abs(va - vb);
    }
    return sum;
}

int reach(const Params& params) {
    return params.shape == Shape::circle ? (params.diameter - 1) / 2
                                         : square_side(params.diameter) / 2;
}

void validate(const Params& params, int width, int height) {
    if (params.diameter < kMinDiameter || params.diameter > kMaxDiameter ||
        params.diameter % 2 == 0) {
        throw std::invalid_argument(
            "ASW window (diameter) must be odd and in [" + std::to_string(kMinDiameter) + ", " +
            std::to_string(kMaxDiameter) + "], got " + std::to_string(params.diameter));
    }
    if (params.colour_range < 1 || params.colour_range > kMaxColourDifference) {
        throw std::invalid_argument("ASW colour range must be in [1, 765], got " +
                                    std::to_string(params.colour_range));
    }
    if (params.disparity_range < 1 || params.disparity_range > 255) {
        throw std::invalid_argument("ASW disparity range must be in [1, 255], got " +
                                    std::to_string(params.disparity_range));
    }
    if ((params.truncation < 0 && params.truncation != kTruncationByCost) ||
        params.truncation > kMaxColourDifference) {
        throw std::invalid_argument(
            "ASW cost truncation must be in [0, 765] (0: none) or -1 (by the cost), got " +
            std::to_string(params.truncation));
    }
    if (params.threads < 0) {
        throw std::invalid_argument("ASW threads must be >= 0, got " +
                                    std::to_string(params.threads));
    }
    const int r = reach(params);
    if (width <= 2 * r || height <= 2 * r) {
        // The largest odd circle that fits: diameter <= the smaller side.
        const int side = std::min(width, height);
        const int largest = side % 2 == 1 ? side : side - 1;
        throw std::invalid_argument("the ASW window (diameter " + std::to_string(params.diameter) +
                                    ") must be smaller than the image " + std::to_string(width) +
                                    "x" + std::to_string(height) +
                                    (largest >= kMinDiameter
                                         ? ": use --window " + std::to_string(largest) + " or less"
                                         : ""));
    }
}

namespace {

// The inputs of the passes, prepared once per pair: tables, regions and colour planes.
class Passes {
  public:
    Passes(const Dsi& cost, const Image& left, const Image& right, int min_disp,
           const Params& params)
        : cost_(cost),
          min_disp_(min_disp),
          params_(params),
          tables_(response_tables(params)),
          region_(support_region(params)),
          left_(left),
          right_(right) {}

    // The whole support region (the full variant).
    Dsi full(const std::vector<std::int16_t>& labels) const {
        return aggregate_pass({cost_, min_disp_}, left_, right_, region_, tables_, params_, labels,
                              kOutputFracBits);
    }

  private:
    const Dsi& cost_;
    int min_disp_;
    Params params_;
    ResponseTables tables_;
    std::vector<Offset> region_;
    Planes left_;
    Planes right_;
};

}  // namespace

Dsi aggregate(const Dsi& cost, const Image& left, const Image& right, int min_disp,
              const Params& params, const std::vector<std::int16_t>& labels) {
    check_inputs(cost, left, right, params, labels);
    validate(params, left.width, left.height);
    if (params.separable) {
        return aggregate_separable(cost, left, right, min_disp, params, labels);
    }
    const Passes passes(cost, left, right, min_disp, params);
    return passes.full(labels);
}

void check_hardware_variant(const Params& params, std::string_view core, bool takes_truncation) {
    Params hardware;
    hardware.diameter = params.diameter;
    hardware.separable = true;
    if (takes_truncation) {
        hardware.truncation = params.truncation;
    }
    hardware.threads = params.threads;
    if (params != hardware) {
        throw std::invalid_argument(
            std::string(core) +
            " computes the separable variant with the default responses only: --separable, no "
            "--response, --shape, --no-continuity" +
            (takes_truncation ? " or --left-weights-only"
                              : ", --left-weights-only or --truncation"));
    }
}

int truncation_for(int truncation, std::string_view cost) {
    if (truncation != kTruncationByCost) {
        return truncation;
    }
    return catalogue::cost(cost).asw_truncation;
}

void truncate_cost(Dsi& cost, int truncation) {
    if (truncation == 0) {
        return;
    }
    const auto cap = static_cast<CostValue>(truncation);
    for (int k = 0; k < cost.ndisp(); ++k) {
        for (CostValue& cell : cost.plane(k)) {
            cell = std::min(cell, cap);
        }
    }
}

void exclude_outside_matches(Dsi& aggregated, int min_disp) {
    const int width = aggregated.width();
    for (int k = 0; k < aggregated.ndisp(); ++k) {
        const int d = min_disp + k;
        // Inside: 0 <= x - d < width, i.e. x in [max(0, d), min(width, width + d)).
        const int inside_begin = std::clamp(d, 0, width);
        const int inside_end = std::clamp(width + d, inside_begin, width);
        const std::span<CostValue> plane = aggregated.plane(k);
        for (int y = 0; y < aggregated.height(); ++y) {
            const auto row =
                plane.subspan(static_cast<std::size_t>(y) * width, static_cast<std::size_t>(width));
            std::fill(row.begin(), row.begin() + inside_begin, kNoCandidate);
            std::fill(row.begin() + inside_end, row.end(), kNoCandidate);
        }
    }
}

ValidatedDisparity select_validated(const Dsi& aggregated, const MatchParams& match) {
    ValidatingSelector selector(aggregated.width(), aggregated.height(), match.ndisp,
                                match.min_disp, match.validation, InvalidBorder{0});
    for (int k = 0; k < match.ndisp; ++k) {
        selector.update(aggregated.plane(k).data(), k, 0);
    }
    return selector.result();
}

ValidatedDisparity match(const Image& left, const Image& right, const MatchParams& match,
                         const Params& params) {
    check_pair(left, right);
    validate(params, left.width, left.height);
    MatchParams checked = match;
    checked.window = 1;  // the Gaussian window is not used; its checks must not reject
    checked.use_ca = false;
    stereo::validate(checked, left.width, left.height);
    if (params.separable) {
        return match_separable(left, right, match, params);
    }
    Dsi cost = parallel_cost_volume(*make_cost(match.cost), left, right, match, params);
    truncate_cost(cost, truncation_for(params.truncation, match.cost));
    const Passes passes(cost, left, right, match.min_disp, params);
    Dsi aggregated = passes.full({});
    if (params.continuity) {
        exclude_outside_matches(aggregated, match.min_disp);
        const auto labels = winners_of(aggregated, match.min_disp);
        aggregated = Dsi();  // at most two volumes alive: the cost and one aggregate
        aggregated = passes.full(labels);
    }
    exclude_outside_matches(aggregated, match.min_disp);
    return select_validated(aggregated, match);
}

}  // namespace stereo::asw
