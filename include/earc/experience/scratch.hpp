// A private temporary directory removed with everything in it when the
// object dies: scratch databases for benchmarks and tests.
#pragma once

#include <filesystem>
#include <string>

namespace earc::exp {

class ScratchDirectory {
 public:
  // Creates a fresh directory under the system temporary directory
  // ($TMPDIR or /tmp) named after `label`. Throws std::runtime_error.
  explicit ScratchDirectory(const std::string& label);
  ~ScratchDirectory();
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

}  // namespace earc::exp
