#include <nlohmann/json.hpp>

#include <filesystem>
#include <iostream>
#include <stdexcept>

#include "experiments.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/output.hpp"
#include "stereo_io/versioned_json.hpp"

namespace stereo::experiments {

void add_report_files(OutputFiles& files, const std::string& markdown_path,
                      const std::string& markdown, const std::string& json_path,
                      const nlohmann::json& report) {
    if (!markdown_path.empty()) {
        files.emplace_back(markdown_path, markdown);
    }
    if (!json_path.empty()) {
        files.emplace_back(json_path, io::versioned(report).dump(2) + '\n');
    }
}

void print_and_write_report(OutputFiles files, const std::string& markdown_path,
                            const std::string& markdown, const std::string& json_path,
                            const nlohmann::json& report) {
    std::cout << markdown;
    add_report_files(files, markdown_path, markdown, json_path, report);
    io::write_files_atomic(files);
}

void check_report_outputs(const std::vector<std::string>& files,
                          const std::vector<std::string>& folders) {
    std::vector<std::filesystem::path> outputs(files.begin(), files.end());
    io::check_outputs_distinct(outputs, {});
    for (const std::string& file : files) {
        if (!file.empty()) {
            io::check_writable_location(file);
        }
    }
    for (const std::string& folder : folders) {
        if (!folder.empty() && !std::filesystem::is_directory(folder)) {
            throw std::runtime_error("figure folder '" + folder + "' does not exist");
        }
    }
}

}  // namespace stereo::experiments
