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
    add_report_files(files, markdown_path, markdown, json_path, report);
    io::write_files_atomic(files);
    std::cout << markdown;  // after the files: no report on stdout for a run that then fails
}

void check_report_outputs(const std::vector<std::string>& files,
                          const std::vector<std::string>& folders, const std::string& data_dir) {
    std::vector<std::filesystem::path> outputs(files.begin(), files.end());
    // A figure folder inside the data: a name in it stands for the figures (none exists yet).
    for (const std::string& folder : folders) {
        if (!folder.empty()) {
            outputs.push_back(std::filesystem::path(folder) / ".figures");
        }
    }
    io::check_outputs(outputs, {.folders = {data_dir}});
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
