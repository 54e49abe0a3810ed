// `stereo_experiments illumination`: the tables and the figure of docs/results-illumination.md
// (issue 17). Every method runs in the same process on the same images:
//   * ideal lighting: AD and LCDM on the four Middlebury 2003 pairs, beside the thesis' Table 3.8;
//   * the LCDM dark floor (lcdm::kDarkFloor) against the mean over those pairs and the sweep;
//   * the lightness sweep on Tsukuba (right image -25 .. +25 % HSL lightness): LCDM, AD,
//     census, ZNCC 15x15 and OpenCV SGBM, as a table and a PNG plot;
//   * variably altered illumination (gradient -50..+50 %, vignette) on three scenes, with and
//     without lightness histogram equalisation for AD;
//   * real pairs (Middlebury 2014 Motorcycle/MotorcycleE, Piano/PianoL): the share of pixels valid
//     in both maps whose disparity changes by more than 1;
//   * speed: the cost stage's share of the pipeline time, LCDM against AD.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <opencv2/imgproc.hpp>

#include "cli_command.hpp"
#include "experiments.hpp"
#include "stereo/asw.hpp"
#include "stereo/defaults.hpp"
#include "stereo/pipeline.hpp"
#include "stereo/search.hpp"
#include "stereo/stages.hpp"
#include "stereo/stages/lcdm.hpp"
#include "stereo_io/data_dir.hpp"
#include "stereo_io/disparity_files.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/lighting.hpp"
#include "stereo_io/middlebury.hpp"

