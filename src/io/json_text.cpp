// Strict JSON text in and atomic text out.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <random>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "earc/io/json_io.hpp"
#include "earc/util/memory_reserve.hpp"
#include "json_reader.hpp"

namespace earc {
namespace {

using nlohmann::json;

// Builds the document from the parser's SAX events, in one pass, and
// follows them to know the JSON path of the value being read, so that a
// duplicate key (which json::parse would silently drop) or a syntax error
// can be located by path as well as by line and column. (nlohmann's DOM
// parser with a callback scans the whole enclosing array at the end of
// every object in it, quadratic on large arrays; a separate tracking pass
// before json::parse lexed every number twice.)
class CheckedDomBuilder {
 public:
  explicit CheckedDomBuilder(const std::string& file) : file_(file) {}

  bool null() { return value(nullptr); }
  bool boolean(bool v) { return value(v); }
  bool number_integer(json::number_integer_t v) { return value(v); }
  bool number_unsigned(json::number_unsigned_t v) { return value(v); }
  bool number_float(json::number_float_t v, const json::string_t&) { return value(v); }
  bool string(json::string_t& v) { return value(std::move(v)); }
  bool binary(json::binary_t& v) { return value(json::binary(std::move(v))); }
  bool start_object(std::size_t) { return open(json::object(), false); }
  bool start_array(std::size_t) { return open(json::array(), true); }
  bool key(json::string_t& k) {
    Frame& top = stack_.back();
    top.key = k;
    if (top.node->contains(k)) throw InputError(file_, path(), "duplicate key \"" + top.key + "\"");
    top.has_key = true;
    return true;
  }
  bool end_object() { return close(); }
  bool end_array() { return close(); }
  bool parse_error(std::size_t position, const std::string&, const json::exception& e) {
    error_ = e.what();
    error_position_ = position;
    return false;
  }

  // Path of the value the parser is in (or about to read).
  std::string path() const {
    std::string p = "$";
    for (const Frame& f : stack_) {
      if (f.array) p = io::element(p, f.index);
      else if (f.has_key) p = io::member(p, f.key.c_str());
    }
    return p;
  }
  // The parser's message, when it stopped at an error, and how many bytes
  // it had read then (the last one is where it stopped).
  const std::string& error() const { return error_; }
  std::size_t errorPosition() const { return error_position_; }
  // Which bracket closes what the parser is in: ']', '}', or 0 at the top.
  char closer() const { return stack_.empty() ? 0 : stack_.back().array ? ']' : '}'; }
  json& document() { return root_; }

