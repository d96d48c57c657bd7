#include "earc/bench/options.hpp"

#include <unistd.h>

#include <algorithm>
#include <filesystem>

#include "earc/bench/suites.hpp"
#include "earc/io/input_error.hpp"
#include "earc/io/json_io.hpp"

namespace fs = std::filesystem;

namespace earc::bench {

void requireExecutable(const std::string& path, const std::string& option) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError(path, option, "no such file");
  if (!fs::is_regular_file(path, ec) || ::access(path.c_str(), X_OK) != 0)
    throw InputError(path, option, "not an executable program");
}

void requireOutputDirectory(const std::string& path, const std::string& option) {
  std::error_code ec;
  if (fs::exists(path, ec)) {
    if (!fs::is_directory(path, ec)) throw InputError(path, option, "exists and is not a directory");
    return;
  }
  const std::string ext = lowerExtension(path);
  for (const char* file_ext : {".png", ".svg", ".pdf", ".csv", ".log"})
    if (ext == file_ext)
      throw InputError(path, option, "names the directory the files go into, not a " + ext + " file; give a directory name");
}

std::vector<std::string> splitOptionList(const std::string& list, const std::string& option) {
  if (list.empty()) throw InputError("", option, "empty list");
  std::vector<std::string> items = splitList(list);
  // splitList drops empty items: one is missing for each of them.
  if (items.size() != static_cast<std::size_t>(std::count(list.begin(), list.end(), ',')) + 1)
    throw InputError("", option, "empty item in '" + list + "'");
  return items;
}

std::string reasonAbout(const std::exception& e, const std::string& path) {
  std::string why = e.what();
  if (why.rfind(path + ": ", 0) == 0) why.erase(0, path.size() + 2);
  return why;
}

void requireSeparateOutputs(const std::string& input, const std::string& input_option,
                            const std::vector<std::pair<std::string, std::string>>& outputs) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const auto& [path, option] = outputs[i];
    if (path.empty()) continue;
    if (sameFile(path, input))
      throw InputError(path, option, "is the " + input_option + " file; writing it would destroy that");
    for (const char* suffix : kDatabaseCompanions)
      if (sameFile(path, input + suffix))
        throw InputError(path, option,
                         "is the " + input_option + " file's " + suffix + " file; writing it would destroy that");
    for (std::size_t j = 0; j < i; ++j)
      if (!outputs[j].first.empty() && sameFile(path, outputs[j].first))
        throw InputError(path, option, "is the same file as " + outputs[j].second + " " + outputs[j].first);
  }
}

}  // namespace earc::bench
