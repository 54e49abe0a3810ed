// Co-simulation on demand (on_demand.hpp): the cache of Verilated runners and the process that
// drives one.
#include "on_demand.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <optional>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include "cosim_protocol.hpp"
#include "stereo/catalogue.hpp"
#include "stereo/constants.hpp"
#include "stereo/stage_table.hpp"

extern char** environ;

namespace stereo::sim {
namespace fs = std::filesystem;

namespace {

// Where the sources a runner is built from live: $STEREO_SOURCE_DIR, else the source tree this
// tool was built from (STEREO_SOURCE_DIR, sim/CMakeLists.txt).
fs::path source_root() {
    if (const char* root = std::getenv("STEREO_SOURCE_DIR"); root != nullptr && *root != '\0') {
        return root;
    }
    return STEREO_SOURCE_DIR;
}

// "ad or census": the costs of the lean memory core.
std::string lean_costs() {
    return catalogue::join(
        catalogue::cost_names_if([](const catalogue::CostRow& row) { return row.lean_core; }),
        " or ");
}

int cost_parameter(const std::string& cost) {
    catalogue::require_cost(cost, catalogue::CostUse::hardware, "a core built on demand");
    return catalogue::cost(cost).hardware_code;
}

int lanes_of(const CoreRequest& request) {
    return request.lanes == 0 ? request.ndisp : request.lanes;
}

std::string read_file(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw std::runtime_error("cosim: cannot read " + path.string() +
                                 " (the runner is built from the project's sources; set "
                                 "STEREO_SOURCE_DIR to the source tree)");
    }
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The RTL sources in rtl/files.f order (lines that are not comments).
std::vector<fs::path> rtl_sources(const fs::path& rtl) {
    std::istringstream list(read_file(rtl / "files.f"));
    std::vector<fs::path> sources;
    for (std::string line; std::getline(list, line);) {
        if (!line.empty() && line[0] != '/') {
            sources.push_back(rtl / line);
        }
    }
    return sources;
}

// Every file the runner is built from, in a fixed order.
std::vector<fs::path> runner_inputs(const fs::path& root) {
    std::vector<fs::path> inputs = rtl_sources(root / "rtl");
    std::vector<fs::path> headers;
    for (const fs::path folder : {root / "rtl", root / "model" / "include" / "stereo"}) {
        for (const auto& entry : fs::directory_iterator(folder)) {
            const auto extension = entry.path().extension();
            if (extension == ".svh" || extension == ".hpp") {
                headers.push_back(entry.path());
            }
        }
    }
    std::sort(headers.begin(), headers.end());
    inputs.insert(inputs.end(), headers.begin(), headers.end());
    for (const char* name : {"cosim_runner_main.cpp", "cosim_protocol.hpp", "axis_driver.hpp",
                             "verilated_harness.hpp", "port_bits.hpp", "stereo_top_sim.hpp"}) {
        inputs.push_back(root / "sim" / name);
    }
    return inputs;
}

// FNV-1a, 64 bits: a cache key, not a security boundary.
std::uint64_t fnv1a(std::uint64_t hash, const std::string& bytes) {
    for (const char c : bytes) {
        hash ^= static_cast<unsigned char>(c);
        hash *= 1099511628211ULL;
    }
    return hash;
}

std::string verilator_program() {
    const char* chosen = std::getenv("STEREO_VERILATOR");
    return chosen != nullptr && *chosen != '\0' ? chosen : "verilator";
}

// Runs `argv` with stdout and stderr into `log` (or /dev/null), in `folder` when given; returns
// the exit status, or -1 when the program could not be started.
int run_program(const std::vector<std::string>& argv, const fs::path& log,
                const std::vector<std::string>& extra_env = {}) {
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    const std::string log_path = log.empty() ? "/dev/null" : log.string();
    posix_spawn_file_actions_addopen(&actions, 1, log_path.c_str(), O_WRONLY | O_CREAT | O_APPEND,
                                     0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    // Verilator, make and the compiler get the default SIGPIPE and SIGXFSZ back (the tool ignores
    // both to report write errors itself, and an ignored signal would be inherited).
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    sigset_t defaults;
    sigemptyset(&defaults);
    sigaddset(&defaults, SIGPIPE);
    sigaddset(&defaults, SIGXFSZ);
    posix_spawnattr_setsigdefault(&attributes, &defaults);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGDEF);
    std::vector<char*> args;
    for (const std::string& arg : argv) {
        args.push_back(const_cast<char*>(arg.c_str()));
    }
    args.push_back(nullptr);
    std::vector<std::string> env_strings(extra_env);
    for (char** e = environ; *e != nullptr; ++e) {
        env_strings.emplace_back(*e);
    }
    std::vector<char*> env;
    for (std::string& entry : env_strings) {
        env.push_back(entry.data());
    }
    env.push_back(nullptr);
    pid_t pid = 0;
    const int spawned = posix_spawnp(&pid, args[0], &actions, &attributes, args.data(), env.data());
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attributes);
    if (spawned != 0) {
        return -1;
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0) {
        if (errno != EINTR) {
            return -1;
        }
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// The first line of `program --version`, empty when it does not run.
std::string version_of(const std::string& program, const fs::path& scratch) {
    const fs::path out = scratch / "version.txt";
    std::error_code ignored;
    fs::remove(out, ignored);
    if (run_program({program, "--version"}, out) != 0) {
        return {};
    }
    std::istringstream text(read_file(out));
    std::string line;
    std::getline(text, line);
    fs::remove(out, ignored);
    return line;
}

// The C++ compiler of the Verilated code: $STEREO_COSIM_CXX when set, otherwise clang++ when it
// runs (measured at 640x480 / 64 labels, docs/gtkwave.md: the same core simulates in 2.0 s built
// by clang++ against 2.6 s by g++, both -O2 -march=native), otherwise Verilator's default.
// Empty: Verilator's default.
std::string simulation_compiler(const fs::path& scratch) {
    if (const char* chosen = std::getenv("STEREO_COSIM_CXX"); chosen != nullptr) {
        return chosen;
    }
    return version_of("clang++", scratch).empty() ? std::string{} : "clang++";
}

// The instruction-set line of /proc/cpuinfo: the runners are built for this processor
// (-march=native), so a cache folder shared between machines keeps one runner per processor kind.
std::string processor_features() {
    std::ifstream cpuinfo("/proc/cpuinfo");
    std::string line;
    while (std::getline(cpuinfo, line)) {
        if (line.starts_with("flags") || line.starts_with("Features")) {
            return line;
        }
    }
    return {};
}

// "-march=native " when `compiler` (empty: c++) accepts it (older clang++ on AArch64 does not),
// else nothing: the runner is then built for the generic target.
std::string native_flag(const std::string& compiler, const fs::path& scratch) {
    const fs::path source = scratch / "native.cpp";
    std::ofstream(source) << "int main() { return 0; }\n";
    const int status =
        run_program({compiler.empty() ? std::string{"c++"} : compiler, "-march=native", "-c",
                     source.string(), "-o", (scratch / "native.o").string()},
                    {});
    return status == 0 ? "-march=native " : "";
}

std::string last_line(const fs::path& log) {
    std::ifstream in(log);
    std::string line;
    std::string last;
    std::string error;
    while (std::getline(in, line)) {
        if (!line.empty()) {
            last = line;
            if (error.empty() && line.find("%Error") != std::string::npos) {
                error = line;
            }
        }
    }
    return error.empty() ? last : error;
}

std::string describe(const CoreRequest& request) {
    return std::to_string(request.width) + "x" + std::to_string(request.height) + ", " +
           std::to_string(request.ndisp) + " labels, window " + std::to_string(request.window) +
           ", cost " + request.cost + ", LANES " + std::to_string(lanes_of(request)) +
           ", MAX_MIN_DISP " + std::to_string(request.max_min_disp) +
           (request.lean ? ", lean memory" : "");
}

std::string folder_name(const CoreRequest& request) {
    return std::to_string(request.width) + "x" + std::to_string(request.height) + "-n" +
           std::to_string(request.ndisp) + "-w" + std::to_string(request.window) + "-" +
           request.cost + "-l" + std::to_string(lanes_of(request)) + "-m" +
           std::to_string(request.max_min_disp) + (request.lean ? "-lean" : "");
}

// $STEREO_COSIM_DEFINES: macro names for the RTL (the test hooks), checked.
std::vector<std::string> rtl_defines() {
    std::vector<std::string> names;
    const char* text = std::getenv("STEREO_COSIM_DEFINES");
    if (text == nullptr) {
        return names;
    }
    std::istringstream words(text);
    for (std::string name; words >> name;) {
        const bool valid = (std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_') &&
                           std::all_of(name.begin(), name.end(), [](char c) {
                               return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
                           });
        if (!valid) {
            throw std::invalid_argument("STEREO_COSIM_DEFINES: '" + name + "' is not a macro name");
        }
        names.push_back(name);
    }
    return names;
}

// A new folder `cache`/PREFIX-XXXXXX made by mkdtemp.
fs::path private_folder(const fs::path& cache, const std::string& prefix) {
    std::string pattern = (cache / (prefix + "-XXXXXX")).string();
    if (::mkdtemp(pattern.data()) == nullptr) {
        throw std::runtime_error("cosim: the cache folder " + cache.string() +
                                 " is not writable (" + std::strerror(errno) + ")");
    }
    return pattern;
}

// The cache folder's name: the configuration, then what else changes the runner.
std::string entry_name(const CoreRequest& request, const std::vector<std::string>& defines) {
    return folder_name(request) + (request.probes ? "-probes" : "") +
           (request.trace ? "-trace" : "") +
           (request.threads > 1 ? "-t" + std::to_string(request.threads) : "") +
           (defines.empty() ? "" : "-defines");
}

}  // namespace

void check_request(const CoreRequest& r) {
    const auto fail = [&r](const std::string& what) {
        throw std::invalid_argument("co-simulation core " + std::to_string(r.width) + "x" +
                                    std::to_string(r.height) + " / " + std::to_string(r.ndisp) +
                                    " labels / window " + std::to_string(r.window) + ": " + what);
    };
    if (r.width < 1 || r.height < 1 || r.width > kMaxCoreSide || r.height > kMaxCoreSide) {
        fail("the frame must be 1.." + std::to_string(kMaxCoreSide) +
             " pixels on each side (the limit of the on-demand cache)");
    }
    if (r.ndisp < 1 || r.ndisp > kMaxCoreNdisp) {
        fail("NDISP must be in 1.." + std::to_string(kMaxCoreNdisp));
    }
    if (r.window < 1 || r.window > fx::kMaxWindow || r.window % 2 == 0) {
        fail("the window must be odd, 1.." + std::to_string(fx::kMaxWindow));
    }
    if (r.window > r.width || r.window > r.height) {
        fail("the window is larger than the frame");
    }
    const int lanes = lanes_of(r);
    if (lanes < 1 || lanes > r.ndisp || r.ndisp % lanes != 0) {
        fail("LANES " + std::to_string(lanes) + " must divide NDISP " + std::to_string(r.ndisp));
    }
    if (r.max_min_disp < 0 || r.max_min_disp > fx::kMaxMinDisparity) {
        fail("MAX_MIN_DISP must be in 0.." + std::to_string(fx::kMaxMinDisparity));
    }
    cost_parameter(r.cost);
    if (r.threads < 1 || r.threads > kMaxCoreThreads) {
        fail("the simulation threads must be 1.." + std::to_string(kMaxCoreThreads));
    }
    if (r.probes && lanes != r.ndisp) {
        fail("stage probes need every label in one clock (LANES = NDISP)");
    }
    if (r.lean && !catalogue::cost(r.cost).lean_core) {
        fail("the lean memory architecture has no " + r.cost + " form (" + lean_costs() + ")");
    }
}

void check_fits(const CoreRequest& request, int width, int height, int min_disp) {
    if (width > request.width || height > request.height) {
        throw std::invalid_argument("the pair is " + std::to_string(width) + "x" +
                                    std::to_string(height) + ", larger than the core's " +
                                    std::to_string(request.width) + "x" +
                                    std::to_string(request.height));
    }
    if (std::abs(min_disp) > request.max_min_disp) {
        throw std::invalid_argument("minimum disparity " + std::to_string(min_disp) +
                                    " is beyond the core's MAX_MIN_DISP " +
                                    std::to_string(request.max_min_disp));
    }
}

TopConfig on_demand_config(const CoreRequest& request) {
    check_request(request);
    return {"on-demand " + folder_name(request),
            request.width,
            request.height,
            request.ndisp,
            request.window,
            request.max_min_disp,
            lanes_of(request),
            cost_parameter(request.cost)};
}

fs::path default_cache_folder() {
    if (const char* chosen = std::getenv("STEREO_COSIM_CACHE");
        chosen != nullptr && *chosen != '\0') {
        return chosen;
    }
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg != nullptr && *xdg != '\0') {
        return fs::path(xdg) / "stereo" / "cosim";
    }
    if (const char* home = std::getenv("HOME"); home != nullptr && *home != '\0') {
        return fs::path(home) / ".cache" / "stereo" / "cosim";
    }
    return fs::temp_directory_path() / "stereo-cosim";
}

fs::path ensure_runner(const CoreRequest& request, const fs::path& cache_folder,
                       std::ostream& progress) {
    check_request(request);
    // Absolute: Verilator runs make in its object folder, where a relative path means another.
    const fs::path cache = fs::absolute(cache_folder);
    const std::vector<std::string> defines = rtl_defines();
    const fs::path root = source_root();
    const std::vector<fs::path> inputs = runner_inputs(root);

    std::error_code error;
    fs::create_directories(cache, error);
    if (error || !fs::is_directory(cache)) {
        throw std::runtime_error("cosim: cannot use the cache folder " + cache.string() + " (" +
                                 (error ? error.message() : "not a folder") + ")");
    }
    // A private scratch folder (mkdtemp: a fresh name no one can predict or plant a link at,
    // mode 0700): everything of this build goes there and is renamed into place.
    const fs::path scratch = private_folder(cache, ".build-" + entry_name(request, defines));
    struct RemoveOnExit {
        fs::path path;
        ~RemoveOnExit() {
            std::error_code ignored;
            fs::remove_all(path, ignored);
        }
    } cleanup{scratch};

    const std::string verilator = verilator_program();
    const std::string version = version_of(verilator, scratch);
    if (version.empty()) {
        throw std::runtime_error("cosim: cannot run '" + verilator + " --version': Verilator " +
                                 "is needed to build the core " + describe(request) +
                                 " on demand (Debian: apt-get install verilator; or set " +
                                 "STEREO_VERILATOR)");
    }
    std::uint64_t hash = 14695981039346656037ULL;
    std::string defines_text;
    for (const std::string& name : defines) {
        defines_text += name + " ";
    }
    const std::string compiler = simulation_compiler(scratch);
    const std::string native = native_flag(compiler, scratch);
    const std::string compiler_version =
        version_of(compiler.empty() ? std::string{"c++"} : compiler, scratch);
    hash = fnv1a(hash, std::to_string(protocol::kVersion) + "\n" + entry_name(request, defines) +
                           "\n" + version + "\n" + defines_text + "\n" + compiler_version + "\n" +
                           processor_features() + "\n" + native + "\n");
    for (const fs::path& input : inputs) {
        hash = fnv1a(hash, input.filename().string() + "\n" + read_file(input));
    }
    char key[17];
    std::snprintf(key, sizeof key, "%016llx", static_cast<unsigned long long>(hash));
    const fs::path folder = cache / (entry_name(request, defines) + "-" + key);
    const fs::path runner = folder / "runner";
    if (fs::is_regular_file(runner)) {
        return runner;
    }

    progress << "cosim: building the Verilated core " << describe(request)
             << (request.probes ? " with stage probes" : "")
             << (defines.empty() ? "" : " with " + defines_text + "defined") << " into "
             << folder.string() << " (first use of this configuration; a minute or more)"
             << std::endl;
    const auto start = std::chrono::steady_clock::now();
    const fs::path log = scratch / "build.log";
    const unsigned jobs = std::max(1U, std::thread::hardware_concurrency());
    std::vector<std::string> argv = {
        verilator, "--cc", "--exe", "--build", "-j", std::to_string(jobs), "--Mdir",
        (scratch / "obj").string(), "-o", (scratch / "runner").string(), "-Wno-fatal", "-Wno-lint",
        "-Wno-style", "--x-assign", "fast", "--x-initial", "unique", "-O3", "--top-module",
        "stereo_top", "--prefix", "Vstereo_top", "-GWIDTH=" + std::to_string(request.width),
        "-GHEIGHT=" + std::to_string(request.height), "-GNDISP=" + std::to_string(request.ndisp),
        "-GWINDOW=" + std::to_string(request.window),
        "-GLANES=" + std::to_string(lanes_of(request)),
        "-GMAX_MIN_DISP=" + std::to_string(request.max_min_disp),
        // COST is an fx_pkg::cost_e: its code needs -Wno-ENUMVALUE; RECOMPUTE_COSTS is a bit.
        "-GCOST=" + std::to_string(cost_parameter(request.cost)), "-Wno-ENUMVALUE",
        "-GRECOMPUTE_COSTS=" + std::string(request.lean ? "1'b1" : "1'b0"),
        "-I" + (root / "rtl").string(),
        // verilated.mk compiles the model's hot code with
        // OPT_FAST (-Os by default): -O2 simulates 20 % faster,
        // -O3 no faster (measured, docs/gtkwave.md).
        "-MAKEFLAGS", "OPT_FAST=-O2", "-CFLAGS",
        "-std=c++20 -O2 " + native + "-I" + (root / "sim").string() + " -I" +
            (root / "model" / "include").string()};
    if (!compiler.empty()) {
        argv.emplace_back("-MAKEFLAGS");
        argv.push_back("CXX=" + compiler);
    }
    if (request.trace) {
        argv.emplace_back("--trace-fst");
    }
    if (request.threads > 1) {
        argv.emplace_back("--threads");
        argv.push_back(std::to_string(request.threads));
    }
    if (request.probes) {
        argv.emplace_back("--public-flat-rw");
        argv.emplace_back("-CFLAGS");
        argv.emplace_back("-DSTEREO_RUNNER_PROBES=1 -DSTEREO_PROBE_NDISP=" +
                          std::to_string(request.ndisp));
    }
    for (const std::string& name : defines) {
        argv.push_back("+define+" + name);
    }
    for (const fs::path& source : rtl_sources(root / "rtl")) {
        argv.push_back(source.string());
    }
    argv.push_back((root / "sim" / "cosim_runner_main.cpp").string());
    std::vector<std::string> env;
    if (version_of("ccache", scratch).size() > 0) {
        env.emplace_back("OBJCACHE=ccache");  // verilated.mk compiles through it
    }
    const int status = run_program(argv, log, env);
    if (status != 0 || !fs::is_regular_file(scratch / "runner")) {
        throw std::runtime_error(
            "cosim: building the core " + describe(request) + " failed (" + verilator +
            (status < 0 ? " could not start" : " exited with status " + std::to_string(status)) +
            "): " + last_line(log));
    }
    // Only the runner is kept; the rename makes it visible whole.
    const fs::path staged = private_folder(cache, ".ready-" + entry_name(request, defines));
    fs::permissions(staged,
                    fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                        fs::perms::others_read | fs::perms::others_exec,
                    error);  // the cache entry it becomes is read by everyone, as before
    fs::rename(scratch / "runner", staged / "runner", error);
    if (!error) {
        fs::rename(staged, folder, error);
    }
    if (error) {
        std::error_code ignored;
        fs::remove_all(staged, ignored);
        if (!fs::is_regular_file(runner)) {  // another process may have put the same one there
            throw std::runtime_error("cosim: cannot move the built core into " + folder.string() +
                                     " (" + error.message() + ")");
        }
    }
    progress << "cosim: built in "
             << std::chrono::duration_cast<std::chrono::seconds>(std::chrono::steady_clock::now() -
                                                                 start)
                    .count()
             << " s" << std::endl;
    return runner;
}

namespace {

// The runner as a child process; closing its input ends it.
class RunnerSim final : public TopSim {
  public:
    RunnerSim(TopConfig config, const fs::path& runner) : config_(std::move(config)) {
        // A runner that dies must turn into an error here, not a SIGPIPE of the tool.
        struct sigaction ignore = {};
        ignore.sa_handler = SIG_IGN;
        sigaction(SIGPIPE, &ignore, nullptr);
        std::array<int, 2> to_child{};
        std::array<int, 2> from_child{};
        if (::pipe2(to_child.data(), O_CLOEXEC) != 0) {
            throw std::runtime_error("cosim: cannot create a pipe to the runner");
        }
        if (::pipe2(from_child.data(), O_CLOEXEC) != 0) {
            ::close(to_child[0]);
            ::close(to_child[1]);
            throw std::runtime_error("cosim: cannot create a pipe from the runner");
        }
        posix_spawn_file_actions_t actions;
        posix_spawn_file_actions_init(&actions);
        posix_spawn_file_actions_adddup2(&actions, to_child[0], 0);
        posix_spawn_file_actions_adddup2(&actions, from_child[1], 1);
        const std::string path = runner.string();
        char* argv[] = {const_cast<char*>(path.c_str()), nullptr};
        const int spawned = posix_spawn(&pid_, path.c_str(), &actions, nullptr, argv, environ);
        posix_spawn_file_actions_destroy(&actions);
        ::close(to_child[0]);
        ::close(from_child[1]);
        write_fd_ = to_child[1];
        read_fd_ = from_child[0];
        if (spawned != 0) {
            pid_ = -1;
            close_pipes();
            throw std::runtime_error("cosim: cannot start the runner " + path + " (" +
                                     std::strerror(spawned) + ")");
        }
        channel_.emplace(read_fd_, write_fd_);
    }
    RunnerSim(const RunnerSim&) = delete;
    RunnerSim& operator=(const RunnerSim&) = delete;
    ~RunnerSim() override {
        close_pipes();  // the runner sees the end of its input and exits
        if (pid_ > 0) {
            int status = 0;
            while (waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
            }
        }
    }

