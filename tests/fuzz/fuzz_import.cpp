// libFuzzer target: the import reader (earc-db import). The bytes become a
// file, read by readImportSource as earc-db import reads it: a JSON-lines
// export, or, when they start with the SQLite header, a database opened as
// hostile (read-only, quick_check, cell_size_check, no mmap). Bad input must
// end in InputError (one line, exit 2); anything else escaping is a finding.
// Every line is also fed to experienceFromJson alone.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "earc/experience/transfer.hpp"
#include "earc/io/input_error.hpp"
#include "earc/io/json_io.hpp"

namespace {

const std::string& scratchFile() {
  static const std::string path = [] {
    const char* tmp = std::getenv("TMPDIR");
    std::string p = std::string(tmp && *tmp ? tmp : "/tmp") + "/earc-fuzz-import-" + std::to_string(::getpid());
    return p;
  }();
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string& path = scratchFile();
  if (std::FILE* f = std::fopen(path.c_str(), "wb")) {
    if (size) std::fwrite(data, 1, size, f);
    std::fclose(f);
  } else {
    std::abort();
  }
  try {
    (void)earc::exp::readImportSource(path);
  } catch (const earc::InputError&) {
  }
  std::remove(path.c_str());
  // The row reader alone, on each line.
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::size_t begin = 0;
  int lines = 0;
  while (begin < text.size() && lines++ < 16) {
    std::size_t end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    try {
      nlohmann::json row = earc::parseJsonText(text.substr(begin, end - begin), "fuzz.jsonl");
      (void)earc::exp::experienceToJson(earc::exp::experienceFromJson(row, "fuzz.jsonl", "line")).dump();
    } catch (const earc::InputError&) {
    }
    begin = end + 1;
  }
  return 0;
}