 private:
  struct Frame {
    json* node = nullptr;
    bool array = false;
    std::size_t index = 0;  // arrays: the element being read
    std::string key;        // objects: the member being read
    bool has_key = false;
  };
  // Where the next value goes: the root, the end of an array, an object's
  // member under the last key.
  json* place(json&& v) {
    if (stack_.empty()) {
      root_ = std::move(v);
      return &root_;
    }
    Frame& top = stack_.back();
    if (top.array) {
      top.node->push_back(std::move(v));
      return &top.node->back();
    }
    json& slot = (*top.node)[top.key];
    slot = std::move(v);
    return &slot;
  }
  bool value(json&& v) {
    place(std::move(v));
    return advance();
  }
  bool open(json&& container, bool array) {
    json* node = place(std::move(container));
    stack_.push_back(Frame{node, array, 0, {}, false});
    return true;
  }
  bool close() {
    stack_.pop_back();
    return advance();
  }
  bool advance() {
    if (!stack_.empty() && stack_.back().array) ++stack_.back().index;
    return true;
  }
  const std::string& file_;
  json root_;
  std::vector<Frame> stack_;
  std::string error_;
  std::size_t error_position_ = 0;
};

// "[json.exception.parse_error.101] parse error at line 3, column 7: syntax
// error while parsing value - invalid literal; last read: 'NaN'" ->
// where "line 3, column 7", reason "syntax error ...".
void splitParseError(const std::string& what, std::string& where, std::string& reason) {
  static const std::regex located(R"(^\[json\.exception\.[a-z_]+\.\d+\] (?:parse error )?at (line \d+, column \d+): (.*)$)");
  static const std::regex plain(R"(^\[json\.exception\.[a-z_]+\.\d+\] (.*)$)");
  std::smatch m;
  if (std::regex_match(what, m, located)) {
    where = m[1];
    reason = m[2];
  } else if (std::regex_match(what, m, plain)) {
    reason = m[1];
  } else {
    reason = what;
  }
}

bool isWordChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

std::string lowerCase(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

// What the user most likely wrote instead of JSON, judged by the text
// where the parser stopped (`position` bytes read, the last one the byte
// it could not take; `closer` the bracket that would close what it is in),
// as " (hint)", or "" when nothing looks familiar.
std::string syntaxHint(const std::string& text, std::size_t position, char closer, const std::string& reason) {
  if (position == 0 || position > text.size()) return "";
  const std::size_t at = position - 1;
  const char c = text[at];
  if (c == '/' && at + 1 < text.size() && (text[at + 1] == '/' || text[at + 1] == '*'))
    return " (JSON has no comments)";
  if (c == '\'') return " (JSON strings use double quotes)";
  // A comma, then the bracket that closes the array or object (another
  // bracket is a different mistake: "{"a": 1,]" leaves an object open).
  if (c == closer && reason.find("unexpected '") != std::string::npos) {
    std::size_t before = at;
    while (before > 0 && std::isspace(static_cast<unsigned char>(text[before - 1]))) --before;
    if (before > 0 && text[before - 1] == ',')
      return std::string(" (a trailing comma: JSON allows none before '") + c + "')";
    return "";
  }
  if (!isWordChar(c)) return "";
  // The whole word the offending byte is in: "NaN", "Infinity", "True".
  std::size_t begin = at, end = at + 1;
  while (begin > 0 && isWordChar(text[begin - 1])) --begin;
  while (end < text.size() && isWordChar(text[end])) ++end;
  const std::string word = lowerCase(text.substr(begin, std::min<std::size_t>(end - begin, 16)));
  if (reason.find("object key") != std::string::npos) return " (keys are strings in double quotes)";
  if (word == "nan" || word.starts_with("inf")) return " (JSON has no NaN or Infinity; numbers must be finite)";
  if (word == "true" || word == "false" || word == "null" || word == "none")
    return " (JSON's literals are true, false and null, in lower case)";
  return "";
}

}  // namespace

json parseJsonText(const std::string& text, const std::string& file) {
  // nlohmann would skip it; JSON text must not start with one (RFC 8259)
  // and the independent checker refuses it, so refuse it too.
  if (text.starts_with("\xEF\xBB\xBF"))
    throw InputError(file, "line 1, column 1", "malformed JSON: starts with a UTF-8 byte order mark");
  CheckedDomBuilder tracker(file);
  if (!json::sax_parse(text, &tracker)) {
    std::string where, reason;
    splitParseError(tracker.error(), where, reason);
    // A number too large for a double ("1e999") overflows to infinity: the
    // parser refuses it without a position, the tracker knows the path.
    const std::string path = tracker.path();
    where = where.empty() ? path : where + " (" + path + ")";
    reason += syntaxHint(text, tracker.errorPosition(), tracker.closer(), reason);
    throw InputError(file, where, "malformed JSON: " + reason);
  }
  return std::move(tracker.document());
}

std::string readTextFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", std::string("cannot open file: ") + std::strerror(errno));
  // A directory opens, then reads as nothing, which would be reported as
  // an empty or malformed file.
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError(path, "", "is a directory, not a file");
  // Read in chunks up to a bound: /dev/zero, or a FIFO that never ends,
  // would otherwise grow memory until the process dies.
  std::string text;
  std::vector<char> chunk(std::size_t{1} << 20);
  while (in.read(chunk.data(), static_cast<std::streamsize>(chunk.size())) || in.gcount() > 0) {
    text.append(chunk.data(), static_cast<std::size_t>(in.gcount()));
    if (text.size() > kMaxTextFileBytes)
      throw InputError(path, "", "more than " + std::to_string(kMaxTextFileBytes >> 20) +
                                     " MiB: too large to read (is it the file you meant?)");
  }
  if (in.bad()) throw InputError(path, "", std::string("cannot read file: ") + std::strerror(errno));
  return text;
}

json readJsonFile(const std::string& path) {
  std::size_t bytes = 0;
  try {
    const std::string text = readTextFile(path);
    bytes = text.size();
    return parseJsonText(text, path);
  } catch (const std::bad_alloc&) {
    // A document takes several times its text in memory; say which file
    // did not fit rather than only "std::bad_alloc".
    const std::string size =
        bytes ? " (" + formatNumber("%.1f", static_cast<double>(bytes) / (1 << 20)) + " MB of JSON)" : "";
    throw OutOfMemory(path + ": " + outOfMemoryText("while reading it" + size));
  }
}

namespace {

namespace fs = std::filesystem;

// The directory a file of this path lives in.
std::string directoryOf(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? "." : parent.string();
}

// A symbolic link's final target (the link itself stays), else the path.
std::string throughLinks(const std::string& path) {
  std::error_code ec;
  if (!fs::is_symlink(fs::symlink_status(path, ec))) return path;
  if (fs::exists(path, ec)) {  // /dev/stdout -> a pipe: kept as given when unresolvable
    const fs::path target = fs::weakly_canonical(path, ec);
    return ec ? path : target.string();
  }
  fs::path p = path;
  // A link whose target does not exist yet (weakly_canonical leaves it
  // unresolved) is followed by hand, as the shell's `> link` would: the
  // target is created and the link kept.
  for (int hops = 0; hops < 40 && fs::is_symlink(fs::symlink_status(p, ec)); ++hops) {
    const fs::path to = fs::read_symlink(p, ec);
    if (ec) return path;
    p = to.is_absolute() ? to : p.parent_path() / to;
  }
  if (p == fs::path(path)) return path;
  const fs::path target = fs::weakly_canonical(p, ec);
  return ec ? p.lexically_normal().string() : target.string();
}

// Where an output's bytes go: the path to write (a link's target), and
// whether that is a device or FIFO, to be written directly. Throws
// InputError naming the output for a directory or a missing directory.
struct OutputTarget {
  std::string path;
  bool special = false;
};

OutputTarget outputTarget(const NamedPath& output) {
  OutputTarget target{throughLinks(output.path)};
  std::error_code ec;
  const fs::file_status st = fs::status(target.path, ec);
  if (fs::is_directory(st)) throw InputError(output.path, output.name, "is a directory, not a file");
  target.special = fs::exists(st) && !fs::is_regular_file(st);
  if (!target.special) {
    const std::string dir = directoryOf(target.path);
    if (!fs::is_directory(dir, ec)) throw InputError(output.path, output.name, "cannot write: no directory " + dir);
  }
  return target;
}

// A new file in dir for output not yet named: anonymous (O_TMPFILE, so a
// process killed while writing leaves nothing behind) where the file system
// has it, else created as `tmp`. -1, errno set, when neither can be made.
int openUnnamed(const std::string& dir, const std::string& tmp, bool& anonymous) {
  int fd = ::open(dir.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0644);
  anonymous = fd >= 0;
  if (!anonymous) fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  return fd;
}

std::string temporaryName(const std::string& path) {
  std::random_device rd;
  return path + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(rd());
}

// Why openUnnamed failed for path in dir, an existing directory. There
// ENOENT means that the file system makes no new files (/proc), not that
// anything is missing: "/proc/version: cannot write in /proc: No such file
// or directory" was false twice.
std::string cannotMakeFile(const std::string& path, const std::string& dir, int err) {
  std::error_code ec;
  const std::string why = err == ENOENT ? "its file system makes no new files" : std::strerror(err);
  return (fs::exists(path, ec) ? "cannot replace it: " : "") + ("cannot write in " + dir + ": " + why);
}

}  // namespace

namespace {
// An output that could not be written. No room (a full disk, a used-up
// quota) is said plainly and is exit status 2, as for a database that
// cannot take a build, an import or a curate; other errors stay runtime
// errors (exit 1).
[[noreturn]] void throwWriteError(const std::string& path, const std::string& doing, int err) {
  if (err == ENOSPC) throw InputError(path, "", "cannot write: the disk is full");
  if (err == EDQUOT) throw InputError(path, "", "cannot write: the disk quota is used up");
  throw std::runtime_error(path + ": " + doing + ": " + std::strerror(err));
}
}  // namespace

void writeAll(int fd, std::string_view bytes, const std::string& path) {
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throwWriteError(path, "cannot write", n < 0 ? errno : EIO);
    bytes.remove_prefix(static_cast<std::size_t>(n));
  }
}

