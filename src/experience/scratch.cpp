#include "earc/experience/scratch.hpp"

#include <stdlib.h>

#include <stdexcept>
#include <system_error>
#include <vector>

namespace earc::exp {

ScratchDirectory::ScratchDirectory(const std::string& label) {
  std::string pattern = (std::filesystem::temp_directory_path() / ("earc-" + label + "-XXXXXX")).string();
  std::vector<char> buf(pattern.begin(), pattern.end());
  buf.push_back('\0');
  // mkdtemp: a new directory only we can enter, with a name nobody else has.
  if (!mkdtemp(buf.data())) throw std::runtime_error("cannot create a temporary directory like " + pattern);
  path_ = buf.data();
}

ScratchDirectory::~ScratchDirectory() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

}  // namespace earc::exp
