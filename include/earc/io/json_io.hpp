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
// Write atomically (temporary file, fsync, rename): a crash leaves the old
// file or the new one, never half of one. A symbolic link is written
// through (its target replaced, the link kept); a device or FIFO (such as
// /dev/stdout) is written to directly, never replaced by a file. Throws
// InputError naming the file when it cannot be written.
void writeTextFileAtomic(const std::string& path, const std::string& text);

// The same for output too large to hold in memory at once: write() it as
// it comes; commit() names the file. Destroyed uncommitted (an error on the
// way), it leaves the old file as it was and no temporary. A stream
// (/dev/stdout, a FIFO or device) is written as it comes: what was written
// before an error stays written.
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

// A command's file argument: what the user called it ("-o", "--trace",
// "scenario") and the path given.
// The files SQLite keeps beside a database (committed rows not yet in it,
// lock state, a rollback in progress): part of the database.
inline constexpr const char* kDatabaseCompanions[] = {"-wal", "-shm", "-journal"};

struct NamedPath {
  std::string name;
  std::string path;
  // An SQLite database: its kDatabaseCompanions files are part of it.
  bool database = false;
};
// Whether two paths name one file: by identity (links included) when both
// exist, else by their absolute normal forms.
bool sameFile(const std::string& a, const std::string& b);
// Refuses (InputError naming the later path) when two of the paths are
// one file, so that an output never overwrites an input or another
// output. Empty paths are ignored. Existing files are compared by
// identity (links included), others by their absolute normal form.
void requireDistinctFiles(const std::vector<NamedPath>& paths);
// Refuses an output path that cannot be written: a directory, or one whose
// directory is missing or takes no new file (not writable; /proc, even for
// root). Cheap, it makes the writer's temporary file and drops it; call it
// before long work.
void requireWritableOutput(const NamedPath& output);
// A name's extension in lower case, with its dot ("R.SVG" -> ".svg").
std::string lowerExtension(const std::string& path);
// Refuses (InputError naming the output) a file name that does not end in
// one of `extensions` (".svg", in any case): the name says what the file
// holds, and SVG written to "r.txt" is mislabelled. The target of a
// symbolic link may have it instead; a device or FIFO (-o /dev/stdout)
// has no name to check. Returns the extension matched, "" for a device or
// FIFO.
std::string requireOutputExtension(const NamedPath& output, const std::vector<std::string>& extensions);
// Where a command's summary line goes: stdout, unless one of its outputs is
// the file stdout writes to (-o /dev/stdout, or -o x.json > x.json), whose
// contents a summary line there would corrupt: then stderr.
std::ostream& summaryStream(const std::vector<std::string>& outputs);

// Warnings about an input that is read all the same: an unknown key (the
// contract ignores it; a misspelt optional field would otherwise become
// its default unseen), a heading that looks like degrees, an obstacle
// outside the workspace. Every reader below that takes an InputWarnings*
// appends its warnings there; given nullptr, it prints each on stderr as
// one line (printInputWarnings). Either way only once the whole input has
// been read: refused input gets its one error line and no warnings.
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
nlohmann::json solutionToJson(const Solution& s);
Solution loadSolution(const std::string& path, const Scenario* scenario, InputWarnings* warnings = nullptr);
void saveSolution(const std::string& path, const Solution& s);

}  // namespace earc