namespace {
// The descriptor a name stands for (/dev/stdout, /dev/stderr, /dev/fd/N,
// /proc/self/fd/N), or -1.
int descriptorNamed(const std::string& name) {
  if (name == "/dev/stdout") return STDOUT_FILENO;
  if (name == "/dev/stderr") return STDERR_FILENO;
  for (const std::string prefix : {"/dev/fd/", "/proc/self/fd/"})
    if (name.starts_with(prefix) && name.size() > prefix.size() && name.size() <= prefix.size() + 6 &&
        isDigits(name.substr(prefix.size())))
      return std::stoi(name.substr(prefix.size()));
  return -1;
}
}  // namespace

AtomicFile::AtomicFile(const std::string& given) : given_(given) {
  // An open descriptor is written where it already points, at its own
  // offset: through the link to a regular file the output would replace
  // it (`earc-bench export --csv /dev/stdout >> log` lost the log).
  if (const int named = descriptorNamed(given); named >= 0) {
    fd_ = ::dup(named);
    if (fd_ >= 0) {
      special_ = true;
      return;
    }
  }
  const OutputTarget target = outputTarget({"", given});
  path_ = target.path;
  special_ = target.special;
  if (special_) {
    // A device or FIFO: renaming a file over it would destroy it.
    fd_ = ::open(path_.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd_ < 0) throw InputError(given, "", std::string("cannot open for writing: ") + std::strerror(errno));
    return;
  }
  const std::string dir = directoryOf(path_);
  // Same directory, so the rename stays on one file system and is atomic.
  // Named only once complete and synced.
  tmp_ = temporaryName(path_);
  fd_ = openUnnamed(dir, tmp_, anonymous_);
  if (fd_ < 0) throw InputError(given, "", cannotMakeFile(path_, dir, errno));
  named_ = !anonymous_;
}