    const TopConfig& config() const override { return config_; }

    void reset() override {
        channel_->put(protocol::kReset);
        request_ok();
    }

    void set_params(const CoreParams& params) override {
        channel_->put(protocol::kParams);
        protocol::put_ports(*channel_, port_values(config_, params));
        request_ok();
    }

    StreamResult stream(const std::vector<InputBeat>& beats, std::size_t expected_outputs,
                        const Traffic& traffic, std::uint64_t max_cycles) override {
        channel_->put(protocol::kStream);
        protocol::put_beats(*channel_, beats);
        channel_->put(static_cast<std::uint64_t>(expected_outputs));
        channel_->put(traffic.input_gap);
        channel_->put(traffic.output_stall);
        channel_->put(static_cast<std::uint32_t>(traffic.seed));
        channel_->put(max_cycles);
        request_ok();
        return protocol::get_result(*channel_, expected_outputs);
    }

    void trace_to(const std::string& path) override {
        check_trace_path(path);
        channel_->put(protocol::kTrace);
        channel_->put_string(path);
        request_ok();
    }

    std::vector<protocol::PixelProbe> probe(const std::vector<InputBeat>& beats,
                                            const std::vector<std::pair<int, int>>& pixels) {
        channel_->put(protocol::kWatch);
        channel_->put(static_cast<std::uint32_t>(pixels.size()));
        for (const auto& [x, y] : pixels) {
            channel_->put(static_cast<std::int32_t>(x));
            channel_->put(static_cast<std::int32_t>(y));
        }
        request_ok();
        const StreamResult result =
            stream(beats, beats.size(), Traffic{}, 100 * beats.size() + 100000);
        if (!result.completed) {
            throw std::runtime_error("cosim: the probe run stalled");
        }
        channel_->put(protocol::kGetProbes);
        request_ok();
        return protocol::get_probes(*channel_);
    }

