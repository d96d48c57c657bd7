// Reading and writing the contract's JSON formats (shared/spec/formats.md).
// Readers ignore unknown keys (with a warning) and throw InputError naming
// the file, the JSON path and the reason for anything else that is wrong.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "earc/io/input_error.hpp"
#include "earc/scene/scenario.hpp"
#include "earc/scene/solution.hpp"

namespace earc {

inline constexpr const char* kScenarioFormat = "earc.scenario.v1";
inline constexpr const char* kSolutionFormat = "earc.solution.v1";

// Parse JSON text strictly: no NaN/Infinity literals, no duplicate keys.
// `file` only names the source in errors.
nlohmann::json parseJsonText(const std::string& text, const std::string& file);
nlohmann::json readJsonFile(const std::string& path);
// Inputs read whole (scenarios, solutions, traces, maps, Lightning
// databases) stop here: a scenario of 200,000 obstacles is about 20 MB.
inline constexpr std::size_t kMaxTextFileBytes = std::size_t{256} << 20;
// A whole file's bytes. Throws InputError naming the file when it cannot be
// opened or read, is a directory, or holds more than kMaxTextFileBytes.
std::string readTextFile(const std::string& path);
// Appends v as JSON text: the fewest digits that read back to v, laid out as
// nlohmann::json prints a double ("2.0", "0.05", "1e-07"); "null" when not
// finite. Thread-safe.
void appendJsonDouble(std::string& out, double v);
// v as compact JSON text (nlohmann::json's dump()), invalid UTF-8 in its
// strings replaced rather than thrown on. Thread-safe.
std::string dumpCompact(const nlohmann::json& v);
// Writes atomically (temporary file, fsync, rename), through a symbolic link,
// directly to a device or FIFO. Throws InputError naming the file on failure.
void writeTextFileAtomic(const std::string& path, const std::string& text);

// As writeTextFileAtomic for output written as it comes; commit() names the
// file, destruction uncommitted leaves the old file. Streams are written directly.
class AtomicFile {
 public:
  explicit AtomicFile(const std::string& path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  void write(std::string_view text);
  void commit();

 private:
  std::string given_, path_, tmp_;
  int fd_ = -1;
  bool special_ = false, anonymous_ = false, named_ = false, committed_ = false;
};

// Writes all of `bytes` to fd (retrying short writes); throws naming `path`.
// The caller closes fd.
void writeAll(int fd, std::string_view bytes, const std::string& path);

// fsync the directory holding `path`, so that a rename into it survives a
// crash (best effort).
void syncDirectoryOf(const std::string& path);

// The files SQLite keeps beside a database: part of the database.
inline constexpr const char* kDatabaseCompanions[] = {"-wal", "-shm", "-journal"};

// A command's file argument: what the user called it ("-o", "--trace",
// "scenario") and the path given.
struct NamedPath {
  std::string name;
  std::string path;
  // An SQLite database: its kDatabaseCompanions files are part of it.
  bool database = false;
};
// Whether two paths name one file: by identity (links included) when both
// exist, else by their absolute normal forms.
bool sameFile(const std::string& a, const std::string& b);
// Refuses (InputError naming the later path) two paths that are one file, so
// that an output never overwrites an input or another output; empty ignored.
void requireDistinctFiles(const std::vector<NamedPath>& paths);
// Refuses (InputError) an output path that cannot be written: a directory,
// or in a missing or unwritable directory. Cheap: call it before long work.
void requireWritableOutput(const NamedPath& output);
// A name's extension in lower case, with its dot ("R.SVG" -> ".svg").
std::string lowerExtension(const std::string& path);
// Refuses (InputError) an output file name (or link target) not ending in
// one of `extensions`, in any case. Returns the one matched, "" for a device.
std::string requireOutputExtension(const NamedPath& output, const std::vector<std::string>& extensions);
// Where a command's summary line goes: stdout, unless one of its outputs is
// the file stdout writes to (-o /dev/stdout, or -o x.json > x.json), whose
// contents a summary line there would corrupt: then stderr.
std::ostream& summaryStream(const std::vector<std::string>& outputs);

// Warnings about input read all the same (unknown key, degrees-like heading,
// obstacle outside the workspace); readers given nullptr print them, once the
// whole input is read.
using InputWarnings = std::vector<InputWarning>;
// "PROGRAM: warning: FILE: PATH: REASON", made printable (control
// characters as '?'), without a line break.
std::string inputWarningLine(const InputWarning& warning, std::string_view program);
// Each warning as an inputWarningLine on stderr, PROGRAM being the running
// program's name (earc-plan, earc-db, earc-bench).
void printInputWarnings(const InputWarnings& warnings);

// Structure and types only (no geometry).
Scenario scenarioFromJson(const nlohmann::json& doc, const std::string& file, InputWarnings* warnings = nullptr);
nlohmann::json scenarioToJson(const Scenario& s);

// A scenario file read: structure and types only (no geometry; loadScenario
// in validate/scenario_check.hpp also checks starts and goals).
Scenario readScenarioFile(const std::string& path, InputWarnings* warnings = nullptr);

// Paths must match the scenario's robots (names, dimensions) when one is given.
Solution solutionFromJson(const nlohmann::json& doc, const Scenario* scenario, const std::string& file,
                          InputWarnings* warnings = nullptr);
// Without paths (with_paths false), the document appendSolutionPaths completes.
nlohmann::json solutionToJson(const Solution& s, bool with_paths = true);
// The solution's "paths" array as compact JSON appended to out: the values
// of solutionToJson(s)["paths"], each double in the shortest digits that read back.
void appendSolutionPaths(std::string& out, const Solution& s);
Solution loadSolution(const std::string& path, const Scenario* scenario, InputWarnings* warnings = nullptr);
void saveSolution(const std::string& path, const Solution& s);

}  // namespace earc