AtomicFile::~AtomicFile() {
  if (fd_ >= 0) ::close(fd_);
  if (named_ && !committed_) ::unlink(tmp_.c_str());
}

void AtomicFile::write(std::string_view text) { writeAll(fd_, text, given_); }

void AtomicFile::commit() {
  const int fd = std::exchange(fd_, -1);
  if (special_) {
    if (::close(fd) != 0) throwWriteError(given_, "cannot flush", errno);
    committed_ = true;
    return;
  }
  // Where the file system allocates late (NFS, delayed allocation), a
  // full disk shows only here.
  int err = ::fsync(fd) == 0 ? 0 : errno;
  std::string doing = "cannot flush";
  if (err == 0 && anonymous_) {
    named_ = ::linkat(AT_FDCWD, ("/proc/self/fd/" + std::to_string(fd)).c_str(), AT_FDCWD, tmp_.c_str(),
                      AT_SYMLINK_FOLLOW) == 0;
    if (!named_) {
      err = errno;
      doing = "cannot flush: cannot name the written file";
    }
  }
  if (::close(fd) != 0 && err == 0) err = errno;
  if (err != 0) throwWriteError(given_, doing, err);
  if (::rename(tmp_.c_str(), path_.c_str()) != 0)
    throw InputError(given_, "", std::string("cannot replace it: ") + std::strerror(errno));
  committed_ = true;
  syncDirectoryOf(path_);  // make the rename itself durable
}