  private:
    void request_ok() {
        try {
            channel_->flush();
            const auto reply = channel_->get<char>();
            if (reply == protocol::kError) {
                throw std::runtime_error(channel_->get_string());
            }
            if (reply != protocol::kOk) {
                throw std::runtime_error("cosim: unexpected reply from the runner");
            }
        } catch (const std::runtime_error&) {
            if (!runner_alive()) {
                throw std::runtime_error("cosim: the co-simulation runner of '" + config_.name +
                                         "' ended unexpectedly");
            }
            throw;
        }
    }

    bool runner_alive() {
        if (pid_ <= 0) {
            return false;
        }
        int status = 0;
        if (waitpid(pid_, &status, WNOHANG) == pid_) {
            pid_ = -1;
            return false;
        }
        return true;
    }

    void close_pipes() {
        for (int* fd : {&write_fd_, &read_fd_}) {
            if (*fd >= 0) {
                ::close(*fd);
                *fd = -1;
            }
        }
    }

    TopConfig config_;
    pid_t pid_ = -1;
    int write_fd_ = -1;
    int read_fd_ = -1;
    std::optional<protocol::Channel> channel_;
};

}  // namespace

std::unique_ptr<TopSim> make_runner_sim(const TopConfig& config, const fs::path& runner) {
    return std::make_unique<RunnerSim>(config, runner);
}

std::vector<std::string> probed_stages() {
    return {std::begin(protocol::kProbedStages), std::end(protocol::kProbedStages)};
}

std::vector<PixelStages> probe_stages(CoreRequest request, const fs::path& cache,
                                      const CoreParams& params, const std::vector<InputBeat>& beats,
                                      const std::vector<std::pair<int, int>>& pixels,
                                      std::ostream& progress) {
    request.probes = true;
    request.trace = false;
    request.threads = 1;
    const fs::path runner = ensure_runner(request, cache, progress);
    RunnerSim sim(on_demand_config(request), runner);
    sim.reset();
    sim.set_params(params);
    std::vector<PixelStages> out;
    for (const protocol::PixelProbe& probe : sim.probe(beats, pixels)) {
        PixelStages pixel{probe.x, probe.y, {}, {}};
        for (int stage = 0; stage < protocol::kProbedStageCount; ++stage) {
            pixel.seen.push_back(probe.seen[stage]);
            pixel.values.push_back(probe.values[stage]);
        }
        out.push_back(std::move(pixel));
    }
    return out;
}

}  // namespace stereo::sim
