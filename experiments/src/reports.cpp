#include <nlohmann/json.hpp>

#include "experiments.hpp"
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

}  // namespace stereo::experiments
