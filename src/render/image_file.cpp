// Writing a rendered picture: SVG as is, PNG through rsvg-convert.
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "earc/io/json_io.hpp"
#include "earc/render/svg.hpp"

extern char** environ;

namespace earc::render {

namespace {

constexpr const char* kConverter = "rsvg-convert";

bool onPath(const std::string& program) {
  const char* path = std::getenv("PATH");
  if (!path) return false;
  std::string dirs(path);
  std::size_t from = 0;
  while (from <= dirs.size()) {
    std::size_t to = dirs.find(':', from);
    if (to == std::string::npos) to = dirs.size();
    const std::string dir = dirs.substr(from, to - from);
    const std::string candidate = (dir.empty() ? "." : dir) + "/" + program;
    if (::access(candidate.c_str(), X_OK) == 0) return true;
    from = to + 1;
  }
  return false;
}

// Runs argv[0] (searched on PATH) and returns its exit status (-1 if it
// could not be started or did not exit normally).
int run(std::vector<std::string> args) {
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawnp(&pid, argv[0], nullptr, nullptr, argv.data(), environ) != 0) return -1;
  int status = 0;
  if (waitpid(pid, &status, 0) < 0 || !WIFEXITED(status)) return -1;
  return WEXITSTATUS(status);
}

}  // namespace

// The checks writeImage makes, for a command to make before its work:
// InputError naming `option` for a name that ends in neither .svg nor .png
// (any case; a device or FIFO gets SVG), std::runtime_error when a .png
// needs rsvg-convert and it is not on PATH (naming the package
// librsvg2-bin). True for PNG.
bool requireImageOutput(const std::string& path, const std::string& option) {
  const bool png = requireOutputExtension({option, path}, {".svg", ".png"}) == ".png";
  if (png && !onPath(kConverter))
    throw std::runtime_error("writing " + path + " needs rsvg-convert, which is not on PATH: install librsvg2-bin "
                             "(apt-get install librsvg2-bin) or write an .svg file");
  return png;
}

void writeImage(const std::string& path, const std::string& svg) {
  if (!requireImageOutput(path, "")) {
    writeTextFileAtomic(path, svg);
    return;
  }
  // Convert into a temporary file beside the target, then rename: a failed
  // conversion never leaves half a picture under the requested name.
  const std::string svg_tmp = path + ".tmp.svg", png_tmp = path + ".tmp.png";
  writeTextFileAtomic(svg_tmp, svg);
  const int status = run({kConverter, "--format", "png", "--output", png_tmp, svg_tmp});
  std::error_code ignored;
  std::filesystem::remove(svg_tmp, ignored);
  if (status != 0) {
    std::filesystem::remove(png_tmp, ignored);
    throw std::runtime_error(std::string(kConverter) + " failed to convert the picture for " + path);
  }
  std::filesystem::rename(png_tmp, path);
}

}  // namespace earc::render