// Write atomically (temporary file, fsync, rename): a crash leaves the old
// file or the new one, never half of one. A symbolic link is written
// through (its target replaced, the link kept); a device or FIFO (such as
// /dev/stdout) is written to directly, never replaced by a file. Throws
// InputError naming the file when it cannot be written.
void writeTextFileAtomic(const std::string& path, const std::string& text) {
  AtomicFile file(path);
  file.write(text);
  file.commit();
}

void syncDirectoryOf(const std::string& path) {
  const int dfd = ::open(directoryOf(path).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    ::fsync(dfd);
    ::close(dfd);
  }
}

bool sameFile(const std::string& a, const std::string& b) {
  auto normal = [](const std::string& p) {
    std::error_code ec;
    // Absolute first: of a relative path none of whose parts exists
    // ("r.db"), weakly_canonical gives it back relative, and "./r.db"
    // absolute, and the two would differ.
    fs::path absolute = fs::absolute(p, ec).lexically_normal();
    if (ec) absolute = fs::path(p).lexically_normal();
    fs::path c = fs::weakly_canonical(absolute, ec);
    return ec ? absolute : c;
  };
  std::error_code ea, eb;
  const bool xa = fs::exists(a, ea), xb = fs::exists(b, eb);
  if (xa && xb) {
    const bool same = fs::equivalent(a, b, ea);
    if (!ea) return same;
  }
  if (xa != xb) return false;
  return normal(a) == normal(b);
}

// Refuses (InputError naming the later path) when two of the paths are
// one file, so that an output never overwrites an input or another
// output. Empty paths are ignored. Existing files are compared by
// identity (links included), others by their absolute normal form.
void requireDistinctFiles(const std::vector<NamedPath>& paths) {
  // A database's companion files hold committed rows (-wal) and its lock
  // state (-shm): an output written over one loses or corrupts them.
  // SQLite keeps them beside the real file, through any link.
  auto companion = [](const NamedPath& db, const NamedPath& other) -> std::string {
    if (!db.database) return "";
    // (A dangling link too, which weakly_canonical leaves: the database
    // would be created at its target.)
    std::error_code ec;
    const fs::path real = fs::weakly_canonical(db.path, ec);
    const std::string target = throughLinks(db.path);
    for (const char* suffix : kDatabaseCompanions)
      if (sameFile(db.path + suffix, other.path) || (!ec && sameFile(real.string() + suffix, other.path)) ||
          sameFile(target + suffix, other.path))
        return suffix;
    return "";
  };
  for (std::size_t j = 1; j < paths.size(); ++j)
    for (std::size_t i = 0; i < j; ++i) {
      const NamedPath &a = paths[i], &b = paths[j];
      if (a.path.empty() || b.path.empty()) continue;
      if (sameFile(a.path, b.path))
        throw InputError(b.path, b.name,
                         "is the same file as " + a.name + (a.path == b.path ? "" : " (" + a.path + ")") +
                             "; give each its own file");
      for (const auto& [db, other] : {std::pair{&a, &b}, std::pair{&b, &a}})
        if (const std::string suffix = companion(*db, *other); !suffix.empty())
          throw InputError(other->path, other->name,
                           "is the " + suffix + " file of " + db->name + " (" + db->path +
                               "), part of that database; give each its own file");
    }
}

