#!/bin/bash
# label: unsanitized
# tools/embed_migrations.cmake, which compiles the migrations/ files into
# the programs: each file's text reaches the program byte for byte, however
# awkward (semicolons, backslashes, quotes, no final newline), with the
# version of its NNNN prefix; a gap in the versions, a misnamed file, or one
# holding the raw-string delimiter or a carriage return (which the literal
# would lose) stops the build, naming the file. And this build's generated
# entries are those of the files now in migrations/.
set -u
BUILD=$1
SRC=$2
. "$(dirname "$0")/common.bash"
needCompiler
embed() {  # embed OUT DIR: runs the generator on DIR's *.sql
  local files
  files=$(find "$2" -maxdepth 1 -name '*.sql' | sort | paste -sd';')
  cmake "-DOUT=$1" "-DFILES=$files" "-DDIR=$2" -P "$SRC/tools/embed_migrations.cmake"
}

mkdir "$WORK/m"
printf -- '-- one; two\nCREATE TABLE t (a TEXT DEFAULT '"'"'x;y\\\\n"z'"'"');\n' > "$WORK/m/0001_first.sql"
printf 'ALTER TABLE t ADD COLUMN b;\n-- )sql" R"( ${x} @y@ \\t\tno final newline' > "$WORK/m/0002_second_one.sql"
: > "$WORK/m/0003_empty.sql"
embed "$WORK/m.inc" "$WORK/m" || fail "the generator refused good files"
cat > "$WORK/print.cpp" <<CPP
#include <fstream>
#include <string_view>
struct Migration { int version; std::string_view name; std::string_view sql; };
constexpr Migration kAll[] = {
#include "$WORK/m.inc"
};
int main(int, char** argv) {
  for (const Migration& m : kAll) {
    std::ofstream(std::string(argv[1]) + "/" + std::to_string(m.version) + "-" + std::string(m.name),
                  std::ios::binary) << m.sql;
  }
}
CPP
"$CXX" -std=c++20 -o "$WORK/print" "$WORK/print.cpp" 2> "$WORK/err" || fail "the entries do not compile: $(head -5 "$WORK/err")"
mkdir "$WORK/out.d"
"$WORK/print" "$WORK/out.d" || fail "the printer failed"
for f in 1-0001_first.sql 2-0002_second_one.sql 3-0003_empty.sql; do
  [ -f "$WORK/out.d/$f" ] || fail "no entry $f: $(ls "$WORK/out.d")"
  cmp -s "$WORK/out.d/$f" "$WORK/m/${f#*-}" || fail "entry $f differs from its file"
done
[ "$(ls "$WORK/out.d" | wc -l)" -eq 3 ] || fail "not three entries: $(ls "$WORK/out.d")"

# Refused, naming the file.
refused() {  # refused WANT: the generator fails on $WORK/m and says WANT
  embed "$WORK/bad.inc" "$WORK/m" > "$WORK/out" 2>&1 && fail "the generator accepted $1"
  # (CMake wraps its messages: compared with the lines joined.)
  tr -s '\n ' '  ' < "$WORK/out" | grep -qF -- "$1" || fail "the error does not say '$1': $(cat "$WORK/out")"
}
mv "$WORK/m/0002_second_one.sql" "$WORK/m/0004_second_one.sql"
refused "0003_empty.sql: migration 3 where 2 was due"
mv "$WORK/m/0004_second_one.sql" "$WORK/m/0002_second_one.sql"
printf 'x' > "$WORK/m/4_short.sql"
refused "4_short.sql: a migration's name must be NNNN_name.sql"
rm "$WORK/m/4_short.sql"
printf 'SELECT 1;\r\n' > "$WORK/m/0004_crlf.sql"
refused "0004_crlf.sql holds a carriage return"
rm "$WORK/m/0004_crlf.sql"
printf 'SELECT 1; -- )earcsql"\n' > "$WORK/m/0004_clash.sql"
refused "0004_clash.sql contains the raw-string delimiter"
rm -f "$WORK/m"/*.sql
refused "no migrations"

# This build's entries are the ones the files in migrations/ make now.
for set in store:migrations postgresql:migrations/postgresql results:migrations/results; do
  name=${set%%:*} dir=${set#*:}
  [ -f "$BUILD/generated/migrations/$name.inc" ] || fail "no $BUILD/generated/migrations/$name.inc"
  (cd "$SRC" && embed "$WORK/$name.inc" "$dir") || fail "the generator refused $dir"
  cmp -s "$WORK/$name.inc" "$BUILD/generated/migrations/$name.inc" ||
    fail "$BUILD/generated/migrations/$name.inc is not what $dir/*.sql make (a stale build?)"
done
echo "ok: migrations embedded byte for byte; gaps, bad names, carriage returns and delimiter clashes refused"