namespace stereo::experiments {
namespace {
namespace fs = std::filesystem;

struct IlluminationOptions {
    std::string data_dir = io::data_dir().string();
    std::string figure;  // PNG of the lightness sweep; empty: none
    std::vector<std::string> parts = {"ideal", "floor", "sweep", "variable", "real", "speed"};
};

// A method: a pair (RGB images, BGR copies) and a search range in, a float map (0 = invalid) out.
struct Pair {
    Image left;
    Image right;
    cv::Mat left_bgr;
    cv::Mat right_bgr;
};

struct Method {
    std::string name;
    std::function<cv::Mat(const Pair&, int ndisp)> run;
};

MatchParams pipeline_params(int ndisp, const std::string& cost) {
    MatchParams params;
    params.ndisp = ndisp;
    params.cost = cost;
    if (cost == "zncc") {  // a window measure: no aggregation, no CA (stages/zncc.hpp)
        params.window = 1;
        params.use_ca = false;
    }
    return params;
}

Method pipeline_method(const std::string& name, const std::string& cost) {
    return {name, [cost](const Pair& pair, int ndisp) {
                return io::to_float_disparity(
                    match(pair.left, pair.right, pipeline_params(ndisp, cost)));
            }};
}

// The pipeline validated as `stereo match` runs it with `cost`: that cost's uniqueness ratio and
// left-right tolerance (stereo/defaults.hpp), sub-pixel, then the speckle filter; only the
// pixels it can vouch for.
Method validated_method(const std::string& name, const std::string& cost) {
    return {name + " validated", [cost](const Pair& pair, int ndisp) {
                return io::to_float_disparity(
                    match_as_stereo_match(pair.left, pair.right, pipeline_params(ndisp, cost)));
            }};
}

// Adaptive support weights (separable, plain winners; docs/asw.md) with `cost`.
Method asw_method(const std::string& name, const std::string& cost) {
    return {name, [cost](const Pair& pair, int ndisp) {
                MatchParams params;
                params.ndisp = ndisp;
                params.cost = cost;
                asw::Params weights;
                weights.separable = true;
                return io::to_float_disparity(asw::match(pair.left, pair.right, params, weights));
            }};
}

Method lcdm_floor_method(int floor) {
    return {"LCDM floor " + std::to_string(floor), [floor](const Pair& pair, int ndisp) {
                const MatchParams params = pipeline_params(ndisp, "lcdm");
                return io::to_float_disparity(
                    match_with(*make_lcdm_cost(floor), gaussian_kernel(params.window, params.sigma),
                               pair.left, pair.right, params));
            }};
}

Method equalised_ad() {
    return {"AD + HE", [](const Pair& pair, int ndisp) {
                const Image left = io::to_image(io::equalise_lightness(pair.left_bgr), "left");
                const Image right = io::to_image(io::equalise_lightness(pair.right_bgr), "right");
                return io::to_float_disparity(match(left, right, pipeline_params(ndisp, "ad")));
            }};
}

Method sgbm() {
    return {"SGBM", [](const Pair& pair, int ndisp) {
                io::SceneData data;
                data.scene = {"pair", ndisp, 1.0};
                data.left_bgr = pair.left_bgr;
                data.right_bgr = pair.right_bgr;
                return io::run_stereo_sgbm(data);
            }};
}

std::vector<Method> all_methods() {
    return {pipeline_method("LCDM", "lcdm"), pipeline_method("AD", "ad"),
            pipeline_method("census", "census"), pipeline_method("ZNCC 15x15", "zncc"), sgbm()};
}

Pair make_pair(const cv::Mat& left_bgr, const cv::Mat& right_bgr) {
    return {io::to_image(left_bgr, "left"), io::to_image(right_bgr, "right"), left_bgr, right_bgr};
}

Pair relit_pair(const io::SceneData& data, const io::Lighting& lighting) {
    return make_pair(data.left_bgr, io::relight(data.right_bgr, lighting));
}

double nonocc(const io::SceneData& data, const cv::Mat& map) {
    return io::evaluate_scene(data, map).nonocc->percent().value_or(0.0);
}

std::vector<io::SceneData> load_2003(const std::string& data_dir) {
    std::vector<io::SceneData> scenes = load_2003_scenes(data_dir);
    if (scenes.empty()) {
        throw std::runtime_error("no Middlebury 2003 scene found under " + data_dir);
    }
    return scenes;
}

const io::SceneData* find_scene(const std::vector<io::SceneData>& scenes, const std::string& name) {
    for (const auto& s : scenes) {
        if (s.scene.name == name) {
            return &s;
        }
    }
    return nullptr;
}

// ---- the parts ---------------------------------------------------------------------------

// The rest of a table's header after its `leading` column names: one column per method, then
// the separator row.
void print_method_columns(const std::vector<Method>& methods, std::size_t leading) {
    for (const auto& m : methods) {
        std::cout << ' ' << m.name << " |";
    }
    std::cout << "\n|";
    for (std::size_t i = 0; i < leading + methods.size(); ++i) {
        std::cout << "---|";
    }
    std::cout << '\n';
}

void ideal(const std::vector<io::SceneData>& scenes) {
    // Thesis Table 3.8 (LCDM in the thesis' ASW algorithm): nonocc / all / disc.
    const std::map<std::string, std::string> thesis = {{"tsukuba", "5.98 / 7.84 / 22.2"},
                                                       {"venus", "14.5 / 15.4 / 35.9"},
                                                       {"teddy", "20.8 / 27.3 / 38.3"},
                                                       {"cones", "8.90 / 17.2 / 20.0"}};
    std::cout << "\n### Ideal lighting (bad > 1 %, nonocc / all / disc)\n\n"
              << "| pair | thesis LCDM (Table 3.8) | our AD | our LCDM | LCDM - AD (nonocc) |\n"
              << "|---|---|---|---|---|\n";
    for (const auto& data : scenes) {
        const Pair pair = make_pair(data.left_bgr, data.right_bgr);
        std::string cells[2];
        double first[2] = {0, 0};
        int i = 0;
        for (const char* cost : {"ad", "lcdm"}) {
            const io::EvalResult r =
                io::evaluate_scene(data, pipeline_method(cost, cost).run(pair, data.scene.ndisp));
            first[i] = *r.nonocc->percent();
            cells[i++] = fmt(*r.nonocc->percent()) + " / " + fmt(*r.all.percent()) + " / " +
                         fmt(*r.disc->percent());
        }
        std::cout << "| " << data.scene.name << " | " << thesis.at(data.scene.name) << " | "
                  << cells[0] << " | " << cells[1] << " | " << fmt(first[1] - first[0]) << " |\n";
    }
}

std::vector<double> sweep_steps() {
    std::vector<double> steps;
    for (int p = -25; p <= 25; p += 5) {
        steps.push_back(p);
    }
    return steps;
}

void floor_study(const std::vector<io::SceneData>& scenes) {
    const io::SceneData* tsukuba = find_scene(scenes, "tsukuba");
    std::cout << "\n### LCDM dark floor (bad > 1 % nonocc)\n\n| floor |";
    for (const auto& data : scenes) {
        std::cout << ' ' << data.scene.name << " |";
    }
    std::cout << " mean of the pairs | Tsukuba sweep mean | Tsukuba sweep worst / 0 % |\n|---|";
    for (std::size_t i = 0; i < scenes.size() + 3; ++i) {
        std::cout << "---|";
    }
    std::cout << '\n';
    for (const int floor : {1, 8, 16, 32, 64, 128}) {
        const Method method = lcdm_floor_method(floor);
        std::cout << "| " << floor << " |";
        double mean = 0;
        for (const auto& data : scenes) {
            const double v = nonocc(
                data, method.run(make_pair(data.left_bgr, data.right_bgr), data.scene.ndisp));
            mean += v / scenes.size();
            std::cout << ' ' << fmt(v) << " |";
        }
        std::cout << ' ' << fmt(mean) << " |";
        if (tsukuba != nullptr) {
            double sum = 0;
            double worst = 0;
            double zero = 0;
            for (const double p : sweep_steps()) {
                io::Lighting lighting;
                lighting.lightness_percent = p;
                const double v = nonocc(
                    *tsukuba, method.run(relit_pair(*tsukuba, lighting), tsukuba->scene.ndisp));
                sum += v / sweep_steps().size();
                worst = std::max(worst, v);
                zero = p == 0 ? v : zero;
            }
            std::cout << ' ' << fmt(sum) << " | " << fmt(worst / zero) << " |";
        }
        std::cout << '\n' << std::flush;
    }
}

void plot(const std::string& path, const std::vector<double>& steps,
          const std::vector<std::string>& names, const std::vector<std::vector<double>>& values) {
    const int width = 900;
    const int height = 560;
    const int left = 80;
    const int right = 200;
    const int top = 40;
    const int bottom = 70;
    cv::Mat image(height, width, CV_8UC3, cv::Scalar(255, 255, 255));
    double vmax = 10;
    for (const auto& row : values) {
        for (const double v : row) {
            vmax = std::max(vmax, v);
        }
    }
    vmax = std::ceil(vmax / 10) * 10;
    const auto px = [&](double p) {
        return left + static_cast<int>((p - steps.front()) / (steps.back() - steps.front()) *
                                       (width - left - right));
    };
    const auto py = [&](double v) {
        return top + static_cast<int>((1.0 - v / vmax) * (height - top - bottom));
    };
    const cv::Scalar black(0, 0, 0);
    const cv::Scalar grey(220, 220, 220);
    for (double v = 0; v <= vmax + 1e-9; v += 10) {
        cv::line(image, {px(steps.front()), py(v)}, {px(steps.back()), py(v)}, grey, 1);
        cv::putText(image, fmt(v, 0), {left - 40, py(v) + 5}, cv::FONT_HERSHEY_SIMPLEX, 0.5, black);
    }
    for (const double p : steps) {
        cv::line(image, {px(p), py(0)}, {px(p), py(0) + 5}, black, 1);
        cv::putText(image, fmt(p, 0), {px(p) - 12, py(0) + 22}, cv::FONT_HERSHEY_SIMPLEX, 0.5,
                    black);
    }
    cv::rectangle(image, {px(steps.front()), py(vmax)}, {px(steps.back()), py(0)}, black, 1);
    cv::putText(image, "lightness change of the right image (%)", {left + 150, height - 20},
                cv::FONT_HERSHEY_SIMPLEX, 0.55, black);
    cv::putText(image, "Tsukuba: bad > 1 px, non-occluded (%)", {left, 25},
                cv::FONT_HERSHEY_SIMPLEX, 0.6, black);
    const std::vector<cv::Scalar> colours = {{40, 40, 220}, {200, 80, 0},  {0, 150, 0},
                                             {160, 0, 160}, {0, 140, 220}, {90, 90, 90}};
    for (std::size_t m = 0; m < names.size(); ++m) {
        const cv::Scalar colour = colours[m % colours.size()];
        for (std::size_t i = 0; i < steps.size(); ++i) {
            const cv::Point point(px(steps[i]), py(values[m][i]));
            cv::circle(image, point, 4, colour, cv::FILLED, cv::LINE_AA);
            if (i > 0) {
                cv::line(image, {px(steps[i - 1]), py(values[m][i - 1])}, point, colour, 2,
                         cv::LINE_AA);
            }
        }
        const int ly = top + 20 + 28 * static_cast<int>(m);
        cv::line(image, {width - right + 20, ly}, {width - right + 50, ly}, colour, 3);
        cv::putText(image, names[m], {width - right + 58, ly + 5}, cv::FONT_HERSHEY_SIMPLEX, 0.55,
                    black);
    }
    io::write_png(path, image);
}

void sweep(const std::vector<io::SceneData>& scenes, const std::string& figure) {
    const io::SceneData* tsukuba = find_scene(scenes, "tsukuba");
    if (tsukuba == nullptr) {
        throw std::runtime_error("the lightness sweep needs middlebury2003/tsukuba");
    }
    const auto methods = all_methods();
    const auto steps = sweep_steps();
    std::vector<std::vector<double>> values(methods.size());
    std::cout << "\n### Lightness sweep, Tsukuba (bad > 1 % nonocc)\n\n| lightness |";
    print_method_columns(methods, 1);
    for (const double p : steps) {
        io::Lighting lighting;
        lighting.lightness_percent = p;
        const Pair pair = relit_pair(*tsukuba, lighting);
        std::cout << "| " << fmt(p, 0) << " % |";
        for (std::size_t m = 0; m < methods.size(); ++m) {
            const double v = nonocc(*tsukuba, methods[m].run(pair, tsukuba->scene.ndisp));
            values[m].push_back(v);
            std::cout << ' ' << fmt(v) << " |";
        }
        std::cout << '\n' << std::flush;
    }
    std::cout << "| worst / 0 % |";
    const std::size_t zero =
        static_cast<std::size_t>(std::find(steps.begin(), steps.end(), 0.0) - steps.begin());
    for (const auto& row : values) {
        std::cout << ' ' << fmt(*std::max_element(row.begin(), row.end()) / row[zero]) << "x |";
    }
    std::cout << '\n';
    if (!figure.empty()) {
        std::vector<std::string> names;
        for (const auto& m : methods) {
            names.push_back(m.name);
        }
        plot(figure, steps, names, values);
        std::cout << "\n(figure: " << figure << ")\n";
    }
}

void variable(const std::vector<io::SceneData>& scenes) {
    std::vector<Method> methods = all_methods();
    methods.insert(methods.begin() + 2, equalised_ad());
    std::cout << "\n### Variably altered illumination of the right image (bad > 1 % nonocc)\n\n"
              << "| scene | lighting |";
    print_method_columns(methods, 2);
    io::Lighting none;
    io::Lighting gradient;
    gradient.gradient_left = -50;
    gradient.gradient_right = 50;
    io::Lighting vignette;
    vignette.vignette_percent = 50;
    io::Lighting camera;
    camera.gain = 1.3;
    camera.offset = -10;
    camera.gamma = 0.8;
    const std::vector<std::pair<std::string, io::Lighting>> cases = {
        {"none", none},
        {"gradient -50..+50 %", gradient},
        {"vignette 50 %", vignette},
        {"gain 1.3, offset -10, gamma 0.8", camera}};
    for (const char* name : {"tsukuba", "venus", "cones"}) {
        const io::SceneData* data = find_scene(scenes, name);
        if (data == nullptr) {
            continue;
        }
        for (const auto& [label, lighting] : cases) {
            const Pair pair = relit_pair(*data, lighting);
            std::cout << "| " << name << " | " << label << " |";
            for (const auto& m : methods) {
                std::cout << ' ' << fmt(nonocc(*data, m.run(pair, data->scene.ndisp))) << " |";
            }
            std::cout << '\n' << std::flush;
        }
    }
}

// Share (%) of the pixels valid in both maps whose disparities differ by more than 1, and the
// share valid in both.
std::pair<double, double> change(const cv::Mat& a, const cv::Mat& b) {
    std::int64_t both = 0;
    std::int64_t changed = 0;
    for (int y = 0; y < a.rows; ++y) {
        for (int x = 0; x < a.cols; ++x) {
            const float u = a.at<float>(y, x);
            const float v = b.at<float>(y, x);
            if (u > 0 && v > 0) {
                ++both;
                changed += std::abs(u - v) > 1.0F ? 1 : 0;
            }
        }
    }
    return {both == 0 ? 0.0 : 100.0 * changed / both, 100.0 * both / (a.rows * a.cols)};
}

void real(const std::string& data_dir) {
    const fs::path root = fs::path(data_dir) / "middlebury2014_illum";
    if (!fs::is_directory(root)) {
        std::cout << "\n(middlebury2014_illum not found under " << data_dir << ": skipped)\n";
        return;
    }
    constexpr int kNdisp = 80;  // data README: covers both scenes
    // Our methods as they run by default too (validated), beside SGBM, which validates its own.
    std::vector<Method> methods = all_methods();
    methods.push_back(validated_method("LCDM", "lcdm"));
    methods.push_back(validated_method("AD", "ad"));
    methods.push_back(validated_method("census", "census"));
    methods.push_back(asw_method("ASW + LCDM", "lcdm"));  // issue 21's matcher, plain winners
    methods.push_back(asw_method("ASW + AD", "ad"));
    std::cout << "\n### Real lighting / exposure changes (Middlebury 2014, quarter size, 0..79)\n\n"
              << "Changed: % of the pixels valid in both maps whose disparity differs by more "
                 "than 1 (valid in both: % of the image).\n\n| pair |";
    print_method_columns(methods, 1);
    for (const auto& [reference, varied] :
         {std::pair{"Motorcycle", "MotorcycleE"}, std::pair{"Piano", "PianoL"}}) {
        const auto load = [&](const char* folder) {
            return make_pair(io::load_bgr(root / folder / "im0.png"),
                             io::load_bgr(root / folder / "im1.png"));
        };
        const Pair a = load(reference);
        const Pair b = load(varied);
        std::cout << "| " << reference << " / " << varied << " |";
        for (const auto& m : methods) {
            const auto [changed, both] = change(m.run(a, kNdisp), m.run(b, kNdisp));
            std::cout << ' ' << fmt(changed, 1) << " (" << fmt(both, 0) << ") |";
        }
        std::cout << '\n' << std::flush;
    }
}

void speed(const std::vector<io::SceneData>& scenes) {
    std::cout << "\n### Speed (one thread, this machine): cost stage vs whole pipeline\n\n"
              << "| pair | cost | cost planes (ms) | pipeline (ms) | cost share |\n"
              << "|---|---|---|---|---|\n";
    using Clock = std::chrono::steady_clock;
    const auto ms = [](Clock::duration d) {
        return std::chrono::duration<double, std::milli>(d).count();
    };
    for (const auto& data : scenes) {
        for (const char* name : {"ad", "lcdm"}) {
            const auto cost = make_cost(name);
            const MatchParams params = pipeline_params(data.scene.ndisp, name);
            double best_cost = 1e30;
            double best_match = 1e30;
            for (int repeat = 0; repeat < 3; ++repeat) {
                auto t0 = Clock::now();
                const Dsi volume =
                    cost_volume(*cost, data.pair.left, data.pair.right, params.ndisp);
                auto t1 = Clock::now();
                const DisparityMap map = match(data.pair.left, data.pair.right, params);
                auto t2 = Clock::now();
                best_cost = std::min(best_cost, ms(t1 - t0));
                best_match = std::min(best_match, ms(t2 - t1));
                (void)volume;
                (void)map;
            }
            std::cout << "| " << data.scene.name << " | " << name << " | " << fmt(best_cost, 1)
                      << " | " << fmt(best_match, 1) << " | "
                      << fmt(100.0 * best_cost / best_match, 0) << " % |\n"
                      << std::flush;
        }
    }
}

void run_illumination(const IlluminationOptions& options) {
    check_report_outputs({options.figure}, {}, options.data_dir);
    const auto has = [&](const char* part) {
        return std::find(options.parts.begin(), options.parts.end(), part) != options.parts.end();
    };
    const std::vector<io::SceneData> scenes = load_2003(options.data_dir);
    if (has("ideal")) {
        ideal(scenes);
    }
    if (has("floor")) {
        floor_study(scenes);
    }
    if (has("sweep")) {
        sweep(scenes, options.figure);
    }
    if (has("variable")) {
        variable(scenes);
    }
    if (has("real")) {
        real(options.data_dir);
    }
    if (has("speed")) {
        speed(scenes);
    }
}

}  // namespace

void add_illumination_command(CLI::App& app) {
    const auto [command, options] = cli::add_command<IlluminationOptions>(
        app, "illumination",
        "LCDM against AD, census, ZNCC and SGBM under changed illumination "
        "(docs/results-illumination.md).",
        run_illumination);
    cli::add_data_option(*command, options->data_dir);
    command->add_option("--figure", options->figure, "Write the lightness-sweep plot here (PNG)");
    command
        ->add_option("--parts", options->parts,
                     "Which tables: ideal floor sweep variable real speed (default: all)")
        ->check(CLI::IsMember({"ideal", "floor", "sweep", "variable", "real", "speed"}));
}

}  // namespace stereo::experiments