// Refuses an output path that cannot be written: a directory, or one whose
// directory is missing or takes no new file (not writable; /proc, even for
// root). Cheap, it makes the writer's temporary file and drops it; call it
// before long work.
void requireWritableOutput(const NamedPath& output) {
  if (output.path.empty()) return;
  const OutputTarget target = outputTarget(output);
  if (target.special) return;  // a device or FIFO, written to directly
  const std::string dir = directoryOf(target.path);
  // Made and dropped as the writer will make it: access() lets root through
  // where no file can be made (/proc), and the output then failed after
  // the work, without naming the option.
  bool anonymous = false;
  const std::string tmp = temporaryName(target.path);
  const int fd = openUnnamed(dir, tmp, anonymous);
  if (fd < 0) throw InputError(output.path, output.name, cannotMakeFile(target.path, dir, errno));
  ::close(fd);
  if (!anonymous) ::unlink(tmp.c_str());
}

std::ostream& summaryStream(const std::vector<std::string>& outputs) {
  struct stat out_st {};
  if (::fstat(STDOUT_FILENO, &out_st) != 0) return std::cout;
  for (const std::string& path : outputs) {
    struct stat st {};
    if (!path.empty() && ::stat(path.c_str(), &st) == 0 && st.st_dev == out_st.st_dev && st.st_ino == out_st.st_ino)
      return std::cerr;
  }
  return std::cout;
}

std::string lowerExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

// Refuses (InputError naming the output) a file name that does not end in
// one of `extensions` (".svg", in any case): the name says what the file
// holds, and SVG written to "r.txt" is mislabelled. The target of a
// symbolic link may have it instead; a device or FIFO (-o /dev/stdout)
// has no name to check. Returns the extension matched, "" for a device or
// FIFO.
std::string requireOutputExtension(const NamedPath& output, const std::vector<std::string>& extensions) {
  const OutputTarget target = outputTarget(output);
  if (target.special) return "";
  // A link's target has a name too: -o /dev/stdout > x.svg writes x.svg.
  std::string names;
  for (const std::string& e : extensions) {
    if (lowerExtension(output.path) == e || lowerExtension(target.path) == e) return e;
    names += (names.empty() ? "" : " or ") + e;
  }
  throw InputError(output.path, output.name, "must end in " + names + ": the extension says the file's format");
}

std::string dumpCompact(const json& v) { return v.dump(-1, ' ', false, json::error_handler_t::replace); }

void appendJsonDouble(std::string& out, double v) {
  if (!std::isfinite(v)) {
    out += "null";
    return;
  }
  // std::to_chars gives the shortest digits that read back exactly, as
  // d.ddde+XX; they are then placed as nlohmann::json places them: plain
  // from 1e-5 up to 1e15 (a whole number with ".0"), otherwise with an
  // exponent of at least two digits. Writing a plan of millions of numbers
  // this way skips building them into a JSON document first.
  char sci[40];
  const auto res = std::to_chars(sci, sci + sizeof sci, v, std::chars_format::scientific);
  const char* p = sci;
  if (*p == '-') {
    out += '-';
    ++p;
  }
  const char* e = std::find(p, static_cast<const char*>(res.ptr), 'e');
  char digits[24];
  int k = 0;
  for (const char* c = p; c < e; ++c)
    if (*c != '.') digits[k++] = *c;
  int exp10 = 0;
  std::from_chars(e + (e[1] == '+' ? 2 : 1), res.ptr, exp10);
  const int n = exp10 + 1;  // the decimal point's place after the first digit
  const std::string_view d(digits, static_cast<std::size_t>(k));
  if (k <= n && n <= 15) {
    out.append(d).append(static_cast<std::size_t>(n - k), '0').append(".0");
  } else if (0 < n && n <= 15) {
    out.append(d.substr(0, static_cast<std::size_t>(n))).append(".").append(d.substr(static_cast<std::size_t>(n)));
  } else if (-4 < n && n <= 0) {
    out.append("0.").append(static_cast<std::size_t>(-n), '0').append(d);
  } else {
    out += d[0];
    if (k > 1) out.append(".").append(d.substr(1));
    const int x = n - 1;
    out += x < 0 ? "e-" : "e+";
    const int a = x < 0 ? -x : x;
    if (a < 10) out += '0';
    out += std::to_string(a);
  }
}

}  // namespace earc
